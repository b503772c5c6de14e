// Pixel types with an error budget, and layouts, end to end through the heightpack binary:
//  - the worst packed-lookup error each file records (heightpack:lookupError) and pack --json reports
//    equals a brute force written here: a plain double-precision bilinear of the float chain against one
//    from the stored texels as decoded from the file, at 4 x 4 points per texel;
//  - --pixel-type auto picks the fewest bytes within --tolerance (lengths with --height); the refusals
//    of bad choices are in tests/sweep/bad_input_sweep.sh;
//  - --layout plain for heights and xy for normals, read back by heightpack and by the independent
//    readers (ktx-parse; the DDS header record), which agree.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "heightpack/bake/normal_job.hpp"
#include "heightpack/bake/pack_job.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/normal.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/info.hpp"
#include "heightpack/io/read.hpp"
#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
using nlohmann::json;

namespace {

// The packed lookup from design.md, by hand: p = uv * size - 0.5, nearest texel at floor(p) (wrapped or
// clamped), two lerps of its R, G, B, A by frac(p); with clamp p is first kept inside the level.
double packedLookup(const Image& packed, double u, double v, bool periodic) {
    double px = u * packed.width - 0.5, py = v * packed.height - 0.5;
    if (!periodic) {
        px = std::clamp(px, 0.0, double(packed.width - 1));
        py = std::clamp(py, 0.0, double(packed.height - 1));
    }
    const double ix = std::floor(px), iy = std::floor(py);
    const int i = referenceWrap(static_cast<long long>(ix), packed.width, periodic);
    const int j = referenceWrap(static_cast<long long>(iy), packed.height, periodic);
    const double fx = px - ix, fy = py - iy;
    const double r = packed.at(i, j, 0), g = packed.at(i, j, 1), b = packed.at(i, j, 2), a = packed.at(i, j, 3);
    const double top = r + (g - r) * fx, bottom = b + (a - b) * fx;
    return top + (bottom - top) * fy;
}

// Worst |lookup(stored) - lookup(float chain)| over 4 x 4 points per texel: the packed lookup of the
// decoded packed texels, or plain bilinear of the decoded plain texels.
double bruteForceError(const Image& floatLevel, const Image& decoded, bool periodic) {
    double worst = 0.0;
    for (int sy = 0; sy < 4 * floatLevel.height; ++sy)
        for (int sx = 0; sx < 4 * floatLevel.width; ++sx) {
            const double u = (sx / 4.0 + 0.5) / floatLevel.width, v = (sy / 4.0 + 0.5) / floatLevel.height;
            const double stored =
                decoded.channels == 4 ? packedLookup(decoded, u, v, periodic) : referenceBilinear(decoded, u, v, periodic);
            worst = std::max(worst, std::fabs(stored - referenceBilinear(floatLevel, u, v, periodic)));
        }
    return worst;
}

std::vector<double> recordedErrors(const Attributes& attributes) {
    std::vector<double> out;
    std::string text = findAttribute(attributes, "heightpack:lookupError");
    for (size_t at = 0; at < text.size();) {
        const size_t comma = std::min(text.find(',', at), text.size());
        out.push_back(std::stod(text.substr(at, comma - at)));
        at = comma + 1;
    }
    return out;
}

float wave(int x, int y) { return static_cast<float>(0.5 + 0.45 * std::sin(x * 0.37 + 1.0) * std::cos(y * 0.61)); }

// The stored texels of a written file, level by level: heightpack's reader for KTX2 and DDS (checked
// against the independent readers in containers_test), OpenImageIO for EXR.
std::vector<Image> decodedLevels(const std::string& path) {
    auto file = readTextureFile(path);
    EXPECT_TRUE(file.ok()) << (file.ok() ? "" : file.error().what);
    return file.ok() ? file->levels : std::vector<Image>{};
}

}  // namespace

