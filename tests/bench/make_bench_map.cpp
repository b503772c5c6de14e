// Writes a periodic W x H 16-bit grey PNG (a sum of waves with whole periods across the tile, plus
// fine detail), the input bench_pack.sh times heightpack and oiiotool on.
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: %s WIDTH HEIGHT OUT.png\n", argv[0]);
        return 2;
    }
    const int w = std::atoi(argv[1]), h = std::atoi(argv[2]);
    if (w <= 0 || h <= 0) return 2;
    constexpr double kTwoPi = 6.283185307179586;
    struct Wave { int kx, ky; double amplitude, phase; };
    std::mt19937 rng(1234);
    std::uniform_int_distribution<int> k(-64, 64);
    std::uniform_real_distribution<double> phase(0, kTwoPi);
    std::vector<Wave> waves;
    for (int i = 0; i < 48; ++i) {
        const int kx = k(rng), ky = k(rng);
        const double length = std::sqrt(double(kx * kx + ky * ky)) + 1.0;
        waves.push_back({kx, ky, 1.0 / length, phase(rng)});
    }
    double total = 0;
    for (const Wave& wv : waves) total += wv.amplitude;
    std::vector<unsigned short> pixels(size_t(w) * h);
    std::vector<double> cosx(w), siny(h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            double v = 0;
            for (const Wave& wv : waves) v += wv.amplitude * std::cos(kTwoPi * (wv.kx * double(x) / w + wv.ky * double(y) / h) + wv.phase);
            pixels[size_t(y) * w + x] = static_cast<unsigned short>(std::lround((0.5 + 0.5 * v / total) * 65535));
        }
    }
    auto out = OIIO::ImageOutput::create(argv[3]);
    OIIO::ImageSpec spec(w, h, 1, OIIO::TypeDesc::UINT16);
    if (!out || !out->open(argv[3], spec) || !out->write_image(OIIO::TypeDesc::UINT16, pixels.data()) || !out->close()) {
        std::fprintf(stderr, "cannot write %s\n", argv[3]);
        return 1;
    }
    return 0;
}
