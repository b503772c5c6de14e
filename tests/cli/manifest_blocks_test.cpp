// Block formats from a manifest (issue 39): `layout` and `pixel_type = "bc4"` (bc5, astc-NxN), or "auto"
// with allow_block_compression, built by `heightpack build` from real corpus maps. Judged by other programs
// than heightpack: the files' structure and blocks by the independent reader (ktx-parse), BC4/BC5 blocks
// decoded by a decoder written here from the Khronos Data Format Specification's RGTC table, ASTC blocks by
// ARM's astcenc -dl; each decoded level is compared with the float chain the same manifest writes with
// pixel_type "float", and the CPU sampler of each material with bilinear filtering done here. Pairs that
// cannot be are refused before anything is written.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "heightpack/bake/material_sampler.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "support/heightpack_process.hpp"
#include "support/block_oracles.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
using nlohmann::json;

namespace manifest_blocks_test {

const std::vector<std::string> kMaps = {"trigger_mud_heightmap.png", "trigger_grass_heightmap.png",
                                        "trigger_greenland_heightmap.png"};

std::string corpus(const std::string& name) { return std::string(HEIGHTPACK_SOURCE_DIR) + "/tests/corpus/" + name; }

constexpr double kHalfRounding = 1.0 / 4096.0;

double angleDegrees(double x0, double y0, double x1, double y1) {
    const double z0 = std::sqrt(std::max(0.0, 1 - x0 * x0 - y0 * y0)), z1 = std::sqrt(std::max(0.0, 1 - x1 * x1 - y1 * y1));
    const double dot = (x0 * x1 + y0 * y1 + z0 * z1) / std::sqrt((x0 * x0 + y0 * y0 + z0 * z0) * (x1 * x1 + y1 * y1 + z1 * z1));
    return std::acos(std::clamp(dot, -1.0, 1.0)) * 180.0 / M_PI;
}

// A material of one corpus map: plain heights and xy normals, stored as heights / normals say.
std::string manifestText(const std::string& map, const std::string& heights, const std::string& normals) {
    return "format = 1\nname = \"sea\"\n[defaults]\ntileable = false\ncontainer = \"ktx2\"\n"
           "[[displacement]]\nname = \"swell\"\nsource = \"" + corpus(map) + "\"\ntile_size = 64.0\namplitude = 2.0\n"
           "layout = \"plain\"\n" + heights + "\n"
           "[normals]\nsource = \"" + corpus(map) + "\"\ntile_size = 8.0\nheight = 0.5\nlayout = \"xy\"\n" + normals + "\n";
}

// Builds text as OUT/NAME/material.json; the build must succeed.
std::string buildMaterial(const ScratchDir& dir, const std::string& name, const std::string& text) {
    std::ofstream(dir.file(name + ".toml"), std::ios::binary) << text;
    const ProcessResult r = heightpackRun({"build", dir.file(name + ".toml"), "-o", dir.file(name), "--quiet"});
    EXPECT_EQ(r.code, 0) << name << ": " << r.err;
    return dir.file(name);
}

json readJson(const std::string& path) {
    std::ifstream in(path);
    return json::parse(in, nullptr, false);
}

struct Decoded {
    std::vector<Image> levels;  // stored values (heights) or x, y (normals), level 0 first
    std::vector<double> worst;  // as the file records them: lookupError (heights) or angleError (normals)
};

// The levels of a block-compressed KTX2, decoded independently and mapped back through its normalisation.
Decoded decodeBlocks(const ScratchDir& dir, const std::string& file, const std::string& type, int channels) {
    const json j = readIndependently(file);
    Decoded d;
    if (j.is_null()) return d;
    const double offset = std::stod(j["keyValues"]["heightpack:normalisedOffset"].get<std::string>());
    const double scale = std::stod(j["keyValues"]["heightpack:normalisedScale"].get<std::string>());
    const char* recorded = channels == 1 ? "heightpack:lookupError" : "heightpack:angleError";
    if (j["keyValues"].contains(recorded)) d.worst = numberList(j["keyValues"][recorded]);  // a DDS records none
    for (const json& level : j["levels"]) {
        const int width = level["width"], height = level["height"];
        Image unorm;
        if (type.rfind("astc", 0) == 0) {
            const Image rgba = astcencDecode(dir, level["blocks"], std::stoi(type.substr(7)), width, height);
            unorm = Image(width, height, channels);
            for (size_t t = 0; t < unorm.texelCount(); ++t)  // heights in R; normals x in R, y in A (KTXswizzle ra01)
                for (int c = 0; c < channels; ++c) unorm.pixels[t * channels + c] = rgba.pixels[t * 4 + (c == 0 ? 0 : 3)];
        } else {
            unorm = rgtcDecode(hexBytes(level["blocks"]), width, height, channels);
            for (float& v : unorm.pixels) v /= 255.0f;
        }
        for (float& v : unorm.pixels) v = float(offset + scale * v);
        d.levels.push_back(std::move(unorm));
    }
    return d;
}

// The float chain's levels as the independent reader gives them.
std::vector<Image> floatLevels(const std::string& file, int channels) {
    const json j = readIndependently(file);
    std::vector<Image> out;
    for (const json& level : j["levels"]) {
        Image image(level["width"], level["height"], channels);
        const std::vector<double> values = level["values"];
        EXPECT_EQ(values.size(), image.pixels.size());
        for (size_t i = 0; i < std::min(values.size(), image.pixels.size()); ++i) image.pixels[i] = float(values[i]);
        out.push_back(std::move(image));
    }
    return out;
}

}  // namespace manifest_blocks_test

