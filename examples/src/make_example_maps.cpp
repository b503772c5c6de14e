// Makes the example height maps in examples/maps/. Each tileable map is a sum of plane waves with a
// whole number of periods across the tile (so it is periodic by construction) drawn from a directional
// spectrum; the non-tileable one uses fractional wave numbers and painted-like blobs, so its edges do
// not meet. Run: heightpack_make_example_maps examples/maps
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace {

constexpr double kTwoPi = 6.283185307179586;

struct Wave {
    double kx, ky;  // periods across the tile in x and y
    double amplitude, phase;
};

// Waves whose wave numbers lie between kMin and kMax periods per tile, travelling within `spread`
// radians of `direction`, with amplitude falling as k^-slope; `whole` rounds the wave vector to integers.
std::vector<Wave> spectrum(unsigned seed, int count, double kMin, double kMax, double direction, double spread,
                           double slope, bool whole) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> angle(direction, spread);
    std::vector<Wave> waves;
    while (int(waves.size()) < count) {
        const double k = kMin * std::pow(kMax / kMin, unit(rng));
        const double a = angle(rng);
        double kx = k * std::cos(a), ky = k * std::sin(a);
        if (whole) {
            kx = std::round(kx);
            ky = std::round(ky);
        }
        const double length = std::hypot(kx, ky);
        if (length < 0.5) continue;
        waves.push_back({kx, ky, std::pow(length, -slope) * (0.5 + unit(rng)), kTwoPi * unit(rng)});
    }
    return waves;
}

std::vector<double> synthesise(int w, int h, const std::vector<Wave>& waves) {
    std::vector<double> field(size_t(w) * h, 0.0);
    for (const Wave& wave : waves)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                field[size_t(y) * w + x] +=
                    wave.amplitude * std::cos(kTwoPi * (wave.kx * x / w + wave.ky * y / h) + wave.phase);
    return field;
}

// Maps the field's range onto [margin, 1 - margin] and writes it as 8- or 16-bit grey.
bool write(const std::string& path, int w, int h, std::vector<double> field, int bits) {
    const auto [lo, hi] = std::minmax_element(field.begin(), field.end());
    const double min = *lo, range = *hi - *lo, margin = 0.04;
    const double maxCode = bits == 16 ? 65535.0 : 255.0;
    std::vector<float> pixels(field.size());
    for (size_t i = 0; i < field.size(); ++i)
        pixels[i] = float(std::round((margin + (1 - 2 * margin) * (field[i] - min) / range) * maxCode) / maxCode);
    auto out = OIIO::ImageOutput::create(path);
    OIIO::ImageSpec spec(w, h, 1, bits == 16 ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8);
    const bool ok = out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) &&
                    out->close();
    std::printf("%s %s: %dx%d, %d-bit\n", ok ? "wrote" : "FAILED", path.c_str(), w, h, bits);
    return ok;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string dir = argc > 1 ? argv[1] : "examples/maps";
    bool ok = true;

    // Swell: long, smooth crests from one direction (30 degrees), 3-12 periods per tile.
    ok &= write(dir + "/swell.png", 512, 512, synthesise(512, 512, spectrum(1, 80, 3, 12, 0.52, 0.12, 1.3, true)), 16);

    // Choppy wind sea: 6-32 periods per tile, broad directions, crests sharpened by a pointwise
    // trochoid-like mapping (a function of the height alone keeps the map periodic).
    {
        auto field = synthesise(256, 256, spectrum(2, 120, 6, 32, 0.3, 0.7, 1.2, true));
        const auto [lo, hi] = std::minmax_element(field.begin(), field.end());
        const double min = *lo, range = *hi - *lo;
        for (double& v : field) v = std::pow((v - min) / range, 1.8);
        ok &= write(dir + "/choppy.png", 256, 256, field, 16);
    }

    // Fine ripples: capillary scale, 24-64 periods per tile, almost isotropic.
    ok &= write(dir + "/ripple.png", 256, 256, synthesise(256, 256, spectrum(3, 160, 24, 64, 0.0, 2.0, 0.8, true)), 8);

    // A painting that does not tile: fractional wave numbers, a left-to-right gradient, and soft blobs
    // cut by the edges, as a hand-painted map usually is.
    {
        const int w = 512, h = 512;
        auto field = synthesise(w, h, spectrum(4, 60, 1.3, 9.7, 1.0, 0.6, 1.3, false));
        std::mt19937 rng(5);
        std::uniform_real_distribution<double> pos(0.0, 1.0);
        for (int b = 0; b < 14; ++b) {
            const double cx = pos(rng) * w, cy = pos(rng) * h, r = 20 + 60 * pos(rng), a = (pos(rng) - 0.3) * 1.5;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const double d2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / (r * r);
                    field[size_t(y) * w + x] += a * std::exp(-d2);
                }
        }
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) field[size_t(y) * w + x] += 1.2 * x / w;
        ok &= write(dir + "/painted_not_tileable.png", w, h, field, 8);
    }
    return ok ? 0 : 1;
}
