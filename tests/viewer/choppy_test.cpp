// Tessendorf's choppy waves in heightpack-view (issue 15, point 3): a swell with Dx, Dy, packed with
// --shift, seen from straight above as heights in grey. Moving each grid point by choppiness * D
// squeezes the crests and stretches the troughs by an amount known in closed form; the rendered grid must
// show it, in the one-pass and the two-pass paths alike.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "support/test_support.hpp"
#include "viewer_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

constexpr double kAmplitude = 0.8;  // metres
constexpr double kWavelength = 16.0;  // metres: one wave per tile

// h = A cos(k x) and synth's D = i k/|k| h (toward the crests), which for one cosine is Dx = -A sin(k x), Dy = 0.
void writeSwell(const std::string& path) {
    const int w = 64, h = 8;
    OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"Y", "Dx", "Dy"};
    std::vector<float> pixels;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double phase = 2 * M_PI * (x + 0.5) / w;
            pixels.insert(pixels.end(), {float(kAmplitude * std::cos(phase)), float(-kAmplitude * std::sin(phase)), 0.0f});
        }
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
}

struct Grey {
    int width = 0, height = 0;
    std::vector<unsigned char> g;
    int at(int x, int y) const { return g[size_t(y) * width + x]; }
};

Grey greyShot(const ScratchDir& dir, const std::string& name, std::vector<std::string> args) {
    args.insert(args.end(), {"--screenshot", dir.file(name)});
    const ViewRun run = view(args);
    EXPECT_EQ(run.code, 0) << run.err;
    Grey p;
    auto in = OIIO::ImageInput::open(dir.file(name));
    EXPECT_TRUE(in);
    if (!in) return p;
    p.width = in->spec().width;
    p.height = in->spec().height;
    p.g.resize(size_t(p.width) * p.height);
    EXPECT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT8, p.g.data()));
    return p;
}

// The fractions of one wavelength that lie above +A/2 (crest band) and below -A/2 (trough band), measured
// along the picture's middle row or column (whichever crosses the waves), over whole wavelengths: from the
// centre of the first crest band wholly inside the picture to that of the last.
struct Bands {
    double crest = 0, trough = 0;
    int periods = 0;
};

Bands measure(const Grey& p) {
    // The height view's grey: 0.1 + 0.8 (h + 2) / 4 of 255, for heights in -2..2 m.
    const auto grey = [](double h) { return 255.0 * (0.1 + 0.8 * (h + 2.0) / 4.0); };
    const double crestGrey = grey(kAmplitude / 2), troughGrey = grey(-kAmplitude / 2);
    Bands best;
    for (int vertical = 0; vertical < 2; ++vertical) {
        std::vector<int> line;
        const int n = vertical ? p.height : p.width;
        for (int i = 0; i < n; ++i) line.push_back(vertical ? p.at(p.width / 2, i) : p.at(i, p.height / 2));
        std::vector<double> centres;  // of crest runs that do not touch the picture's edge
        for (int i = 0; i < n;) {
            if (line[i] <= crestGrey) {
                ++i;
                continue;
            }
            int j = i;
            while (j < n && line[j] > crestGrey) ++j;
            if (i > 0 && j < n) centres.push_back((i + j - 1) / 2.0);
            i = j;
        }
        if (centres.size() < 2 || int(centres.size()) - 1 <= best.periods) continue;
        const int a = int(std::lround(centres.front())), b = int(std::lround(centres.back()));
        int crest = 0, trough = 0;
        for (int i = a; i < b; ++i) crest += line[i] > crestGrey, trough += line[i] < troughGrey;
        best.periods = int(centres.size()) - 1;
        best.crest = double(crest) / (b - a);
        best.trough = double(trough) / (b - a);
    }
    return best;
}

}  // namespace

TEST(ViewerChoppy, CrestsSharpenAndTroughsWidenByTheClosedFormAmount) {
    ScratchDir dir;
    writeSwell(dir.file("swell.exr"));
    const ProcessResult pack = runProcess({HEIGHTPACK_EXE, "pack", dir.file("swell.exr"), "--shift", "-q", "-o",
                                           dir.file("swell_packed.exr")});
    ASSERT_EQ(pack.code, 0) << pack.err;
    const std::vector<std::string> common = {dir.file("swell_packed.exr"), "--view", "height", "--size", "320x320",
                                             "--time", "0", "--camera", "0,0,60,0,-89.9", "--tile-size",
                                             std::to_string(kWavelength), "--amplitude", "1", "--grid", "512",
                                             "--segments", "512", "--lookup", "bilinear"};
    for (const double c : {0.0, 1.5}) {
        auto args = common;
        args.insert(args.end(), {"--choppiness", std::to_string(c)});
        std::vector<Bands> bands = {measure(greyShot(dir, "one.png", args))};
        if (c > 0) {  // the two-pass path, where the combine pass stores each vertex's shift
            args.push_back("--two-pass");
            bands.push_back(measure(greyShot(dir, "two.png", args)));
        }
        // A point at x moves to x + c D = x - c A sin(k x): the band |k x| < pi/3 where h > A/2 shrinks by c A sqrt(3),
        // the trough band grows by as much; as fractions of the wavelength L: 1/3 -+ c A sqrt(3) / L.
        const double shift = c * kAmplitude * std::sqrt(3.0) / kWavelength;
        for (const Bands& b : bands) {
            std::printf("choppiness %.2f: crest %.4f (expected %.4f), trough %.4f (expected %.4f) over %d wavelengths\n",
                        c, b.crest, 1.0 / 3 - shift, b.trough, 1.0 / 3 + shift, b.periods);
            ASSERT_GE(b.periods, 2) << "choppiness " << c;
            EXPECT_NEAR(b.crest, 1.0 / 3 - shift, 0.025) << "choppiness " << c;
            EXPECT_NEAR(b.trough, 1.0 / 3 + shift, 0.025) << "choppiness " << c;
        }
        if (bands.size() == 2) {
            EXPECT_NEAR(bands[0].crest, bands[1].crest, 0.01) << "one pass against two";
        }
    }
}
