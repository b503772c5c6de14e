// ASTC HDR heights (astc-hdr-4x4, -6x6, -8x8: VK_FORMAT_ASTC_*_SFLOAT_BLOCK_EXT) end to end, judged by other
// programs than heightpack: the KTX2 structure by ktx-parse, the decoded values by ARM's astcenc command
// line (astcenc -dh, its own HDR decoder run as a separate program on each level's blocks) against the
// float chain heightpack writes of the same map, over the corpus's height maps, the example seas, crops of
// the seas and analytic fields; the same bytes on 1 and 4 threads; the pairs HDR cannot hold refused.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "heightpack/io/gpu_texture.hpp"
#include "support/heightpack_process.hpp"
#include "support/block_oracles.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
using nlohmann::json;

// A named namespace: the suites are compiled as one unity file, beside astc_format_test's helpers.
namespace astc_hdr_test {

struct HdrSize {
    const char* pixelType;
    int side;
    const char* vkName;
};
constexpr HdrSize kHdrSizes[] = {{"astc-hdr-4x4", 4, "VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK_EXT"},
                                 {"astc-hdr-6x6", 6, "VK_FORMAT_ASTC_6x6_SFLOAT_BLOCK_EXT"},
                                 {"astc-hdr-8x8", 8, "VK_FORMAT_ASTC_8x8_SFLOAT_BLOCK_EXT"}};

// The family: the corpus's height maps, choppy and ripple whole, two 64x64 crops of swell and choppy (cut by oiiotool)
// and analytic fields (a smooth wave, a steep periodic ridge, fine noise over a slow swell), as 16-bit PNGs.
std::vector<std::string> hdrFamily(const ScratchDir& dir) {
    const std::string root = HEIGHTPACK_SOURCE_DIR;
    std::vector<std::string> maps;
    for (const char* name : {"tests/corpus/trigger_grass_heightmap.png", "tests/corpus/trigger_greenland_heightmap.png",
                             "tests/corpus/trigger_mud_heightmap.png", "examples/maps/choppy.png",
                             "examples/maps/ripple.png"})
        maps.push_back(root + "/" + name);
    for (const char* sea : {"swell", "choppy"}) {
        const std::string crop = dir.file(std::string(sea) + "_crop.png");
        const ProcessResult r =
            runProcess({"oiiotool", root + "/examples/maps/" + sea + ".png", "--cut", "64x64+131+77", "-o", crop});
        EXPECT_EQ(r.code, 0) << r.err;
        maps.push_back(crop);
    }
    const auto ridge = [](int x, int y) {
        return float(0.5 + 0.45 * std::pow(std::fabs(std::sin(x * M_PI / 64.0 + y * M_PI / 128.0)), 8.0));
    };
    const auto noisy = [](int x, int y) {
        const unsigned h = (unsigned(x) * 73856093u) ^ (unsigned(y) * 19349663u);
        return float(0.5 + 0.3 * std::sin(x * 0.05) + 0.02 * (double(h % 1000u) / 1000.0 - 0.5));
    };
    writeImage(dir.file("wave.png"), makeImage(128, 128, smoothWave), OIIO::TypeDesc::UINT16);
    writeImage(dir.file("ridge.png"), makeImage(128, 128, ridge), OIIO::TypeDesc::UINT16);
    writeImage(dir.file("noisy.png"), makeImage(128, 128, noisy), OIIO::TypeDesc::UINT16);
    for (const char* name : {"wave.png", "ridge.png", "noisy.png"}) maps.push_back(dir.file(name));
    return maps;
}

}  // namespace astc_hdr_test

using namespace astc_hdr_test;

