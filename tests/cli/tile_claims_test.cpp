// What `tile` says of its result holds (issue 35): the heights it prints are those of the file it wrote,
// read back by OpenImageIO; the result stays within the input's range; and beyond the bands it reports,
// the re-synthesis changes the map only by a smooth field, as its --help and the README say.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

const std::string kSource = HEIGHTPACK_SOURCE_DIR;

struct Grey {
    int width = 0, height = 0;
    std::vector<float> v;
    float at(int x, int y) const { return v[size_t(y) * width + x]; }
};

// The first channel as OpenImageIO reads it (integers scaled to [0,1]).
Grey readGrey(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    Grey g;
    if (!in) return g;
    const OIIO::ImageSpec& spec = in->spec();
    g.width = spec.width, g.height = spec.height;
    g.v.resize(size_t(g.width) * g.height);
    EXPECT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, g.v.data()));
    return g;
}

// The top-left 3/4 of a map, so that a map which tiles no longer does, written with the given sample type.
std::string cropped(const ScratchDir& dir, const std::string& source, const std::string& name, OIIO::TypeDesc type) {
    const Grey g = readGrey(source);
    const int w = g.width * 3 / 4, h = g.height * 3 / 4;
    Image out(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) out.pixels[size_t(y) * w + x] = g.at(x, y);
    const std::string path = dir.file(name);
    writeImage(path, out, type);
    return path;
}

// Maps nobody here made, as 8-bit, 16-bit and float files, none of them tiling.
std::vector<std::string> mapsToTile(const ScratchDir& dir) {
    return {kSource + "/examples/maps/painted_not_tileable.png",
            cropped(dir, kSource + "/tests/corpus/etr_rock.png", "rock16.png", OIIO::TypeDesc::UINT16),
            cropped(dir, kSource + "/tests/corpus/trigger_mud_heightmap.png", "mud.exr", OIIO::TypeDesc::FLOAT),
            cropped(dir, kSource + "/tests/corpus/etr_pebbles01.png", "pebbles8.png", OIIO::TypeDesc::UINT8)};
}

TEST(TileClaims, ThePrintedHeightsAreThoseOfTheFileWritten) {
    ScratchDir dir;
    int checked = 0, widenings = 0;
    for (const std::string& map : mapsToTile(dir)) {
        for (const char* method : {"periodic", "quilt", "moisan", "crossfade"}) {
            const std::string out = dir.file(std::string("out_") + method + std::filesystem::path(map).extension().string());
            const ProcessResult json = heightpackRun({"tile", map, "--method", method, "-o", out, "--json", "--force"});
            if (json.code == 1) continue;  // the method could not make it tile: nothing written, nothing claimed
            if (json.code == 4) {
                // Its heights leave [0,1], which a PNG cannot hold: nothing written, and a .tif holds them as
                // float, unclipped, as --help says.
                EXPECT_NE(json.err.find("outside the [0,1]"), std::string::npos) << json.err;
                EXPECT_FALSE(std::filesystem::exists(out)) << out;
                const std::string tif = dir.file(std::string("out_") + method + ".tif");
                const ProcessResult widened = heightpackRun({"tile", map, "--method", method, "-o", tif, "--json", "--force"});
                ASSERT_EQ(widened.code, 0) << widened.err;
                EXPECT_TRUE(nlohmann::json::parse(widened.out)["widenedToFloat"].get<bool>());
                auto in = OIIO::ImageInput::open(tif);
                ASSERT_TRUE(in);
                EXPECT_EQ(in->spec().format, OIIO::TypeDesc::FLOAT);
                const Grey g = readGrey(tif);
                const auto [low, high] = std::minmax_element(g.v.begin(), g.v.end());
                EXPECT_TRUE(*low < 0 || *high > 1) << *low << ".." << *high;
                ++widenings;
                continue;
            }
            ASSERT_EQ(json.code, 0) << json.err;
            const Grey written = readGrey(out);
            const auto [low, high] = std::minmax_element(written.v.begin(), written.v.end());
            const nlohmann::json r = nlohmann::json::parse(json.out);
            // To within a float's rounding of an integer sample (a 16-bit step is 1.5e-5).
            EXPECT_NEAR(r["range"][0].get<double>(), double(*low), 1e-6) << map << " " << method;
            EXPECT_NEAR(r["range"][1].get<double>(), double(*high), 1e-6) << map << " " << method;
            ++checked;
            if (std::string(method) != "periodic") continue;
            // The text says the same, to the digits it prints.
            const ProcessResult text = heightpackRun({"tile", map, "--method", method, "-o", out, "--force"});
            char expected[64];
            std::snprintf(expected, sizeof expected, "heights %.4g..%.4g", double(*low), double(*high));
            EXPECT_NE(text.out.find(expected), std::string::npos) << expected << " in " << text.out;
        }
    }
    EXPECT_GE(checked, 12);
    EXPECT_GE(widenings, 1);
}