using namespace manifest_blocks_test;

// Over the corpus maps, heights in bc4 and astc-6x6 and normals in bc5 and astc-6x6, each decoded level errs
// against the float chain by what the file records (the budget `info` reports), material.json records
// each map's layout and pixel type, and the CPU sampler of each material follows GL_LINEAR filtering of
// the plain heights (the float one to rounding, a block one within its recorded error).
TEST(ManifestBlocks, BlockMapsDecodeWithinTheirRecordedBudgetOverTheCorpus) {
    if (!independentReaderInstalled() || !astcencInstalled())
        HEIGHTPACK_WITHOUT_ORACLE("ktx-parse or astcenc is not installed: run scripts/test.sh");
    ScratchDir dir;
    int levelsJudged = 0, samples = 0;
    for (const std::string& map : kMaps) {
        SCOPED_TRACE(map);
        const std::string floats = buildMaterial(dir, "float", manifestText(map, "", ""));
        const std::vector<Image> heights = floatLevels(floats + "/swell.ktx2", 1);
        const std::vector<Image> normals = floatLevels(floats + "/normals.ktx2", 2);
        ASSERT_FALSE(heights.empty());
        auto floatSampler = loadMaterialSampler(floats + "/material.json");
        ASSERT_TRUE(floatSampler.ok()) << floatSampler.error().what;
        for (const auto& [heightType, normalType] : {std::pair<std::string, std::string>{"bc4", "bc5"}, {"astc-6x6", "astc-6x6"}}) {
            SCOPED_TRACE(heightType);
            const std::string out = buildMaterial(dir, heightType, manifestText(map, "pixel_type = \"" + heightType + "\"",
                                                                               "pixel_type = \"" + normalType + "\""));
            const json material = readJson(out + "/material.json");
            EXPECT_EQ(material["displacement"][0]["layout"], "plain");
            EXPECT_EQ(material["displacement"][0]["texture"]["pixelType"], heightType);
            EXPECT_EQ(material["normals"]["layout"], "xy");
            EXPECT_EQ(material["normals"]["texture"]["pixelType"], normalType);

            const Decoded h = decodeBlocks(dir, out + "/swell.ktx2", heightType, 1);
            ASSERT_EQ(h.levels.size(), heights.size());
            ASSERT_EQ(h.worst.size(), heights.size());
            const Decoded n = decodeBlocks(dir, out + "/normals.ktx2", normalType, 2);
            ASSERT_EQ(n.levels.size(), normals.size());
            ASSERT_EQ(n.worst.size(), normals.size());
            const double range = *std::max_element(heights[0].pixels.begin(), heights[0].pixels.end()) -
                                 *std::min_element(heights[0].pixels.begin(), heights[0].pixels.end());
            const double slack = (heightType == "bc4" ? 1e-6 : kHalfRounding) * range + 1e-6;
            for (size_t level = 0; level < heights.size(); ++level) {
                double most = 0.0, steepest = 0.0;
                for (size_t i = 0; i < heights[level].pixels.size(); ++i)
                    most = std::max(most, double(std::fabs(h.levels[level].pixels[i] - heights[level].pixels[i])));
                for (size_t t = 0; t < normals[level].texelCount(); ++t)
                    steepest = std::max(steepest, angleDegrees(normals[level].pixels[2 * t], normals[level].pixels[2 * t + 1],
                                                               n.levels[level].pixels[2 * t], n.levels[level].pixels[2 * t + 1]));
                EXPECT_NEAR(most, h.worst[level], slack) << "heights level " << level;
                EXPECT_LE(steepest, n.worst[level] + (normalType == "bc5" ? 1e-3 : 0.05)) << "normals level " << level;
                levelsJudged += 2;
            }
            // Eight values evenly between a block's two 8-bit ends: at most a fourteenth of the block's range
            // (a 4x4 block's range within the map's) plus half an 8-bit step of the map's, off.
            if (heightType == "bc4") {
                EXPECT_LE(h.worst[0], range / 14 + range / 510) << "bc4's own bound";
            }

            // H = amplitude * (stored(uv) - the 1x1 level): GL_LINEAR of the plain level 0, done here.
            auto sampler = loadMaterialSampler(out + "/material.json");
            ASSERT_TRUE(sampler.ok()) << sampler.error().what;
            const double mid = heights.back().pixels[0];
            const double budget = 2.0 * (h.worst.front() + h.worst.back()) + 1e-4;
            for (int k = 0; k < 200; ++k) {
                const float x = float(std::fmod(0.37 + 0.731 * k * k, 64.0)), y = float(std::fmod(0.05 + 1.3 * k, 64.0));
                const double expected = 2.0 * (referenceBilinear(heights[0], x / 64.0, y / 64.0, true) - mid);
                EXPECT_NEAR(sampleWaterHeight(*floatSampler, x, y, 0.0f), expected, 1e-4) << x << "," << y;
                EXPECT_NEAR(sampleWaterHeight(*sampler, x, y, 0.0f), expected, budget) << x << "," << y;
                ++samples;
            }
        }
    }
    EXPECT_EQ(levelsJudged, 2 * 2 * 3 * 9);
    EXPECT_EQ(samples, 2 * 3 * 200);
}