// Structure: every level (down to 1x1) as whole blocks, typeSize 1, the ASTC Data Format Descriptor with
// the SFLOAT sample KTX-Software writes (FLOAT and SIGNED qualifiers, -1.0f..1.0f), KTXswizzle r001, and
// heightpack's own reader giving one channel.
TEST(AstcHdrFormats, KtxHoldsEveryLevelAsSfloatBlocks) {
    if (!independentReaderInstalled()) HEIGHTPACK_WITHOUT_ORACLE("ktx-parse is not installed: run scripts/test.sh");
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(64, 16, smoothWave), OIIO::TypeDesc::UINT16);
    for (const HdrSize& size : kHdrSizes) {
        const std::string out = dir.file(std::string(size.pixelType) + ".ktx2");
        const ProcessResult r =
            heightpackRun({"pack", dir.file("map.png"), "--layout", "plain", "--pixel-type", size.pixelType, "-o", out, "--quiet"});
        ASSERT_EQ(r.code, 0) << out << ": " << r.err;
        const json j = readIndependently(out);
        EXPECT_EQ(j["format"], size.vkName) << out;
        EXPECT_EQ(j["typeSize"], 1);
        ASSERT_EQ(j["levelCount"], 7) << out;
        for (int level = 0; level < 7; ++level) {
            const int w = std::max(1, 64 >> level), h = std::max(1, 16 >> level);
            EXPECT_EQ(j["levels"][level]["byteLength"], ((w + size.side - 1) / size.side) * ((h + size.side - 1) / size.side) * 16)
                << out << " level " << level;
        }
        EXPECT_EQ(j["dfd"]["colorModel"], 162);  // KHR_DF_MODEL_ASTC
        EXPECT_EQ(j["dfd"]["transferFunction"], 1);  // linear
        EXPECT_EQ(j["dfd"]["texelBlockDimension"], json::array({size.side - 1, size.side - 1, 0, 0}));
        ASSERT_EQ(j["dfd"]["samples"].size(), 1u);
        EXPECT_EQ(j["dfd"]["samples"][0]["bitLength"], 127);
        EXPECT_EQ(j["dfd"]["samples"][0]["channelType"], 0xC0);  // ASTC_DATA | FLOAT | SIGNED
        EXPECT_EQ(j["dfd"]["samples"][0]["lower"], -1082130432);  // -1.0f, read as a signed word
        EXPECT_EQ(j["dfd"]["samples"][0]["upper"], 1065353216);   // 1.0f
        EXPECT_EQ(j["keyValues"]["KTXswizzle"], "r001");
        EXPECT_TRUE(j["keyValues"].contains("heightpack:rmsError")) << out;
        auto ours = readGpuTexture(out);
        ASSERT_TRUE(ours.ok()) << out;
        EXPECT_EQ(ours->levels.size(), 7u);
        EXPECT_EQ(ours->levels[0].channels, 1) << out;
    }
}