// Beyond the bands the re-synthesis or the quilt reports, the result is the map plus a smooth field (the large scales
// made periodic): the discrete Laplacian of the change is a small part of the map's own there, while the
// bands hold new content. Written as float, so no rounding hides or adds detail.
TEST(TileClaims, PeriodicAndQuiltChangeTheMapBeyondTheirBandsOnlyByASmoothField) {
    ScratchDir dir;
    int checked = 0;
    for (const std::string& map : mapsToTile(dir))
    for (const std::string method : {"periodic", "quilt"}) {
        const std::string out = dir.file(method + ".exr");
        const ProcessResult run = heightpackRun({"tile", map, "--method", method, "-o", out, "--depth", "float", "--json"});
        ASSERT_EQ(run.code, 0) << run.err;
        const nlohmann::json r = nlohmann::json::parse(run.out);
        if (r["method"] != method) continue;  // fell back to another method: other claims
        const Grey before = readGrey(map), after = readGrey(out);
        ASSERT_EQ(before.width, after.width);
        const int bandX = r["band"][0], bandY = r["band"][1], w = before.width, h = before.height;
        double changeLaplacian = 0, mapLaplacian = 0, bandChange = 0;
        long inside = 0, inBand = 0, eased = 0;
        const auto [inLow, inHigh] = std::minmax_element(before.v.begin(), before.v.end());
        // Where the result would pass the input's extremes it is eased into the outer 2% of its range.
        const double margin = 0.02 * (double(*inHigh) - *inLow);
        auto nearExtremes = [&](int x, int y) {
            for (int j = -1; j <= 1; ++j)
                for (int i = -1; i <= 1; ++i) {
                    const double a = after.at(x + i, y + j);
                    if (a > *inHigh - margin || a < *inLow + margin) return true;
                }
            return false;
        };
        auto laplacian = [&](const Grey& g, int x, int y) {
            return double(g.at(x - 1, y)) + g.at(x + 1, y) + g.at(x, y - 1) + g.at(x, y + 1) - 4.0 * g.at(x, y);
        };
        for (int y = 1; y < h - 1; ++y) {
            for (int x = 1; x < w - 1; ++x) {
                const int dx = std::min(x, w - 1 - x), dy = std::min(y, h - 1 - y);
                if (dx < (bandX + 1) / 2 + 1 || dy < (bandY + 1) / 2 + 1) {
                    bandChange += std::abs(double(after.at(x, y)) - before.at(x, y));
                    ++inBand;
                    continue;
                }
                if (dx < (bandX + 1) / 2 + 2 || dy < (bandY + 1) / 2 + 2) continue;  // the Laplacian reaches the band
                if (nearExtremes(x, y)) {
                    ++eased;
                    continue;
                }
                const double m = laplacian(before, x, y), a = laplacian(after, x, y);
                mapLaplacian += m * m;
                changeLaplacian += (a - m) * (a - m);
                ++inside;
            }
        }
        ASSERT_GT(inside, 0);
        const double ratio = std::sqrt(changeLaplacian / mapLaplacian);
        std::printf("%s %s: band %dx%d, change's Laplacian %.4f of the map's (%ld texels, %ld near the extremes), mean "
                    "change in the bands %.4f\n",
                    method.c_str(), map.c_str(), bandX, bandY, ratio, inside, eased, bandChange / inBand);
        EXPECT_LT(ratio, 0.005) << map;
        EXPECT_GT(bandChange / inBand, 1e-3) << map << ": the bands hold new content";
        // Within the input's range, as the README says (eased into it, never clipped).
        const auto [outLow, outHigh] = std::minmax_element(after.v.begin(), after.v.end());
        EXPECT_GE(*outLow, *inLow) << map;
        EXPECT_LE(*outHigh, *inHigh) << map;
        ++checked;
    }
    EXPECT_GE(checked, 7);
}

}  // namespace
