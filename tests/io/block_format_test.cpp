// BC4 and BC5 outputs end to end, judged by other programs than heightpack: the structure of the KTX2
// and DDS files by the independent reader (ktx-parse; nvddsinfo), the decoded values by NVIDIA Texture
// Tools' nvdecompress (Debian's libnvtt-bin), and the encoder's accuracy against nvcompress -bc4/-bc5 and
// libsquish's kBc4/kBc5 (Debian's libsquish-dev, linked into this test only) on the same values over the
// real corpus, the example seas and crops of them, both encoders' blocks decoded
// by a decoder written here from the specification's table (nvdecompress rounds its palette to whole
// codes, which would judge encoders by its own arithmetic rather than the format's).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#if HEIGHTPACK_HAVE_SQUISH
#include <squish.h>
#endif

#include "heightpack/core/block_compression.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/normal.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/read.hpp"
#include "support/heightpack_process.hpp"
#include "support/block_oracles.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
using nlohmann::json;

namespace {

bool nvttInstalled() { return runProcess({"sh", "-c", "command -v nvcompress && command -v nvdecompress"}).code == 0; }

void ddsPut32(std::vector<std::uint8_t>& b, size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b[at + size_t(i)] = std::uint8_t(v >> (8 * i));
}

// A DDS without the DX10 header, as nvcompress writes BC4/BC5 (Microsoft's DDS_HEADER with the FourCC
// ATI1 or ATI2): the form nvdecompress reads.
std::vector<std::uint8_t> legacyDds(int width, int height, bool bc5, const std::vector<std::uint8_t>& blocks) {
    std::vector<std::uint8_t> b(128, 0);
    ddsPut32(b, 0, 0x20534444);                // "DDS "
    ddsPut32(b, 4, 124);                       // dwSize
    ddsPut32(b, 8, 0x1 | 0x2 | 0x4 | 0x1000 | 0x80000);  // CAPS HEIGHT WIDTH PIXELFORMAT LINEARSIZE
    ddsPut32(b, 12, std::uint32_t(height));
    ddsPut32(b, 16, std::uint32_t(width));
    ddsPut32(b, 20, std::uint32_t(blocks.size()));
    ddsPut32(b, 76, 32);                       // ddspf.dwSize
    ddsPut32(b, 80, 0x4);                      // DDPF_FOURCC
    b[84] = 'A', b[85] = 'T', b[86] = 'I', b[87] = bc5 ? '2' : '1';
    ddsPut32(b, 108, 0x1000);                  // DDSCAPS_TEXTURE
    b.insert(b.end(), blocks.begin(), blocks.end());
    return b;
}

// An uncompressed TGA (type 2) as nvdecompress writes it: its channels R, G as 0..255 values.
Image readTga(const std::string& path) {
    const std::vector<unsigned char> t = readBytes(path);
    EXPECT_GE(t.size(), 18u);
    if (t.size() < 18) return {};
    const int idLength = t[0], width = t[12] | t[13] << 8, height = t[14] | t[15] << 8, bytes = t[16] / 8;
    const bool topDown = t[17] & 0x20;
    EXPECT_EQ(t[2], 2);
    EXPECT_GE(t.size(), 18u + idLength + size_t(width) * height * bytes);
    Image image(width, height, 2);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t at = 18 + idLength + (size_t(topDown ? y : height - 1 - y) * width + x) * bytes;
            image.at(x, y, 0) = t[at + 2];  // BGR(A)
            image.at(x, y, 1) = t[at + 1];
        }
    return image;
}

// nvdecompress's decode of blocks: R (and G for BC5) as 0..255.
Image nvDecode(const ScratchDir& dir, const std::string& name, int width, int height, bool bc5,
               const std::vector<std::uint8_t>& blocks) {
    writeBytes(dir.file(name + ".dds"), legacyDds(width, height, bc5, blocks));
    const ProcessResult r = runProcess({"nvdecompress", dir.file(name + ".dds")});
    EXPECT_EQ(r.code, 0) << r.err;
    return readTga(dir.file(name + ".tga"));
}

