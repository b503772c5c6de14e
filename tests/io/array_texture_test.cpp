// KTX2 and DDS array textures (issue 25): pack --shift --foam into a .ktx2 or .dds writes one array
// texture, layers heights, Dx, Dy, Foam, each equal to the EXR layer of the same name that pack writes.
// Read by independent readers only: ktx-parse (npm) for KTX2; for DDS a DX10 decode written here from
// Microsoft's "DDS file layout" and DDS_HEADER_DXT10, and nvddsinfo (Debian's libnvtt-bin) where installed;
// the EXRs by OpenImageIO.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/exr_levels.hpp"
#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
using nlohmann::json;

namespace {

const char* kRgba[] = {"R", "G", "B", "A"};

// An array's levels as a reader gives them: level by level, each layer's image in turn, texel by texel,
// channel by channel; uint16 codes already mapped back through the recorded normalisation.
struct Decoded {
    int layers = 0, channels = 0;
    std::string layerList;  // heightpack:layers as the reader found it
    std::vector<std::vector<double>> levels;
    double unormStep = 0.0;  // uint16: the value of one code (scale / 65535); 0 otherwise
};

// binary16 to double, from IEEE 754's definition.
double halfValue(std::uint16_t h) {
    const double sign = h & 0x8000 ? -1.0 : 1.0;
    const int exponent = (h >> 10) & 0x1f, fraction = h & 0x3ff;
    if (exponent == 0) return sign * std::ldexp(fraction, -24);
    if (exponent == 31) return fraction ? NAN : sign * INFINITY;
    return sign * std::ldexp(1024 + fraction, exponent - 25);
}

// A DDS as Microsoft's layout defines it: magic, the 124-byte DDS_HEADER (height at byte 8, width at 12,
// mip count at 24, dwReserved1 from 28), DDS_HEADER_DXT10 (dxgiFormat, dimension, misc, arraySize), then
// each layer's chain, level 0 first; heightpack's record in dwReserved1 as docs/formats.md documents it.
Decoded decodeDds(const std::string& path) {
    const std::vector<unsigned char> b = readBytes(path);
    Decoded d;
    EXPECT_EQ(le32(b, 0), 0x20534444u) << path;  // "DDS "
    const int height = int(le32(b, 4 + 8)), width = int(le32(b, 4 + 12)), levels = int(le32(b, 4 + 24));
    const std::uint32_t dxgi = le32(b, 128);
    d.layers = int(std::max<std::uint32_t>(1, le32(b, 140)));
    EXPECT_EQ(le32(b, 132), 3u) << "TEXTURE2D";
    const bool f32 = dxgi == 2, f16 = dxgi == 10, u16 = dxgi == 11;  // R32G32B32A32_FLOAT, R16G16B16A16_FLOAT, _UNORM
    EXPECT_TRUE(f32 || f16 || u16) << "DXGI format " << dxgi;
    d.channels = 4;
    const size_t reserved = 4 + 28;
    double offset = 0.0, scale = 1.0;
    if (le32(b, reserved) == 0x4b435048u && le32(b, reserved + 4) == 1) {  // 'HPCK', version 1
        const std::uint32_t flags = le32(b, reserved + 24);
        d.layerList = "heights";
        if (flags & 4) d.layerList += ",Dx,Dy";
        if (flags & 8) d.layerList += ",Foam";
        if (flags & 2) offset = leFloat(b, reserved + 28), scale = leFloat(b, reserved + 32);
    }
    if (u16) d.unormStep = scale / 65535.0;
    d.levels.assign(size_t(levels), {});
    size_t at = 148;
    for (int layer = 0; layer < d.layers; ++layer)
        for (int level = 0; level < levels; ++level) {
            const size_t values = size_t(std::max(1, width >> level)) * std::max(1, height >> level) * 4;
            for (size_t i = 0; i < values; ++i) {
                if (f32) d.levels[size_t(level)].push_back(leFloat(b, at)), at += 4;
                else {
                    const std::uint16_t u = std::uint16_t(b.at(at) | b.at(at + 1) << 8);
                    d.levels[size_t(level)].push_back(f16 ? halfValue(u) : offset + scale * (u / 65535.0));
                    at += 2;
                }
            }
        }
    EXPECT_EQ(at, b.size()) << path << ": bytes after the last level";
    return d;
}

// The independent reader's JSON (read_container.mjs: ktx-parse, or nvddsinfo with its own DX10 decode).
Decoded fromReader(const json& r) {
    Decoded d;
    d.layers = r.value("layerCount", 1);
    d.channels = r["channels"].get<int>();
    const json& kv = r["keyValues"];
    d.layerList = kv.value("heightpack:layers", "");
    const bool u16 = r["format"].get<std::string>().find("UNORM") != std::string::npos;
    double offset = 0.0, scale = 1.0;
    if (u16) {
        offset = std::stod(kv.value("heightpack:normalisedOffset", "0"));
        scale = std::stod(kv.value("heightpack:normalisedScale", "1"));
        d.unormStep = scale / 65535.0;
    }
    for (const json& level : r["levels"]) {
        std::vector<double> values;
        for (const json& v : level["values"]) values.push_back(u16 ? offset + scale * (v.get<double>() / 65535.0) : v.get<double>());
        d.levels.push_back(std::move(values));
    }
    return d;
}

// Every layer of every level equals the EXR's channels of the same layer: bit for bit, or within half a
// uint16 code where the array is 16-bit normalised (the EXR is float then). names: the array's layers.
void expectLayersEqualExr(const Decoded& d, const std::string& exrPath, const std::vector<std::string>& names,
                          const std::string& what) {
    SCOPED_TRACE(what);
    const std::vector<Level> exr = readLevels(exrPath);
    ASSERT_EQ(d.layers, int(names.size()));
    ASSERT_EQ(d.levels.size(), exr.size());
    for (size_t level = 0; level < exr.size(); ++level) {
        const Level& e = exr[level];
        const size_t texels = size_t(e.width) * e.height;
        ASSERT_EQ(d.levels[level].size(), texels * d.channels * d.layers) << "level " << level;
        for (int layer = 0; layer < d.layers; ++layer)
            for (int c = 0; c < d.channels; ++c) {
                // The EXR's name of this layer's channel: R..A of the heights (Y plain), NAME.R.. (NAME plain).
                std::string channel = d.channels == 1 ? (layer == 0 ? "Y" : names[size_t(layer)]) : kRgba[c];
                if (layer > 0 && d.channels > 1) channel = names[size_t(layer)] + "." + channel;
                for (size_t t = 0; t < texels; ++t) {
                    const double mine = d.levels[level][(size_t(layer) * texels + t) * d.channels + size_t(c)];
                    const double want = e.at(channel, int(t % e.width), int(t / e.width));
                    if (d.unormStep > 0.0) ASSERT_NEAR(mine, want, d.unormStep * 0.5 + 1e-6 * std::fabs(want)) << channel;
                    else ASSERT_EQ(mine, want) << channel << " level " << level << " texel " << t;
                }
            }
    }
}

const std::vector<std::string> kAll = {"heights", "Dx", "Dy", "Foam"};

// A sea shaped like synth's output: Y, Dx, Dy, Foam, 32x16 (not square, so a swapped side shows).
std::string writeSea(const ScratchDir& dir) {
    static const Image y = makeImage(32, 16, [](int x, int yy) { return float(0.5 + 0.3 * std::sin(x * 0.39) * std::cos(yy * 0.41)); });
    static const Image dx = randomImage(32, 16, 7, -1.5f, 1.5f), dy = randomImage(32, 16, 8, -0.5f, 0.5f);
    static const Image foam = randomImage(32, 16, 9, 0.0f, 1.0f);
    const std::string path = dir.file("sea.exr");
    writeChannels(path, {"Y", "Dx", "Dy", "Foam"}, {&y, &dx, &dy, &foam});
    return path;
}

void pack(const std::vector<std::string>& args) {
    std::vector<std::string> all = {"pack"};
    all.insert(all.end(), args.begin(), args.end());
    all.push_back("-q");
    const ProcessResult r = heightpackRun(all);
    ASSERT_EQ(r.code, 0) << r.err;
}

bool nvddsinfoInstalled() { return runProcess({"sh", "-c", "command -v nvddsinfo"}).code == 0; }

}  // namespace

