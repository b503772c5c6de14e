// ASTC outputs end to end, judged by other programs than heightpack: the structure of the KTX2 files by
// the independent reader (ktx-parse), and the decoded values by ARM's astcenc command-line tool (astcenc
// -dl, Debian's astcenc package: its own decoder, run as a separate program on each level's blocks),
// compared with the float chain heightpack writes of the same map over a family of maps: the corpus's
// grayscale height maps and the example seas (6x6 blocks divide none of their sides: edge blocks are
// partial on every level).
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "heightpack/io/gpu_texture.hpp"
#include "support/heightpack_process.hpp"
#include "support/block_oracles.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
using nlohmann::json;

// A named namespace: the suites are compiled as one unity file, beside block_format_test's helpers.
namespace astc_test {

struct AstcSize {
    const char* pixelType;
    int side;
    const char* vkName;
};
constexpr AstcSize kSizes[] = {{"astc-4x4", 4, "VK_FORMAT_ASTC_4x4_UNORM_BLOCK"},
                               {"astc-6x6", 6, "VK_FORMAT_ASTC_6x6_UNORM_BLOCK"},
                               {"astc-8x8", 8, "VK_FORMAT_ASTC_8x8_UNORM_BLOCK"}};

// The family's maps, each packed as they are (heightpack reads the PNG).
std::vector<std::string> familyMaps() {
    const std::string root = HEIGHTPACK_SOURCE_DIR;
    std::vector<std::string> maps;
    for (const char* name : {"tests/corpus/trigger_grass_heightmap.png", "tests/corpus/trigger_greenland_heightmap.png",
                             "tests/corpus/trigger_mud_heightmap.png", "examples/maps/swell.png", "examples/maps/choppy.png", "examples/maps/ripple.png"})
        maps.push_back(root + "/" + name);
    return maps;
}

// A half holds a value in [0, 1] to within 2^-12 (half of its spacing below 1): what astcenc's EXR adds.
constexpr double kHalfRounding = 1.0 / 4096.0;

double angleDegrees(double x0, double y0, double x1, double y1) {
    const double z0 = std::sqrt(std::max(0.0, 1 - x0 * x0 - y0 * y0)), z1 = std::sqrt(std::max(0.0, 1 - x1 * x1 - y1 * y1));
    const double dot = (x0 * x1 + y0 * y1 + z0 * z1) / std::sqrt((x0 * x0 + y0 * y0 + z0 * z0) * (x1 * x1 + y1 * y1 + z1 * z1));
    return std::acos(std::clamp(dot, -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace astc_test

using namespace astc_test;

// Structure: every level (down to 1x1) as whole blocks of the size asked, typeSize 1, the ASTC Data Format
// Descriptor (model ASTC, the block's dimensions, one 128-bit sample), KTXswizzle saying which channels
// hold the values, and heightpack's own reader giving one channel for heights and two for normals.
TEST(AstcFormats, KtxHoldsEveryLevelAsWholeBlocks) {
    if (!independentReaderInstalled()) HEIGHTPACK_WITHOUT_ORACLE("ktx-parse is not installed: run scripts/test.sh");
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(64, 16, smoothWave), OIIO::TypeDesc::UINT16);
    for (const AstcSize& size : kSizes)
        for (const bool normals : {false, true}) {
            const std::string out = dir.file(std::string(normals ? "n_" : "h_") + size.pixelType + ".ktx2");
            const std::vector<std::string> args =
                normals ? std::vector<std::string>{"normal", dir.file("map.png"), "--tile-size", "8m", "--height", "0.5m",
                                                   "--layout", "xy", "--pixel-type", size.pixelType, "-o", out, "--quiet"}
                        : std::vector<std::string>{"pack", dir.file("map.png"), "--layout", "plain", "--pixel-type",
                                                   size.pixelType, "-o", out, "--quiet"};
            const ProcessResult r = heightpackRun(args);
            ASSERT_EQ(r.code, 0) << out << ": " << r.err;
            const json j = readIndependently(out);
            EXPECT_EQ(j["format"], size.vkName) << out;
            EXPECT_EQ(j["typeSize"], 1);
            ASSERT_EQ(j["levelCount"], 7) << out;  // 64x16 down to 1x1
            for (int level = 0; level < 7; ++level) {
                const int w = std::max(1, 64 >> level), h = std::max(1, 16 >> level);
                // Levels under a block's side are still one whole block.
                EXPECT_EQ(j["levels"][level]["byteLength"], ((w + size.side - 1) / size.side) * ((h + size.side - 1) / size.side) * 16)
                    << out << " level " << level;
            }
            EXPECT_EQ(j["dfd"]["colorModel"], 162);  // KHR_DF_MODEL_ASTC
            EXPECT_EQ(j["dfd"]["bytesPlane0"], 16);
            EXPECT_EQ(j["dfd"]["texelBlockDimension"], json::array({size.side - 1, size.side - 1, 0, 0}));
            ASSERT_EQ(j["dfd"]["samples"].size(), 1u);
            EXPECT_EQ(j["dfd"]["samples"][0]["bitLength"], 127);
            EXPECT_EQ(j["dfd"]["samples"][0]["channelType"], 0);  // KHR_DF_CHANNEL_ASTC_DATA
            EXPECT_EQ(j["keyValues"]["KTXswizzle"], normals ? "ra01" : "r001");
            EXPECT_TRUE(j["keyValues"].contains("heightpack:rmsError")) << out;
            EXPECT_EQ(j["keyValues"].contains("heightpack:angleError"), normals) << out;
            auto ours = readGpuTexture(out);
            ASSERT_TRUE(ours.ok()) << out;
            EXPECT_EQ(ours->levels.size(), 7u);
            EXPECT_EQ(ours->levels[0].channels, normals ? 2 : 1) << out;
        }
}

// Heights: over the family and every block size, astcenc's decode of every level, mapped back through the
// recorded offset and scale, errs against the float chain by the worst and RMS error the file records (to
// within the half astcenc's EXR holds), so `info`'s figures are the budget a loader decoding the file gets.
// Heights come out as luminance: R = G = B, A = 1.
TEST(AstcFormats, AstcencDecodesHeightsWithinTheRecordedErrorOverTheFamily) {
    if (!independentReaderInstalled() || !astcencInstalled())
        HEIGHTPACK_WITHOUT_ORACLE("ktx-parse or astcenc is not installed: run scripts/test.sh");
    ScratchDir dir;
    int levelsJudged = 0, maps = 0;
    for (const std::string& map : familyMaps()) {
        ASSERT_EQ(heightpackRun({"pack", map, "--layout", "plain", "-o", dir.file("f.ktx2"), "--quiet"}).code, 0) << map;
        auto floats = readGpuTexture(dir.file("f.ktx2"));
        ASSERT_TRUE(floats.ok()) << map;
        ++maps;
        for (const AstcSize& size : kSizes) {
            const ProcessResult r = heightpackRun({"pack", map, "--layout", "plain", "--pixel-type", size.pixelType, "-o",
                                                   dir.file("a.ktx2"), "--quiet"});
            ASSERT_EQ(r.code, 0) << map << ": " << r.err;
            const json j = readIndependently(dir.file("a.ktx2"));
            const double offset = std::stod(j["keyValues"]["heightpack:normalisedOffset"].get<std::string>());
            const double scale = std::stod(j["keyValues"]["heightpack:normalisedScale"].get<std::string>());
            const std::vector<double> worst = numberList(j["keyValues"]["heightpack:lookupError"]);
            const std::vector<double> rms = numberList(j["keyValues"]["heightpack:rmsError"]);
            ASSERT_EQ(j["levels"].size(), floats->levels.size());
            ASSERT_EQ(worst.size(), floats->levels.size());
            const double slack = scale * kHalfRounding + 1e-6;
            for (size_t level = 0; level < floats->levels.size(); ++level) {
                const Image& given = floats->levels[level];
                const Image decoded = astcencDecode(dir, j["levels"][level]["blocks"], size.side, given.width, given.height);
                ASSERT_EQ(decoded.width, given.width);
                ASSERT_EQ(decoded.height, given.height);
                double most = 0.0, squares = 0.0, notLuminance = 0.0;
                for (size_t t = 0; t < given.texelCount(); ++t) {
                    const float* rgba = decoded.pixels.data() + 4 * t;
                    const double d = std::fabs(offset + scale * rgba[0] - given.pixels[t]);
                    most = std::max(most, d);
                    squares += d * d;
                    notLuminance = std::max({notLuminance, double(std::fabs(rgba[1] - rgba[0])),
                                             double(std::fabs(rgba[2] - rgba[0])), double(std::fabs(rgba[3] - 1.0f))});
                }
                const double rootMean = std::sqrt(squares / double(given.texelCount()));
                EXPECT_LE(most, worst[level] + slack) << map << " " << size.pixelType << " level " << level;
                EXPECT_GE(most, worst[level] - slack) << map << " " << size.pixelType << " level " << level;
                EXPECT_NEAR(rootMean, rms[level], slack) << map << " " << size.pixelType << " level " << level;
                EXPECT_EQ(notLuminance, 0.0) << map << " " << size.pixelType << " level " << level;
                ++levelsJudged;
                if (level == 0)
                    std::printf("%-50s %s level 0: astcenc -dl worst %.3g rms %.3g (recorded %.3g, %.3g), range %.3g\n",
                                map.substr(map.rfind('/') + 1).c_str(), size.pixelType, most, rootMean, worst[0], rms[0], scale);
            }
        }
    }
    EXPECT_EQ(maps, 6);
    EXPECT_GE(levelsJudged, 150);
}

// xy normals: astcenc's decode (x in R, y in A, z rebuilt) makes the angle against the float normals that
// the file records, worst and RMS per level, over the family and every block size.
TEST(AstcFormats, AstcencDecodesNormalsWithinTheRecordedAngleOverTheFamily) {
    if (!independentReaderInstalled() || !astcencInstalled())
        HEIGHTPACK_WITHOUT_ORACLE("ktx-parse or astcenc is not installed: run scripts/test.sh");
    ScratchDir dir;
    int levelsJudged = 0;
    const std::vector<std::string> maps = familyMaps();
    for (const std::string& map : {maps[0], maps[3], maps[5]}) {
        const std::vector<std::string> common = {"normal", map, "--tile-size", "8m", "--height", "0.25m", "--layout", "xy"};
        std::vector<std::string> args = common;
        args.insert(args.end(), {"-o", dir.file("f.ktx2"), "--quiet"});
        ASSERT_EQ(heightpackRun(args).code, 0) << map;
        auto floats = readGpuTexture(dir.file("f.ktx2"));
        ASSERT_TRUE(floats.ok()) << map;
        for (const AstcSize& size : kSizes) {
            args = common;
            args.insert(args.end(), {"--pixel-type", size.pixelType, "-o", dir.file("a.ktx2"), "--quiet"});
            const ProcessResult r = heightpackRun(args);
            ASSERT_EQ(r.code, 0) << map << ": " << r.err;
            const json j = readIndependently(dir.file("a.ktx2"));
            const double offset = std::stod(j["keyValues"]["heightpack:normalisedOffset"].get<std::string>());
            const double scale = std::stod(j["keyValues"]["heightpack:normalisedScale"].get<std::string>());
            const std::vector<double> worst = numberList(j["keyValues"]["heightpack:angleError"]);
            const std::vector<double> rms = numberList(j["keyValues"]["heightpack:rmsAngleError"]);
            ASSERT_EQ(worst.size(), floats->levels.size());
            for (size_t level = 0; level < floats->levels.size(); ++level) {
                const Image& given = floats->levels[level];
                const Image decoded = astcencDecode(dir, j["levels"][level]["blocks"], size.side, given.width, given.height);
                ASSERT_EQ(decoded.texelCount(), given.texelCount());
                double most = 0.0, squares = 0.0, halfAngle = 0.0;
                for (size_t t = 0; t < given.texelCount(); ++t) {
                    const double x = offset + scale * decoded.pixels[4 * t], y = offset + scale * decoded.pixels[4 * t + 3];
                    const double a = angleDegrees(given.pixels[2 * t], given.pixels[2 * t + 1], x, y);
                    most = std::max(most, a);
                    squares += a * a;
                    // What the half's rounding of x and y alone can turn this normal by.
                    halfAngle = std::max(halfAngle, angleDegrees(x, y, x + scale * kHalfRounding, y + scale * kHalfRounding));
                }
                const double rootMean = std::sqrt(squares / double(given.texelCount()));
                const double slack = halfAngle + 1e-4;
                EXPECT_LE(most, worst[level] + slack) << map << " " << size.pixelType << " level " << level;
                EXPECT_GE(most, worst[level] - slack) << map << " " << size.pixelType << " level " << level;
                EXPECT_NEAR(rootMean, rms[level], slack) << map << " " << size.pixelType << " level " << level;
                ++levelsJudged;
                if (level == 0)
                    std::printf("%-50s %s level 0: astcenc -dl worst %.3g rms %.3g deg (recorded %.3g, %.3g)\n",
                                map.substr(map.rfind('/') + 1).c_str(), size.pixelType, most, rootMean, worst[0], rms[0]);
            }
        }
    }
    EXPECT_GE(levelsJudged, 70);
}

// The same bytes whatever the thread count: heights and normals in every block size on 1 and 2 threads
// (astcenc's workers take blocks as they come: each block's bytes must not depend on which took it).
TEST(AstcFormats, SameBytesOnAnyThreadCount) {
    ScratchDir dir;
    const std::string map = std::string(HEIGHTPACK_SOURCE_DIR) + "/examples/maps/ripple.png";
    for (const AstcSize& size : kSizes)
        for (const bool normals : {false, true}) {
            std::vector<std::vector<unsigned char>> files;
            for (const char* threads : {"1", "2"}) {
                const std::string out = dir.file(std::string("t") + threads + ".ktx2");
                const std::vector<std::string> args =
                    normals ? std::vector<std::string>{"normal", map, "--tile-size", "8m",
                                                       "--height", "0.25m", "--layout", "xy", "--pixel-type", size.pixelType,
                                                       "--threads", threads, "-o", out, "--quiet"}
                            : std::vector<std::string>{"pack", map, "--layout", "plain",
                                                       "--pixel-type", size.pixelType, "--threads", threads, "-o", out, "--quiet"};
                ASSERT_EQ(heightpackRun(args).code, 0) << size.pixelType;
                files.push_back(readBytes(out));
            }
            EXPECT_GT(files[0].size(), 1000u);
            EXPECT_EQ(files[0], files[1]) << size.pixelType << (normals ? " normals" : " heights") << ": 1 and 2 threads";
        }
}

// What ASTC cannot hold says so: exit 2, one line naming what to write instead, nothing written.
TEST(AstcFormats, ImpossiblePairsAreUsageErrorsThatWriteNothing) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
    struct Refusal {
        std::vector<std::string> args;
        std::string output, says;
    };
    const std::string map = dir.file("map.png");
    const std::vector<Refusal> refusals = {
        {{"pack", map, "--layout", "plain", "--pixel-type", "astc-4x4"}, dir.file("p.dds"), ".ktx2"},
        {{"pack", map, "--layout", "plain", "--pixel-type", "astc-6x6"}, dir.file("p.exr"), ".ktx2"},
        {{"pack", map, "--pixel-type", "astc-8x8"}, dir.file("p.ktx2"), "--layout plain"},
        {{"normal", map, "--tile-size", "8m", "--height", "1m", "--layout", "xy", "--pixel-type", "astc-4x4"},
         dir.file("n.dds"), "bc5"},
        {{"normal", map, "--tile-size", "8m", "--height", "1m", "--pixel-type", "astc-4x4"}, dir.file("n.ktx2"), "--layout xy"},
    };
    for (Refusal r : refusals) {
        r.args.insert(r.args.end(), {"-o", r.output});
        const ProcessResult run = heightpackRun(r.args);
        EXPECT_EQ(run.code, 2) << r.output << " " << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
        EXPECT_NE(run.err.find(r.says), std::string::npos) << run.err;
        EXPECT_FALSE(std::filesystem::exists(r.output)) << r.output;
    }
}