TEST(StoredError, RecordedAndReportedErrorEqualsABruteForceOfTheDecodedTexels) {
    ScratchDir dir;
    struct Map {
        std::string name;
        Image heights;
    };
    const std::vector<Map> maps = {{"wave", makeImage(32, 16, wave)}, {"seed4", randomImage(16, 16, 4)},
                                   {"seed9", randomImage(32, 32, 9, 0.2f, 0.7f)}};
    // Each map, container, wrap and 16-bit type at least once (a process start costs a fifth of a second,
    // so not every combination).
    struct Case {
        size_t map;
        const char* wrap;
        std::string out;
        const char* type;
    };
    const std::vector<Case> cases = {{0, "periodic", "p.ktx2", "half"}, {0, "clamp", "p.dds", "uint16"},
                                     {1, "clamp", "p.exr", "half"}, {2, "periodic", "p.ktx2", "uint16"}};
    for (const Map& m : maps) writeImage(dir.file(m.name + ".png"), m.heights, OIIO::TypeDesc::UINT16);
    for (const Case& c : cases) {
        const Map& m = maps[c.map];
        SCOPED_TRACE(m.name + " " + c.wrap + " " + c.out + " " + c.type);
        auto loaded = loadHeightMap(dir.file(m.name + ".png"));
        ASSERT_TRUE(loaded.ok());
        MipOptions mip;
        mip.wrap = *parseName<Wrap>(c.wrap);
        const std::vector<Image> chain = generateMipChain(loaded->heights, mip);
        const ProcessResult r = heightpackRun({"pack", dir.file(m.name + ".png"), "--wrap", c.wrap, "--pixel-type",
                                               c.type, "--json", "-o", dir.file(c.out), "--emit-plain",
                                               dir.file("plain_" + c.out)});
        ASSERT_EQ(r.code, 0) << r.err;
        const json doc = json::parse(r.out);
        EXPECT_EQ(doc["pixelType"], c.type);
        EXPECT_EQ(doc["lookupError"]["units"], "stored");
        const std::vector<Image> packed = decodedLevels(dir.file(c.out));
        const std::vector<Image> plain = decodedLevels(dir.file("plain_" + c.out));
        ASSERT_EQ(packed.size(), chain.size());
        ASSERT_EQ(plain.size(), chain.size());
        auto file = readTextureFile(dir.file(c.out));
        ASSERT_TRUE(file.ok());
        // A DDS has nowhere to record it; KTX2 and EXR do, per level.
        const std::vector<double> recorded = recordedErrors(file->attributes);
        EXPECT_EQ(recorded.size(), c.out == "p.dds" ? 0u : chain.size());
        double worst = 0.0;
        for (size_t l = 0; l < chain.size(); ++l) {
            const bool periodic = mip.wrap == Wrap::Periodic;
            const double expected = bruteForceError(chain[l], packed[l], periodic);
            EXPECT_NEAR(bruteForceError(chain[l], plain[l], periodic), expected, 1e-12) << "level " << l;
            const double reported = doc["levels"][l]["lookupError"].get<double>();
            EXPECT_NEAR(reported, expected, 1e-9 * expected + 1e-12) << "level " << l;
            if (!recorded.empty()) {
                EXPECT_NEAR(recorded[l], expected, 1e-8 * expected + 1e-12) << "level " << l;
            }
            worst = std::max(worst, expected);
        }
        EXPECT_NEAR(doc["lookupError"]["worst"].get<double>(), worst, 1e-9 * worst + 1e-12);
        EXPECT_GT(worst, 0.0);
    }
}

TEST(StoredError, Uint16OfA16BitPaintedMapIsExactAtLevel0) {
    ScratchDir dir;
    std::vector<float> painted(32 * 32);
    for (size_t i = 0; i < painted.size(); ++i) painted[i] = float((i * 40503u) % 61000 + 1234) / 65535.0f;
    writeImage(dir.file("map.png"), 32, 32, 1, painted, OIIO::TypeDesc::UINT16);
    for (const char* name : {"p.ktx2", "p.dds"}) {
        const ProcessResult r = heightpackRun({"pack", dir.file("map.png"), "--pixel-type", "uint16", "--layout",
                                               "plain", "--json", "-o", dir.file(name)});
        ASSERT_EQ(r.code, 0) << r.err;
        // Every code is the painted one (below); what is left at level 0 is the float rounding of
        // offset + scale * u / 65535, as a shader decodes it: within 4 ulps of the largest height (not
        // 0: the float chain's own values are rounded k / 65535), under 1/30 of a code's step.
        const json doc = json::parse(r.out);
        EXPECT_LE(doc["levels"][0]["lookupError"].get<double>(), 4 * 0x1p-24) << name;
        EXPECT_GT(doc["levels"][1]["lookupError"].get<double>(), 1e-6) << name;  // levels 1+ are quantised
        auto t = readGpuTexture(dir.file(name));
        ASSERT_TRUE(t.ok());
        ASSERT_TRUE(t->normalisation.has_value());
        // Decoded texel == the painted 16-bit value: its code maps back to the same 1/65535 step.
        for (size_t i = 0; i < painted.size(); ++i)
            ASSERT_EQ(std::lround(double(t->levels[0].pixels[i]) * 65535.0), std::lround(double(painted[i]) * 65535.0))
                << name << " texel " << i;
    }
    auto info = readFileInfo(dir.file("p.ktx2"));
    ASSERT_TRUE(info.ok());
    ASSERT_TRUE(info->levels[0].lookupError.has_value());
    EXPECT_LE(*info->levels[0].lookupError, 4 * 0x1p-24);
}