// pixel_type = "auto" with allow_block_compression chooses a block format exactly when its worst error over
// the chain (decoded here) is within the tolerance: just over it a DDS (no ASTC) holds bc4, the bytes of
// pixel_type = "bc4"; just under it the choice of "auto" without block formats; material.json records
// what was chosen.
TEST(ManifestBlocks, AutoChoosesABlockFormatExactlyWithinTheTolerance) {
    if (!independentReaderInstalled()) HEIGHTPACK_WITHOUT_ORACLE("ktx-parse is not installed: run scripts/test.sh");
    ScratchDir dir;
    int chosen = 0, passedOver = 0;
    for (const std::string& map : kMaps) {
        SCOPED_TRACE(map);
        auto text = [&](const std::string& storage) {
            return "format = 1\nname = \"sea\"\n[defaults]\ntileable = false\ncontainer = \"dds\"\n"
                   "[[displacement]]\nname = \"swell\"\nsource = \"" + corpus(map) + "\"\ntile_size = 64.0\nlayout = \"plain\"\n" +
                   storage + "\n";
        };
        const std::string floats = buildMaterial(dir, "float", text(""));
        const std::string bc4 = buildMaterial(dir, "bc4", text("pixel_type = \"bc4\""));
        // What auto weighs: the worst error over the chain, of the blocks decoded here.
        const std::vector<Image> heights = floatLevels(floats + "/swell.dds", 1);
        const Decoded decoded = decodeBlocks(dir, bc4 + "/swell.dds", "bc4", 1);
        ASSERT_EQ(decoded.levels.size(), heights.size());
        double chainWorst = 0.0;
        for (size_t level = 0; level < heights.size(); ++level)
            for (size_t i = 0; i < heights[level].pixels.size(); ++i)
                chainWorst = std::max(chainWorst, double(std::fabs(decoded.levels[level].pixels[i] - heights[level].pixels[i])));
        ASSERT_GT(chainWorst, 0.0);
        for (const double factor : {0.9, 1.1}) {
            char tolerance[64];
            std::snprintf(tolerance, sizeof tolerance, "tolerance = %.9g", chainWorst * factor);
            const std::string picked = buildMaterial(dir, "picked", text(std::string("pixel_type = \"auto\"\n") + tolerance +
                                                                         "\nallow_block_compression = true"));
            const json material = readJson(picked + "/material.json");
            const std::string type = material["displacement"][0]["texture"].value("pixelType", "float");
            if (factor > 1.0) {
                EXPECT_EQ(type, "bc4");
                EXPECT_EQ(readBytes(picked + "/swell.dds"), readBytes(bc4 + "/swell.dds"));
                chosen += type == "bc4";
            } else {
                const std::string plainAuto = buildMaterial(dir, "auto", text(std::string("pixel_type = \"auto\"\n") + tolerance));
                EXPECT_NE(type, "bc4");
                EXPECT_EQ(type, readJson(plainAuto + "/material.json")["displacement"][0]["texture"].value("pixelType", "float"));
                passedOver += type != "bc4";
            }
        }
    }
    EXPECT_EQ(chosen, 3);
    EXPECT_EQ(passedOver, 3);
}

