// The viewer's use of synth's baked foam coverage (issue 15, point 4): a flat sea whose coverage is 1 on the
// left half of its tile and 0 on the right, seen from straight above. Where the coverage is 1 the water must
// be foam-white; where it is 0, and everywhere with the baked foam turned off, it is the bare water (the
// flat sea stays far below the height threshold's foam).
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/test_support.hpp"
#include "viewer_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

constexpr int kTexels = 64;          // the tile, one texel a metre
constexpr double kTile = 64.0;       // metres
constexpr double kAltitude = 40.0;   // metres above the water, looking down
constexpr int kPixels = 128;         // square screenshot
constexpr double kFovY = 60.0;       // the viewer's camera

// Channels Y (flat) and Foam: 1 where x < half the tile.
void writeSea(const std::string& path) {
    OIIO::ImageSpec spec(kTexels, kTexels, 2, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"Y", "Foam"};
    std::vector<float> pixels;
    for (int y = 0; y < kTexels; ++y)
        for (int x = 0; x < kTexels; ++x) pixels.insert(pixels.end(), {0.0f, x < kTexels / 2 ? 1.0f : 0.0f});
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
}

// The screen column that sees world x: the camera at x = tile / 2 looks straight down with +x to the right
// (yaw 90), so the picture spans tan(fov / 2) * altitude metres either side of its centre.
double columnOf(double worldX) {
    const double halfWidth = std::tan(kFovY / 2 * M_PI / 180) * kAltitude;
    return kPixels / 2.0 + (worldX - kTile / 2) / halfWidth * (kPixels / 2.0);
}

// The viewer's picture, drawn headless (EGL): no X server to start, so the test stays fast.
Picture foamShot(const ScratchDir& dir, const std::string& name, std::vector<std::string> args) {
    args.insert(args.end(), {"--screenshot", dir.file(name)});
    const ViewRun run = viewWithoutDisplay(args);
    EXPECT_EQ(run.code, 0) << run.err;
    return readPicture(dir.file(name));
}

// Mean brightness (0-255, the mean of r, g, b) of the columns that see world x in [x0, x1], over the middle
// half of the rows.
double brightness(const Picture& p, double x0, double x1) {
    const int c0 = int(std::ceil(columnOf(x0))), c1 = int(std::floor(columnOf(x1)));
    EXPECT_LT(c0, c1);
    double sum = 0;
    int n = 0;
    for (int y = p.height / 4; y < 3 * p.height / 4; ++y)
        for (int x = c0; x <= c1; ++x, ++n) sum += (p.at(x, y, 0) + p.at(x, y, 1) + p.at(x, y, 2)) / 3.0;
    return sum / std::max(n, 1);
}

}  // namespace

TEST(ViewerFoamCoverage, BakedFoamWhitensWhereTheCoverageIsOne) {
    ScratchDir dir;
    writeSea(dir.file("sea.exr"));
    const ProcessResult pack =
        runProcess({HEIGHTPACK_EXE, "pack", dir.file("sea.exr"), "--foam", "-q", "-o", dir.file("packed.exr")});
    ASSERT_EQ(pack.code, 0) << pack.err;
    const std::string size = std::to_string(kPixels) + "x" + std::to_string(kPixels);
    const std::string camera = std::to_string(kTile / 2) + "," + std::to_string(kTile / 2) + "," +
                               std::to_string(kAltitude) + ",90,-89";
    // Six metres clear of the coverage's edge at x = 32 m, where the filtering blends the halves.
    const double foamX0 = 14, foamX1 = 26, bareX0 = 38, bareX1 = 50;
    const std::vector<std::string> view = {"--size", size, "--time", "0", "--camera", camera, "--tile-size",
                                           std::to_string(kTile), "--grid", "64", "--segments", "64"};  // flat: a coarse grid does
    const auto with = [&](const std::string& map, const std::vector<std::string>& extra) {
        std::vector<std::string> args = {dir.file(map)};
        args.insert(args.end(), view.begin(), view.end());
        args.insert(args.end(), extra.begin(), extra.end());
        return foamShot(dir, "shot.png", args);
    };
    // The packed texture, and the sea itself (its Foam channel mip-mapped in memory).
    double packedBare = 0;
    for (const char* map : {"packed.exr", "sea.exr"}) {
        const Picture on = with(map, {});
        const double foam = brightness(on, foamX0, foamX1), bare = brightness(on, bareX0, bareX1);
        std::printf("%s: coverage 1: %.1f, coverage 0: %.1f\n", map, foam, bare);
        EXPECT_GT(foam, 220) << map << ": foam is near-white (0.92 before gamma, 245)";
        EXPECT_GT(foam - bare, 60) << map;
        if (map == std::string("packed.exr")) packedBare = bare;
    }
    const Picture off = with("packed.exr", {"--no-baked-foam"});
    const double offLeft = brightness(off, foamX0, foamX1), offRight = brightness(off, bareX0, bareX1);
    std::printf("baked foam off: %.1f and %.1f\n", offLeft, offRight);
    EXPECT_NEAR(offLeft, offRight, 4.0) << "with the baked foam off the halves match";
    EXPECT_NEAR(packedBare, offRight, 2.0) << "no coverage, no foam";
}