TEST(StoredError, AutoPicksTheFewestBytesWithinTheTolerance) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(32, 32, wave), OIIO::TypeDesc::UINT16);
    // The rule through the library (no process start per case), the CLI's length once at the end.
    auto pack = [&](PixelType type, double tolerance, const std::string& out) {
        PackOptions o;
        o.storage.pixelType = type;
        o.storage.tolerance = tolerance;
        auto r = packHeightMap(dir.file("map.png"), dir.file(out), o);
        EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().what);
        return r.ok() ? *r : PackReport{};
    };
    auto worst = [](const PackReport& r) { return *std::max_element(r.lookupError.begin(), r.lookupError.end()); };
    const double half = worst(pack(PixelType::Half, 0.0, "a.ktx2"));
    const double uint16 = worst(pack(PixelType::Uint16, 0.0, "a.ktx2"));
    ASSERT_GT(half, 1.01 * uint16);  // a 16-bit code is finer than a half's step near 1 on this map
    struct Want {
        double tolerance;
        std::string out;
        PixelType type;
    };
    for (const Want& w : {Want{half * 1.01, "a.ktx2", PixelType::Uint16},  // both within: the smaller error
                          Want{uint16 * 1.01, "a.dds", PixelType::Uint16}, Want{uint16 * 0.5, "a.ktx2", PixelType::Float},
                          Want{1.0, "a.exr", PixelType::Half}}) {  // an EXR has no uint16
        const PackReport r = pack(PixelType::Float, w.tolerance, w.out);
        EXPECT_EQ(r.pixelType, w.type) << w.tolerance << " " << w.out;
        EXPECT_LE(worst(r), w.tolerance);
        auto file = readTextureFile(dir.file(w.out));
        ASSERT_TRUE(file.ok());
        EXPECT_EQ(file->pixelType, pixelTypeName(w.type)) << w.out;
    }
    // The command line: a length with --height is converted to stored units (and reported in metres).
    char tolerance[32];
    std::snprintf(tolerance, sizeof tolerance, "%.6gmm", uint16 * 6.0 * 1000.0 * 1.01);
    const ProcessResult r = heightpackRun({"pack", dir.file("map.png"), "--json", "--height", "6m", "--pixel-type",
                                           "auto", "--tolerance", tolerance, "-o", dir.file("a.ktx2")});
    ASSERT_EQ(r.code, 0) << r.err;
    const json doc = json::parse(r.out);
    EXPECT_EQ(doc["pixelType"], "uint16");
    EXPECT_EQ(doc["pixelTypeRequested"], "auto");
    EXPECT_EQ(doc["lookupError"]["units"], "m");
    EXPECT_NEAR(doc["lookupError"]["worst"].get<double>(), uint16 * 6.0, 1e-9);
}