// [normals] tolerance = "Xdeg" chooses as normal --tolerance Xdeg does: in a DDS (bc5 its one block format
// for normals) bc5 at 1.1 times bc5's worst angle, measured here from the decoded file against the float
// build, and another type at 0.9 times; every stored normal lies within the angle either way.
TEST(ManifestBlocks, NormalsTakeAToleranceInDegrees) {
    ScratchDir dir;
    int chosen = 0, passedOver = 0;
    for (const std::string& map : kMaps) {
        SCOPED_TRACE(map);
        auto text = [&](const std::string& storage) {
            return "format = 1\nname = \"sea\"\n[defaults]\ntileable = false\ncontainer = \"dds\"\n"
                   "[[displacement]]\nname = \"swell\"\nsource = \"" + corpus(map) + "\"\ntile_size = 64.0\n"
                   "[normals]\nsource = \"" + corpus(map) + "\"\ntile_size = 8.0\nheight = 0.5\nlayout = \"xy\"\n" + storage + "\n";
        };
        const std::string floats = buildMaterial(dir, "float", text(""));
        const double bc5 = worstXyAngleDegrees(buildMaterial(dir, "bc5", text("pixel_type = \"bc5\"")) + "/normals.dds", floats + "/normals.dds");
        ASSERT_GT(bc5, 0.0);
        for (const double factor : {0.9, 1.1}) {
            char tolerance[64];
            std::snprintf(tolerance, sizeof tolerance, "tolerance = \"%.6gdeg\"", bc5 * factor);
            const std::string picked = buildMaterial(dir, "picked", text(std::string("pixel_type = \"auto\"\n") + tolerance +
                                                                         "\nallow_block_compression = true"));
            const std::string type = readJson(picked + "/material.json")["normals"]["texture"].value("pixelType", "float");
            EXPECT_LE(worstXyAngleDegrees(picked + "/normals.dds", floats + "/normals.dds"), bc5 * factor) << type;
            (factor > 1.0 ? chosen : passedOver) += (type == "bc5") == (factor > 1.0);
        }
    }
    EXPECT_EQ(chosen, 3);
    EXPECT_EQ(passedOver, 3);
}