// An uncompressed 32-bit TGA, top row first, of 8-bit codes: R = x, G = y (0 when absent), B = 0.
void writeTga(const std::string& path, const std::vector<int>& r, const std::vector<int>& g, int width, int height) {
    std::vector<unsigned char> t(18, 0);
    t[2] = 2;
    t[12] = width & 255, t[13] = width >> 8, t[14] = height & 255, t[15] = height >> 8;
    t[16] = 32, t[17] = 0x20 | 8;
    // One channel (BC4): R = G = B = A, since nvcompress -bc4 takes alpha and readers take red.
    for (size_t i = 0; i < r.size(); ++i) {
        const unsigned char v = (unsigned char)r[i];
        if (g.empty()) t.insert(t.end(), {v, v, v, v});
        else t.insert(t.end(), {0, (unsigned char)g[i], v, 255});
    }
    writeBytes(path, t);
}

// nvcompress -bc4/-bc5 of unorm values quantised to 8 bits (as it takes them): its blocks.
std::vector<std::uint8_t> nvcompressBlocks(const ScratchDir& dir, const Image& unorm, bool bc5) {
    std::vector<int> r, g;
    for (size_t t = 0; t < unorm.texelCount(); ++t) {
        r.push_back(int(std::lround(std::clamp(unorm.pixels[t * unorm.channels], 0.0f, 1.0f) * 255)));
        if (bc5) g.push_back(int(std::lround(std::clamp(unorm.pixels[t * 2 + 1], 0.0f, 1.0f) * 255)));
    }
    writeTga(dir.file("in.tga"), r, g, unorm.width, unorm.height);
    const ProcessResult c = runProcess({"nvcompress", bc5 ? "-bc5" : "-bc4", "-nomips", dir.file("in.tga"), dir.file("nv.dds")});
    EXPECT_EQ(c.code, 0) << c.err;
    const std::vector<unsigned char> dds = readBytes(dir.file("nv.dds"));
    EXPECT_EQ(dds.size(), 128 + size_t((unorm.width + 3) / 4) * ((unorm.height + 3) / 4) * (bc5 ? 16 : 8));
    EXPECT_EQ(dds[87], bc5 ? '2' : '1');  // FourCC ATI1 / ATI2, no DX10 header
    return std::vector<std::uint8_t>(dds.begin() + 128, dds.end());
}

// libsquish's kBc4/kBc5 blocks of unorm values quantised to 8 bits (as it takes them), R (and G) of RGBA.
std::vector<std::uint8_t> squishBlocks(const Image& unorm, bool bc5) {
#if HEIGHTPACK_HAVE_SQUISH
    std::vector<squish::u8> rgba(unorm.texelCount() * 4, 255);
    for (size_t t = 0; t < unorm.texelCount(); ++t)
        for (int c = 0; c < (bc5 ? 2 : 1); ++c)
            rgba[t * 4 + size_t(c)] = squish::u8(std::lround(std::clamp(unorm.pixels[t * unorm.channels + size_t(c)], 0.0f, 1.0f) * 255));
    const int flags = bc5 ? squish::kBc5 : squish::kBc4;
    std::vector<std::uint8_t> blocks(size_t(squish::GetStorageRequirements(unorm.width, unorm.height, flags)));
    squish::CompressImage(rgba.data(), unorm.width, unorm.height, blocks.data(), flags);
    return blocks;
#else
    (void)unorm, (void)bc5;
    return {};
#endif
}

struct BlockErrors {
    double rms = 0.0, worst = 0.0;
};