TEST(Layouts, PlainHeightsAndXyNormalsInEveryContainerAndType) {
    const bool independent = independentReaderInstalled();
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(16, 8, wave), OIIO::TypeDesc::UINT16);
    auto loaded = loadHeightMap(dir.file("map.png"));
    ASSERT_TRUE(loaded.ok());
    const std::vector<Image> heights = generateMipChain(loaded->heights, Filter::Kaiser);
    NormalOptions n;
    n.tileWidth = 8.0;
    n.heightRange = 0.5;
    const std::vector<Image> normals = generateNormalChain(heights, n);
    // Each container and pixel type (an EXR has no uint16) through the library; the flags once each
    // through the command line; the independent readers on one KTX2 and one DDS case.
    struct Case {
        std::string ext, type;
        bool cli, independentReader;
    };
    const std::vector<Case> cases = {{".ktx2", "float", false, false}, {".ktx2", "uint16", true, true},
                                     {".dds", "half", false, true},     {".dds", "uint16", false, false},
                                     {".exr", "half", false, false}};
    for (const Case& c : cases) {
        SCOPED_TRACE(c.ext + " " + c.type);
        const std::string plain = dir.file("plain_" + c.type + c.ext), xy = dir.file("xy_" + c.type + c.ext);
        if (c.cli) {
            ASSERT_EQ(heightpackRun({"pack", dir.file("map.png"), "--layout", "plain", "--pixel-type", c.type, "--quiet",
                                     "-o", plain}).code, 0);
            ASSERT_EQ(heightpackRun({"normal", dir.file("map.png"), "--tile-size", "8m", "--height", "0.5m", "--layout",
                                     "xy", "--pixel-type", c.type, "--quiet", "-o", xy}).code, 0);
        } else {
            PackOptions p;
            p.layout = Layout::Plain;
            p.storage.pixelType = *parsePixelType(c.type);
            ASSERT_TRUE(packHeightMap(dir.file("map.png"), plain, p).ok());
            NormalJobOptions o;
            o.normal = n;
            o.layout = Layout::Xy;
            o.storage.pixelType = p.storage.pixelType;
            ASSERT_TRUE(makeNormalMap(dir.file("map.png"), xy, o).ok());
        }
        for (const auto& [path, layout, channels] :
             {std::tuple<std::string, std::string, int>{plain, "plain", 1}, {xy, "normalXY", 2}}) {
            auto file = readTextureFile(path);
            ASSERT_TRUE(file.ok()) << file.error().what;
            EXPECT_EQ(findAttribute(file->attributes, "heightpack:layout"), layout);
            ASSERT_EQ(file->levels.size(), heights.size());
            EXPECT_EQ(file->levels[0].channels, channels);
            // Values: the chain's heights, or x and y of its normals, to the type's precision.
            const double tolerance = c.type == "float" ? 0.0 : c.type == "half" ? 4.9e-4 : 1.6e-5;
            for (size_t l = 0; l < heights.size(); ++l)
                for (size_t t = 0; t < heights[l].texelCount(); ++t)
                    for (int k = 0; k < channels; ++k) {
                        const double want = channels == 1 ? heights[l].pixels[t] : normals[l].pixels[t * 3 + k];
                        ASSERT_NEAR(file->levels[l].pixels[t * channels + k], want, tolerance) << l << " " << t;
                    }
            // What info reports (the CLI's text is checked once below): GPU bytes and the error.
            auto info = readFileInfo(path);
            ASSERT_TRUE(info.ok());
            const size_t componentBytes = c.type == "float" ? 4 : 2;
            EXPECT_EQ(info->levels[0].gpuBytes, 16 * 8 * channels * componentBytes);
            EXPECT_EQ(info->levels.back().gpuBytes, channels * componentBytes);
            double worst = 0.0;  // a level may happen to store exactly, not the whole chain
            for (const LevelInfo& l : info->levels) {
                if (c.type == "float") {
                    EXPECT_EQ(l.lookupError, 0.0);
                } else if (c.ext == ".dds") {
                    EXPECT_FALSE(l.lookupError.has_value());
                } else {
                    ASSERT_TRUE(l.lookupError.has_value());
                    worst = std::max(worst, *l.lookupError);
                }
            }
            if (c.type != "float" && c.ext != ".dds") {
                EXPECT_GT(worst, 0.0);
            }
            if (!c.independentReader || !independent) continue;
            // The independent reader: the format, the layout, and the same texels.
            const json other = readIndependently(path);
            auto own = readGpuTexture(path);
            ASSERT_TRUE(own.ok());
            const TexelFormatInfo& f = texelFormatInfo(own->format);
            EXPECT_EQ(f.channels, channels);
            EXPECT_EQ(other["format"], c.ext == ".ktx2" ? f.vkName : f.dxgiName);
            EXPECT_EQ(other["keyValues"].value("heightpack:layout", ""), layout);
            ASSERT_EQ(other["levels"].size(), heights.size());
            for (size_t l = 0; l < heights.size(); ++l) {
                const json& values = other["levels"][l]["values"];
                ASSERT_EQ(values.size(), own->levels[l].pixels.size());
                for (size_t i = 0; i < values.size(); ++i) {
                    double v = values[i].get<double>();
                    if (f.kind == ComponentKind::Unorm16)
                        v = own->normalisation->offset + own->normalisation->scale * (v / 65535.0);
                    ASSERT_NEAR(v, own->levels[l].pixels[i], 1e-6) << l << " " << i;
                }
            }
        }
    }
    const ProcessResult info = heightpackRun({"info", dir.file("xy_uint16.ktx2"), "--json"});
    ASSERT_EQ(info.code, 0) << info.err;
    const json doc = json::parse(info.out);
    EXPECT_EQ(doc["layout"], "normalXY");
    EXPECT_EQ(doc["levels"][0]["gpuBytes"], 16 * 8 * 2 * 2);
    EXPECT_EQ(doc["gpuBytes"], (16 * 8 + 8 * 4 + 4 * 2 + 2 * 1 + 1 * 1) * 2 * 2);
    EXPECT_EQ(doc["lookupError"]["units"], "normal");
    EXPECT_GT(doc["lookupError"]["worst"].get<double>(), 0.0);
    if (!independent) HEIGHTPACK_WITHOUT_ORACLE("the independent readers are not installed: run scripts/test.sh");
}