// Changing the layout, the pixel type or allow_block_compression makes the map again.
TEST(ManifestBlocks, LayoutAndBlockSettingsShapeTheOutputKey) {
    ScratchDir dir;
    writeImage(dir.file("a.png"), makeImage(32, 32, [](int x, int y) {
                   return float(0.5 + 0.3 * std::sin(x * 0.19635) * std::cos(y * 0.19635));
               }),
               OIIO::TypeDesc::UINT16);
    auto build = [&](const std::string& storage) {
        std::ofstream(dir.file("m.toml"), std::ios::binary)
            << "format = 1\nname = \"sea\"\n[[displacement]]\nname = \"swell\"\nsource = \"a.png\"\ntile_size = 8.0\n"
               "output = \"swell.ktx2\"\n" + storage + "\n";
        const ProcessResult r = heightpackRun({"build", dir.file("m.toml"), "-o", dir.file("out"), "--json"});
        EXPECT_EQ(r.code, 0) << r.err;
        const json j = json::parse(r.out, nullptr, false);
        int rebuilt = 0;
        for (const json& m : j["materials"])
            for (const json& a : m["assets"]) rebuilt += a["status"] == "rebuilt";
        return rebuilt;
    };
    EXPECT_EQ(build("pixel_type = \"uint16\""), 1);
    EXPECT_EQ(build("pixel_type = \"uint16\""), 0);
    EXPECT_EQ(build("layout = \"plain\"\npixel_type = \"uint16\""), 1) << "the layout";
    EXPECT_EQ(build("layout = \"plain\"\npixel_type = \"bc4\""), 1) << "a block type";
    EXPECT_EQ(build("layout = \"plain\"\npixel_type = \"astc-4x4\""), 1) << "another block type";
    EXPECT_EQ(build("layout = \"plain\"\npixel_type = \"auto\"\ntolerance = 0.01"), 1);
    EXPECT_EQ(build("layout = \"plain\"\npixel_type = \"auto\"\ntolerance = 0.01\nallow_block_compression = true"), 1)
        << "weighing the block formats";
    EXPECT_EQ(build("layout = \"plain\"\npixel_type = \"auto\"\ntolerance = 0.01\nallow_block_compression = true"), 0);
}