// The error of decoded (0..255 codes) against unorm values in [0, 1], in unorm units, over `channels`.
BlockErrors unormErrors(const Image& unorm, const Image& decoded) {
    BlockErrors e;
    double sum = 0.0;
    for (size_t t = 0; t < unorm.texelCount(); ++t)
        for (int c = 0; c < unorm.channels; ++c) {
            const double d = decoded.pixels[t * decoded.channels + size_t(c)] / 255.0 - unorm.pixels[t * unorm.channels + size_t(c)];
            sum += d * d;
            e.worst = std::max(e.worst, std::fabs(d));
        }
    e.rms = std::sqrt(sum / double(unorm.pixels.size()));
    return e;
}

// Unorm values of image: (v - lo) / (hi - lo) over all its values.
Image unormOf(const Image& image) {
    const auto [lo, hi] = std::minmax_element(image.pixels.begin(), image.pixels.end());
    Image out = image;
    const float low = *lo, span = std::max(*hi - *lo, 1e-6f);
    for (float& v : out.pixels) v = (v - low) / span;
    return out;
}

Image cropOf(const Image& image, int x0, int y0, int w, int h) {
    Image out(w, h, image.channels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < image.channels; ++c) out.at(x, y, c) = image.at(x0 + x, y0 + y, c);
    return out;
}

// The family: the corpus's grayscale height maps, the example seas, and 64x64 crops of the seas; for
// each its first three mip levels (what a chain stores most of).
std::vector<std::pair<std::string, Image>> heightFamily() {
    const std::string root = HEIGHTPACK_SOURCE_DIR;
    std::vector<std::pair<std::string, Image>> maps;
    for (const char* name : {"tests/corpus/trigger_altitude_heightmap.png", "tests/corpus/trigger_grass_heightmap.png",
                             "tests/corpus/trigger_greenland_heightmap.png", "tests/corpus/trigger_mud_heightmap.png",
                             "tests/corpus/etr_milos_castle_elev.png", "examples/maps/swell.png",
                             "examples/maps/choppy.png", "examples/maps/ripple.png"}) {
        auto loaded = loadHeightMap(root + "/" + name);
        EXPECT_TRUE(loaded.ok()) << name;
        if (!loaded.ok()) continue;
        const Image& h = loaded->heights;
        const bool pow2 = (h.width & (h.width - 1)) == 0 && (h.height & (h.height - 1)) == 0;
        const std::vector<Image> chain = pow2 ? generateMipChain(h, Filter::Kaiser) : std::vector<Image>{h};
        for (size_t level = 0; level < std::min<size_t>(3, chain.size()); ++level)
            maps.emplace_back(std::string(name) + " level " + std::to_string(level), chain[level]);
        if (std::string(name).find("examples") != std::string::npos && h.width >= 128 && h.height >= 128)
            for (int k = 0; k < 3; ++k) {
                const int x0 = (37 * k * 13) % (h.width - 64), y0 = (53 * k * 7) % (h.height - 64);
                maps.emplace_back(std::string(name) + " cropOf " + std::to_string(k), cropOf(h, x0, y0, 64, 64));
            }
    }
    return maps;
}

}  // namespace