TEST(ArrayTextures, Ktx2LayersAreTheExrLayersThroughKtxParse) {
    if (!independentReaderInstalled())
        HEIGHTPACK_WITHOUT_ORACLE("ktx-parse is not installed: run scripts/test.sh (npm install into " << HEIGHTPACK_NPM_DIR << ")");
    ScratchDir dir;
    const std::string sea = writeSea(dir);
    // The EXR references: float and half (an EXR has no uint16: those arrays are judged against float).
    for (const char* type : {"float", "half"})
        pack({sea, "--shift", "--foam", "--pixel-type", type, "-o", dir.file(std::string("ref_") + type + ".exr"),
              "--emit-plain", dir.file(std::string("ref_plain_") + type + ".exr")});
    struct Case {
        std::string type, reference;
        bool zstd;
    };
    for (const Case& c : {Case{"float", "float", false}, Case{"half", "half", false}, Case{"uint16", "float", false},
                          Case{"float", "float", true}, Case{"half", "half", true}}) {
        const std::string name = c.type + (c.zstd ? "_zstd" : "");
        std::vector<std::string> args = {sea, "--shift", "--foam", "--pixel-type", c.type, "-o",
                                         dir.file(name + ".ktx2"), "--emit-plain", dir.file(name + "_plain.ktx2")};
        if (c.zstd) args.insert(args.end(), {"--compression", "zstd"});
        pack(args);
        for (const bool plain : {false, true}) {
            const std::string file = dir.file(name + (plain ? "_plain" : "") + ".ktx2");
            const json r = readIndependently(file);
            ASSERT_FALSE(r.is_null()) << file;
            EXPECT_EQ(r["layerCount"], 4) << file;
            EXPECT_EQ(r["channels"], plain ? 1 : 4) << file;
            EXPECT_EQ(r["keyValues"]["heightpack:layers"], "heights,Dx,Dy,Foam") << file;
            EXPECT_EQ(r["keyValues"]["heightpack:displacement"], plain ? "plain" : "neighbour4") << file;
            EXPECT_EQ(r["keyValues"]["heightpack:foam"], plain ? "plain" : "neighbour4") << file;
            expectLayersEqualExr(fromReader(r), dir.file("ref_" + std::string(plain ? "plain_" : "") + c.reference + ".exr"),
                                 kAll, file);
        }
    }
}