// Pairs that cannot be are bad manifests: exit 3, one line naming manifest:line and the key, saying what to
// write instead, and nothing written.
TEST(ManifestBlocks, ImpossiblePairsAreRefusedAtParseTimeWithNothingWritten) {
    ScratchDir dir;
    writeImage(dir.file("a.png"), makeImage(32, 32, [](int x, int y) { return float(0.5 + 0.01 * ((x * 7 + y * 3) % 11)); }),
               OIIO::TypeDesc::UINT8);
    const std::string top = "format = 1\nname = \"sea\"\n";
    const std::string swell = "[[displacement]]\nname = \"swell\"\nsource = \"a.png\"\ntile_size = 8.0\n";
    const std::string head = top + swell;
    const std::string normals = "[normals]\nsource = \"a.png\"\ntile_size = 8.0\nheight = 0.5\n";
    struct Refusal {
        std::string text;
        int line;            // of the key (or table) named
        std::string words;   // in the message
        std::string instead; // in the hint
    };
    const std::vector<Refusal> refusals = {
        {head + "container = \"ktx2\"\npixel_type = \"bc4\"\n", 8, "'displacement[0].pixel_type' is \"bc4\", but its layout is neighbour4",
         "layout = \"plain\""},
        {head + "layout = \"plain\"\npixel_type = \"bc4\"\n", 8, "an EXR", "container = \"ktx2\" or \"dds\""},
        {head + "layout = \"plain\"\ncontainer = \"dds\"\npixel_type = \"astc-6x6\"\n", 9, "DDS, which has no ASTC",
         "pixel_type = \"bc4\""},
        {head + "layout = \"plain\"\noutput = \"s.dds\"\npixel_type = \"bc5\"\n", 9, "bc5 holds two channels", "\"bc4\""},
        {head + "layout = \"rgb\"\n", 7, "must be one of: neighbour4, plain", ""},
        {head + normals + "layout = \"xy\"\ncontainer = \"ktx2\"\npixel_type = \"bc4\"\n", 13, "bc4 holds one channel",
         "pixel_type = \"bc5\""},
        {head + normals + "container = \"ktx2\"\npixel_type = \"bc5\"\n", 12, "its layout is rgb", "layout = \"xy\""},
        {head + normals + "layout = \"xy\"\nalpha = \"height\"\n", 11, "leave no alpha", "alpha = \"none\""},
        {head + "container = \"ktx2\"\npixel_type = \"auto\"\ntolerance = 0.01\nallow_block_compression = true\n", 10,
         "neighbour4, which none can hold", "layout = \"plain\""},
        {head + "layout = \"plain\"\npixel_type = \"auto\"\ntolerance = 0.01\nallow_block_compression = true\n", 10,
         "the output is an EXR", "container = \"ktx2\" or \"dds\""},
        {head + "container = \"ktx2\"\nallow_block_compression = true\n", 8, "pixel_type is not \"auto\"", "pixel_type = \"auto\""},
        {top + "[defaults]\ncontainer = \"ktx2\"\npixel_type = \"bc4\"\n" + swell, 6,
         "[displacement[0]] takes pixel_type from [defaults]", "layout = \"plain\""},
        {head + "[fresnel]\npixel_type = \"bc4\"\n", 8, "a block format, which is for mip-mapped maps", "float, half, uint16"},
    };
    for (const Refusal& r : refusals) {
        SCOPED_TRACE(r.text);
        std::ofstream(dir.file("m.toml"), std::ios::binary) << r.text;
        const ProcessResult run = heightpackRun({"build", dir.file("m.toml"), "-o", dir.file("out")});
        EXPECT_EQ(run.code, 3) << run.err;
        expectOneLineError(run, dir.file("m.toml") + ":" + std::to_string(r.line) + ":");
        EXPECT_NE(run.err.find(r.words), std::string::npos) << run.err;
        EXPECT_NE(run.err.find(r.instead), std::string::npos) << run.err;
        EXPECT_FALSE(std::filesystem::exists(dir.file("out"))) << "nothing written";
    }
}

// A choppy sea (Dx, Dy and foam beside the heights) in the plain layout and a block format: its file holds
// them as further layers, and material.json says so, as it does for a packed one.
TEST(ManifestBlocks, PlainChoppyMapsRecordTheirShiftAndFoam) {
    ScratchDir dir;
    std::ofstream(dir.file("m.toml"), std::ios::binary)
        << "format = 1\nname = \"sea\"\n[defaults]\ncontainer = \"ktx2\"\n"
           "[[displacement]]\nname = \"packed\"\ntile_size = 64.0\nchoppiness = 0.8\npixel_type = \"half\"\n"
           "[displacement.synth]\nwind = 10.0\nsize = 64\nshift = true\nfoam = true\n"
           "[[displacement]]\nname = \"plain\"\ntile_size = 64.0\nchoppiness = 0.8\nlayout = \"plain\"\npixel_type = \"bc4\"\n"
           "[displacement.synth]\nwind = 10.0\nsize = 64\nshift = true\nfoam = true\n";
    const ProcessResult r = heightpackRun({"build", dir.file("m.toml"), "-o", dir.file("out"), "--quiet"});
    ASSERT_EQ(r.code, 0) << r.err;
    const json material = readJson(dir.file("out/material.json"));
    for (const std::string name : {"packed", "plain"}) {
        const json& d = material["displacement"][name == "packed" ? 0 : 1];
        EXPECT_EQ(d["layout"], name == "packed" ? "neighbour4" : "plain");
        EXPECT_EQ(d.value("shift", false), true) << name;
        EXPECT_EQ(d.value("choppiness", 0.0), 0.8) << name;
        EXPECT_EQ(d.value("foam", false), true) << name;
    }
    EXPECT_EQ(material["displacement"][1]["texture"]["pixelType"], "bc4");
}