// Structure: the files pack and normal write hold every level as whole blocks, with the formats' codes and
// the Data Format Descriptor a block format has, as the independent readers see them.
TEST(BlockFormats, KtxAndDdsHoldEveryLevelAsWholeBlocks) {
    if (!independentReaderInstalled() || !nvttInstalled())
        HEIGHTPACK_WITHOUT_ORACLE("ktx-parse or libnvtt-bin is not installed: run scripts/test.sh");
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(64, 16, smoothWave), OIIO::TypeDesc::UINT16);
    struct Run {
        std::vector<std::string> args;
        std::string file, format;
        int blockBytes;
    };
    const std::vector<Run> runs = {
        {{"pack", dir.file("map.png"), "--layout", "plain", "--pixel-type", "bc4"}, "h.ktx2", "VK_FORMAT_BC4_UNORM_BLOCK", 8},
        {{"pack", dir.file("map.png"), "--layout", "plain", "--pixel-type", "bc4", "--compression", "zstd"}, "hz.ktx2",
         "VK_FORMAT_BC4_UNORM_BLOCK", 8},
        {{"pack", dir.file("map.png"), "--layout", "plain", "--pixel-type", "bc4"}, "h.dds", "DXGI_FORMAT_BC4_UNORM", 8},
        {{"normal", dir.file("map.png"), "--tile-size", "8m", "--height", "0.5m", "--layout", "xy", "--pixel-type", "bc5"},
         "n.ktx2", "VK_FORMAT_BC5_UNORM_BLOCK", 16},
        {{"normal", dir.file("map.png"), "--tile-size", "8m", "--height", "0.5m", "--layout", "xy", "--pixel-type", "bc5"},
         "n.dds", "DXGI_FORMAT_BC5_UNORM", 16},
    };
    for (Run run : runs) {
        run.args.insert(run.args.end(), {"-o", dir.file(run.file), "--quiet"});
        const ProcessResult r = heightpackRun(run.args);
        ASSERT_EQ(r.code, 0) << run.file << ": " << r.err;
        const json j = readIndependently(dir.file(run.file));
        EXPECT_EQ(j["format"], run.format) << run.file;
        ASSERT_EQ(j["levelCount"], 7) << run.file;  // 64x16 down to 1x1
        for (int level = 0; level < 7; ++level) {
            const int w = std::max(1, 64 >> level), h = std::max(1, 16 >> level);
            // Levels under a block's side are still whole 4x4 blocks.
            EXPECT_EQ(j["levels"][level]["byteLength"], ((w + 3) / 4) * ((h + 3) / 4) * run.blockBytes) << run.file << " " << level;
        }
        if (j["reader"] == "ktx-parse") {
            EXPECT_EQ(j["typeSize"], 1);
            EXPECT_EQ(j["dfd"]["colorModel"], run.blockBytes == 8 ? 131 : 132);  // KHR_DF_MODEL_BC4 / BC5
            EXPECT_EQ(j["dfd"]["bytesPlane0"], run.blockBytes);
            EXPECT_EQ(j["dfd"]["texelBlockDimension"], json::array({3, 3, 0, 0}));
            EXPECT_EQ(j["dfd"]["samples"].size(), size_t(run.blockBytes / 8));
            EXPECT_EQ(j["dfd"]["samples"][0]["bitLength"], 63);
            EXPECT_TRUE(j["keyValues"].contains("heightpack:rmsError")) << run.file;
            if (run.blockBytes == 16) {
                EXPECT_TRUE(j["keyValues"].contains("heightpack:angleError")) << run.file;
            }
        }
    }
}