TEST(ArrayTextures, DdsLayersAreTheExrLayersThroughADx10DecodeAndNvddsinfo) {
    ScratchDir dir;
    const std::string sea = writeSea(dir);
    const bool nvdds = nvddsinfoInstalled() && runProcess({"sh", "-c", "command -v node"}).code == 0;
    if (!nvdds) HEIGHTPACK_WITHOUT_ORACLE("nvddsinfo (libnvtt-bin) or node is not installed: run scripts/test.sh");
    for (const char* type : {"float", "half"})
        pack({sea, "--shift", "--foam", "--pixel-type", type, "-o", dir.file(std::string("ref_") + type + ".exr")});
    pack({sea, "--foam", "-o", dir.file("ref_foam.exr")});
    struct Case {
        std::string type, reference, companions;
        std::vector<std::string> layers;
    };
    for (const Case& c : {Case{"float", "ref_float", "both", kAll}, Case{"half", "ref_half", "both", kAll},
                          Case{"uint16", "ref_float", "both", kAll}, Case{"float", "ref_foam", "foam", {"heights", "Foam"}}}) {
        const std::string file = dir.file(c.type + "_" + c.companions + ".dds");
        std::vector<std::string> args = {sea, "--foam", "--pixel-type", c.type, "-o", file};
        if (c.companions == "both") args.push_back("--shift");
        pack(args);
        std::string list;
        for (const std::string& n : c.layers) list += (list.empty() ? "" : ",") + n;
        const Decoded mine = decodeDds(file);
        EXPECT_EQ(mine.layerList, list) << file;
        expectLayersEqualExr(mine, dir.file(c.reference + ".exr"), c.layers, file + " (DX10 decode)");
        if (!nvdds) continue;  // nvddsinfo (libnvtt-bin) absent: the decode above stands alone
        const json r = readIndependently(file);
        ASSERT_FALSE(r.is_null()) << file;
        EXPECT_EQ(r["reader"], "nvddsinfo");
        EXPECT_EQ(r["keyValues"]["heightpack:layers"], list) << file;
        expectLayersEqualExr(fromReader(r), dir.file(c.reference + ".exr"), c.layers, file + " (nvddsinfo)");
    }
}