// Over the family and every block size, astcenc -dh's decode of every level, mapped back through the
// recorded offset and scale, errs against the float chain by the worst and RMS error the file records
// (`info`'s figures), with A = 1. R holds the value (KTXswizzle r001): astcenc's HDR encoder may choose RGB
// endpoint modes for a grey block, whose G and B then differ from R (printed, not judged). The comparison
// with LDR at the same bytes is tests/bench/bench_astc_hdr.sh's.
TEST(AstcHdrFormats, AstcencDecodesHdrHeightsWithinTheRecordedErrorOverTheFamily) {
    if (!independentReaderInstalled() || !astcencInstalled())
        HEIGHTPACK_WITHOUT_ORACLE("ktx-parse or astcenc is not installed: run scripts/test.sh");
    ScratchDir dir;
    int levelsJudged = 0, maps = 0;
    double greenBlueSpread = 0.0;  // in units of the range
    for (const std::string& map : hdrFamily(dir)) {
        ASSERT_EQ(heightpackRun({"pack", map, "--layout", "plain", "-o", dir.file("f.ktx2"), "--quiet"}).code, 0) << map;
        auto floats = readGpuTexture(dir.file("f.ktx2"));
        ASSERT_TRUE(floats.ok()) << map;
        ++maps;
        for (const HdrSize& size : kHdrSizes) {
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
            // Both decoders give the block's half floats: only float arithmetic on the way back differs.
            const double slack = scale * 1e-6 + 1e-6;
            for (size_t level = 0; level < floats->levels.size(); ++level) {
                const Image& given = floats->levels[level];
                const Image decoded = astcencDecode(dir, j["levels"][level]["blocks"], size.side, given.width, given.height, AstcProfile::Hdr);
                ASSERT_EQ(decoded.width, given.width);
                ASSERT_EQ(decoded.height, given.height);
                double most = 0.0, squares = 0.0, notOpaque = 0.0;
                for (size_t t = 0; t < given.texelCount(); ++t) {
                    const float* rgba = decoded.pixels.data() + 4 * t;
                    const double d = std::fabs(offset + scale * rgba[0] - given.pixels[t]);
                    most = std::max(most, d);
                    squares += d * d;
                    notOpaque = std::max(notOpaque, double(std::fabs(rgba[3] - 1.0f)));
                    greenBlueSpread = std::max({greenBlueSpread, double(std::fabs(rgba[1] - rgba[0])), double(std::fabs(rgba[2] - rgba[0]))});
                }
                const double rootMean = std::sqrt(squares / double(given.texelCount()));
                EXPECT_LE(most, worst[level] + slack) << map << " " << size.pixelType << " level " << level;
                EXPECT_GE(most, worst[level] - slack) << map << " " << size.pixelType << " level " << level;
                EXPECT_NEAR(rootMean, rms[level], slack) << map << " " << size.pixelType << " level " << level;
                EXPECT_EQ(notOpaque, 0.0) << map << " " << size.pixelType << " level " << level;
                ++levelsJudged;
            }
            std::printf("%-34s %s level 0: astcenc -dh worst %.3g rms %.3g (units of the range %.3g)\n",
                        map.substr(map.rfind('/') + 1).c_str(), size.pixelType, worst[0] / scale, rms[0] / scale, scale);
        }
    }
    std::printf("G and B differ from R by up to %.3g of the range\n", greenBlueSpread);
    EXPECT_EQ(maps, 10);
    EXPECT_GE(levelsJudged, 200);
}

// The same bytes whatever the thread count: every HDR size on 1 and 4 threads (astcenc's workers take
// blocks as they come; each block's bytes must depend on its texels alone).
TEST(AstcHdrFormats, SameBytesOnOneAndManyThreads) {
    ScratchDir dir;
    const std::string map = std::string(HEIGHTPACK_SOURCE_DIR) + "/examples/maps/ripple.png";
    for (const HdrSize& size : kHdrSizes) {
        std::vector<std::vector<unsigned char>> files;
        for (const char* threads : {"1", "4"}) {
            const std::string out = dir.file(std::string("t") + threads + ".ktx2");
            ASSERT_EQ(heightpackRun({"pack", map, "--layout", "plain", "--pixel-type", size.pixelType, "--threads", threads,
                                     "-o", out, "--quiet"}).code, 0) << size.pixelType;
            files.push_back(readBytes(out));
        }
        EXPECT_GT(files[0].size(), 1000u);
        EXPECT_EQ(files[0], files[1]) << size.pixelType << ": 1 and 4 threads";
    }
}

// What ASTC HDR cannot hold says so: exit 2, one line naming what to write instead, nothing written.
TEST(AstcHdrFormats, ImpossiblePairsAreUsageErrorsThatWriteNothing) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
    struct Refusal {
        std::vector<std::string> args;
        std::string output, says;
    };
    const std::string map = dir.file("map.png");
    const std::vector<Refusal> refusals = {
        {{"pack", map, "--layout", "plain", "--pixel-type", "astc-hdr-4x4"}, dir.file("p.dds"), ".ktx2"},
        {{"pack", map, "--layout", "plain", "--pixel-type", "astc-hdr-6x6"}, dir.file("p.exr"), ".ktx2"},
        {{"pack", map, "--pixel-type", "astc-hdr-8x8"}, dir.file("p.ktx2"), "--layout plain"},
        {{"normal", map, "--tile-size", "8m", "--height", "1m", "--layout", "xy", "--pixel-type", "astc-hdr-6x6"},
         dir.file("n.ktx2"), "--pixel-type astc-6x6"},
        {{"normal", map, "--tile-size", "8m", "--height", "1m", "--pixel-type", "astc-hdr-4x4"}, dir.file("n2.ktx2"),
         "--layout plain"},
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