// Values: heightpack's reader decodes every level of what it wrote as nvdecompress does (within the one
// code nvdecompress's integer arithmetic may round away), and the worst error the file records for
// level 0 is what nvdecompress's decode makes against the painted values.
TEST(BlockFormats, DecodedValuesAgreeWithNvdecompress) {
    if (!independentReaderInstalled() || !nvttInstalled())
        HEIGHTPACK_WITHOUT_ORACLE("ktx-parse or libnvtt-bin is not installed: run scripts/test.sh");
    ScratchDir dir;
    const Image painted = makeImage(64, 32, [](int x, int y) { return std::round(255 * smoothWave(x, y)) / 255.0f; });
    writeImage(dir.file("map.png"), painted, OIIO::TypeDesc::UINT8);
    ASSERT_EQ(heightpackRun({"pack", dir.file("map.png"), "--layout", "plain", "--pixel-type", "bc4", "-o",
                             dir.file("h.ktx2"), "--quiet"}).code, 0);
    ASSERT_EQ(heightpackRun({"normal", dir.file("map.png"), "--tile-size", "8m", "--height", "2m", "--layout", "xy",
                             "--pixel-type", "bc5", "-o", dir.file("n.dds"), "--quiet"}).code, 0);
    for (const std::string file : {"h.ktx2", "n.dds"}) {
        const bool bc5 = file == "n.dds";
        const json j = readIndependently(dir.file(file));
        auto ours = readGpuTexture(dir.file(file));
        ASSERT_TRUE(ours.ok()) << file;
        ASSERT_TRUE(ours->normalisation.has_value());
        const Normalisation n = *ours->normalisation;
        ASSERT_EQ(j["levels"].size(), ours->levels.size());
        for (size_t level = 0; level < ours->levels.size(); ++level) {
            const Image& read = ours->levels[level];
            const Image nv = nvDecode(dir, "level" + std::to_string(level), read.width, read.height, bc5,
                                      hexBytes(j["levels"][level]["blocks"].get<std::string>()));
            ASSERT_EQ(nv.width, read.width);
            double worst = 0.0;
            for (size_t t = 0; t < read.texelCount(); ++t)
                for (int c = 0; c < read.channels; ++c) {
                    const double code = (read.pixels[t * read.channels + c] - n.offset) / n.scale * 255.0;
                    worst = std::max(worst, std::fabs(code - nv.pixels[t * 2 + size_t(c)]));
                }
            EXPECT_LE(worst, 1.0 + 1e-3) << file << " level " << level;
        }
        if (bc5) continue;
        // Level 0 of the plain chain is the painted map itself: the recorded worst error against it.
        const Image nv = nvDecode(dir, "zero", 64, 32, false, hexBytes(j["levels"][0]["blocks"].get<std::string>()));
        double worst = 0.0;
        for (size_t t = 0; t < painted.texelCount(); ++t)
            worst = std::max(worst, std::fabs(n.offset + n.scale * nv.pixels[t * 2] / 255.0 - painted.pixels[t]));
        const std::string recorded = j["keyValues"]["heightpack:lookupError"];
        EXPECT_NEAR(std::stod(recorded.substr(0, recorded.find(','))), worst, n.scale / 255.0 + 1e-6);
    }
}

// Accuracy: on every map of the family, heightpack's BC4 is at least as accurate as nvcompress -bc4 and
// libsquish's kBc4 given the same values (RMS and worst, in units of the map's range: metres once scaled
// by it): the rate of maps where it is worse is 0 against each.
TEST(BlockFormats, Bc4AtLeastAsAccurateAsNvcompressAndSquishOverTheFamily) {
    if (!nvttInstalled()) HEIGHTPACK_WITHOUT_ORACLE("libnvtt-bin (nvcompress, nvdecompress) is not installed");
    if (!HEIGHTPACK_HAVE_SQUISH) HEIGHTPACK_WITHOUT_ORACLE("libsquish-dev was not found when this test was configured");
    ScratchDir dir;
    int rmsWorse = 0, worstWorse = 0, rmsWorseSquish = 0, worstWorseSquish = 0, maps = 0;
    double oursRms = 0, nvRms = 0, squishRms = 0;
    for (const auto& [name, heights] : heightFamily()) {
        const Image unorm = unormOf(heights);
        const std::vector<std::uint8_t> blocks = encodeBlocks(unorm, BlockFormat::Bc4, 0);
        const BlockErrors ours = unormErrors(unorm, rgtcDecode(blocks, unorm.width, unorm.height, 1));
        const BlockErrors nv = unormErrors(unorm, rgtcDecode(nvcompressBlocks(dir, unorm, false), unorm.width, unorm.height, 1));
        const BlockErrors sq = unormErrors(unorm, rgtcDecode(squishBlocks(unorm, false), unorm.width, unorm.height, 1));
        rmsWorse += ours.rms > nv.rms;
        worstWorse += ours.worst > nv.worst + 1e-9;
        rmsWorseSquish += ours.rms > sq.rms;
        worstWorseSquish += ours.worst > sq.worst + 1e-9;
        oursRms += ours.rms, nvRms += nv.rms, squishRms += sq.rms;
        ++maps;
        std::printf("%-50s ours rms %.5f worst %.5f  nvcompress rms %.5f worst %.5f  squish rms %.5f worst %.5f\n", name.c_str(),
                    ours.rms, ours.worst, nv.rms, nv.worst, sq.rms, sq.worst);
    }
    std::printf("bc4 maps %d: worse than nvcompress rms %d worst %d; worse than squish rms %d worst %d\n", maps, rmsWorse,
                worstWorse, rmsWorseSquish, worstWorseSquish);
    EXPECT_GE(maps, 20);
    EXPECT_EQ(rmsWorse, 0) << "of " << maps << " maps";
    EXPECT_EQ(worstWorse, 0) << "of " << maps << " maps";
    EXPECT_EQ(rmsWorseSquish, 0) << "of " << maps << " maps";
    EXPECT_EQ(worstWorseSquish, 0) << "of " << maps << " maps";
    EXPECT_LT(oursRms, nvRms);
    EXPECT_LT(oursRms, squishRms);
}

// BC5 xy normals of those maps, against nvcompress -bc5 and libsquish's kBc5: the components' RMS error
// within 1% of nvcompress's on every map (the encoder gives a little RMS for a smaller worst error, see
// bc4_fit.cpp) and smaller over the family, and the angle between decoded and float normals (z rebuilt),
// median and worst: the rate of maps where heightpack's is larger is 0 against each encoder, for the median
// and for the worst angle (heightpack pairs x and y by the angle; a steep normal's rebuilt z turns an error
// in x or y into a large angle, which encoders fitting each channel alone do not see).
TEST(BlockFormats, Bc5NormalsAtLeastAsAccurateAsNvcompressAndSquishOverTheFamily) {
    if (!nvttInstalled()) HEIGHTPACK_WITHOUT_ORACLE("libnvtt-bin (nvcompress, nvdecompress) is not installed");
    if (!HEIGHTPACK_HAVE_SQUISH) HEIGHTPACK_WITHOUT_ORACLE("libsquish-dev was not found when this test was configured");
    ScratchDir dir;
    int rmsWorse = 0, maps = 0;
    int medianWorse[2] = {0, 0}, worstWorse[2] = {0, 0};  // against nvcompress, squish
    double oursMedians = 0, nvMedians = 0, oursWorst = 0, nvWorst = 0, oursRmsSum = 0, nvRmsSum = 0;
    for (const auto& [name, heights] : heightFamily()) {
        NormalOptions o;
        o.tileWidth = heights.width / 64.0;
        o.heightRange = 0.5;
        const Image normals = generateNormalChain({heights}, o)[0];
        Image xy(normals.width, normals.height, 2);
        for (size_t t = 0; t < xy.texelCount(); ++t)
            for (int c = 0; c < 2; ++c) xy.pixels[t * 2 + c] = normals.pixels[t * normals.channels + c];
        const auto [lo, hi] = std::minmax_element(xy.pixels.begin(), xy.pixels.end());
        const double offset = *lo, scale = std::max(*hi - *lo, 1e-6f);
        const Image unorm = unormOf(xy);
        auto angles = [&](const Image& decoded) {
            std::vector<double> a;
            for (size_t t = 0; t < xy.texelCount(); ++t) {
                const double x0 = xy.pixels[t * 2], y0 = xy.pixels[t * 2 + 1];
                const double x1 = offset + scale * decoded.pixels[t * 2] / 255.0, y1 = offset + scale * decoded.pixels[t * 2 + 1] / 255.0;
                const double z0 = std::sqrt(std::max(0.0, 1 - x0 * x0 - y0 * y0)), z1 = std::sqrt(std::max(0.0, 1 - x1 * x1 - y1 * y1));
                const double dot = (x0 * x1 + y0 * y1 + z0 * z1) / std::sqrt((x0 * x0 + y0 * y0 + z0 * z0) * (x1 * x1 + y1 * y1 + z1 * z1));
                a.push_back(std::acos(std::clamp(dot, -1.0, 1.0)) * 180.0 / M_PI);
            }
            std::sort(a.begin(), a.end());
            return std::pair{a[a.size() / 2], a.back()};
        };
        const Image oursDecoded =
            rgtcDecode(encodeBlocks(unorm, BlockFormat::Bc5, 0, NormalUnits{offset, scale}), unorm.width, unorm.height, 2);
        const Image nvDecoded = rgtcDecode(nvcompressBlocks(dir, unorm, true), unorm.width, unorm.height, 2);
        const Image squishDecoded = rgtcDecode(squishBlocks(unorm, true), unorm.width, unorm.height, 2);
        const auto ours = angles(oursDecoded);
        const std::pair<double, double> others[2] = {angles(nvDecoded), angles(squishDecoded)};
        const double oursRms = unormErrors(unorm, oursDecoded).rms, nvRms = unormErrors(unorm, nvDecoded).rms;
        rmsWorse += oursRms > 1.01 * nvRms;
        for (int k = 0; k < 2; ++k) {
            medianWorse[k] += ours.first > others[k].first;
            worstWorse[k] += ours.second > others[k].second;
        }
        oursRmsSum += oursRms, nvRmsSum += nvRms;
        oursMedians += ours.first, nvMedians += others[0].first, oursWorst += ours.second, nvWorst += others[0].second;
        ++maps;
        std::printf("%-50s ours rms %.5f median %.4f worst %.4f deg  nvcompress rms %.5f median %.4f worst %.4f deg  "
                    "squish median %.4f worst %.4f deg\n",
                    name.c_str(), oursRms, ours.first, ours.second, nvRms, others[0].first, others[0].second,
                    others[1].first, others[1].second);
    }
    std::printf("bc5 maps %d: worse than nvcompress median %d worst %d; worse than squish median %d worst %d\n", maps,
                medianWorse[0], worstWorse[0], medianWorse[1], worstWorse[1]);
    EXPECT_EQ(rmsWorse, 0) << "of " << maps << " maps";
    for (int k = 0; k < 2; ++k) {
        EXPECT_EQ(medianWorse[k], 0) << (k ? "squish" : "nvcompress") << ", of " << maps << " maps";
        EXPECT_EQ(worstWorse[k], 0) << (k ? "squish" : "nvcompress") << ", of " << maps << " maps";
    }
    EXPECT_LT(oursRmsSum, nvRmsSum);
    EXPECT_LT(oursMedians, nvMedians);
    EXPECT_LE(oursWorst, nvWorst);
}

// What cannot be block-compressed says so: exit 2, one line naming what to write instead, nothing written.
TEST(BlockFormats, ImpossiblePairsAreUsageErrorsThatWriteNothing) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
    struct Refusal {
        std::vector<std::string> args;
        std::string says;
    };
    const std::string map = dir.file("map.png");
    const std::vector<Refusal> refusals = {
        {{"pack", map, "--pixel-type", "bc4", "-o", dir.file("p.ktx2")}, "--layout plain"},
        {{"pack", map, "--layout", "plain", "--pixel-type", "bc4", "-o", dir.file("p.exr")}, ".ktx2 or .dds"},
        {{"pack", map, "--layout", "plain", "--pixel-type", "bc5", "-o", dir.file("p.dds")}, "bc4"},
        {{"normal", map, "--tile-size", "8m", "--height", "1m", "--pixel-type", "bc5", "-o", dir.file("n.ktx2")}, "--layout xy"},
        {{"normal", map, "--tile-size", "8m", "--height", "1m", "--layout", "xy", "--pixel-type", "bc4", "-o", dir.file("n.dds")},
         "bc5"},
        {{"fresnel", "--pixel-type", "bc4", "-o", dir.file("f.ktx2")}, "{float,half,uint16}"},
    };
    for (const Refusal& r : refusals) {
        const ProcessResult run = heightpackRun(r.args);
        EXPECT_EQ(run.code, 2) << r.args[0] << " " << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
        EXPECT_NE(run.err.find(r.says), std::string::npos) << run.err;
    }
    EXPECT_EQ(dir.listing(), std::vector<std::string>{"map.png"});
}
