// A manifest that bakes a whole sea (issue 15, point 7): [displacement.synth] with shift = true
// A manifest that bakes a whole sea (issue 15, point 7): [displacement.synth] with shift = true
// gives the texture `heightpack synth --shift` then `pack --shift` give (an EXR's layers or
// a KTX2 array's), with foam = true (issue 25) what `synth --foam` then `pack --foam` give, and with
// cascades = N the N tiles of `synth --cascades`, each a layer of material.json at core's tile size. Each
// is checked against the command line run on the same parameters, texel by texel, at every level.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "heightpack/core/sea/cascades.hpp"
#include "heightpack/io/gpu_texture.hpp"

#include "support/exr_levels.hpp"
#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// Two textures hold the same texels in the same channels at every level (bit for bit).
void expectSameTexels(const std::string& built, const std::string& reference) {
    const std::vector<Level> a = readLevels(built), b = readLevels(reference);
    ASSERT_FALSE(a.empty()) << built;
    ASSERT_EQ(a.size(), b.size()) << built;
    for (size_t mip = 0; mip < a.size(); ++mip) {
        ASSERT_EQ(a[mip].names, b[mip].names) << built << " level " << mip;
        ASSERT_EQ(a[mip].width, b[mip].width);
        ASSERT_EQ(a[mip].height, b[mip].height);
        for (size_t i = 0; i < a[mip].pixels.size(); ++i)
            ASSERT_EQ(a[mip].pixels[i], b[mip].pixels[i]) << built << " level " << mip << " value " << i;
    }
}

nlohmann::json material(const std::string& folder) {
    std::ifstream in(folder + "/material.json");
    return nlohmann::json::parse(in);
}

void writeText(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

const std::string kChoppy = R"(format = 1
name = "choppy"

[[displacement]]
name = "sea"
tile_size = 48.0
choppiness = 0.8

[displacement.synth]
spectrum = "jonswap"
wind = 11.0
fetch = 80000.0
direction = 25.0
size = 64
seed = 5
loop = 6.0
frames = 2
shift = true
)";

}  // namespace

// shift = true: each frame's packed EXR holds the heights and Dx, Dy that synth --shift and
// pack --shift make of the same sea, and material.json tells the viewer to draw them choppy.
TEST(SynthManifest, ShiftIsWhatSynthThenPackMake) {
    ScratchDir dir;
    writeText(dir.file("choppy.toml"), kChoppy);
    std::filesystem::create_directory(dir.file("cli"));
    const ProcessResult built = heightpackRun({"build", dir.file("choppy.toml"), "-q", "-o", dir.file("out")});
    ASSERT_EQ(built.code, 0) << built.err;
    ASSERT_EQ(heightpackRun({"synth", "--spectrum", "jonswap", "--wind", "11m/s", "--fetch", "80km", "--direction", "25",
                   "--tile-size", "48m", "--size", "64", "--seed", "5", "--loop", "6s", "--frames", "2", "--shift",
                   "-q", "-o", dir.file("cli/sea.exr")}).code, 0);
    ASSERT_EQ(heightpackRun({"pack", dir.file("cli/sea.exr"), "--shift", "--filter", "kaiser", "--wrap", "periodic", "-q",
                   "-o", dir.file("cli/packed.exr")}).code, 0);
    for (const char* frame : {"0000", "0001"}) {
        const std::string out = dir.file(std::string("out/sea.") + frame + ".exr");
        EXPECT_EQ(readLevels(out).at(0).names.size(), 12u) << "heights, Dx and Dy, four neighbours each";
        expectSameTexels(out, dir.file(std::string("cli/packed.") + frame + ".exr"));
    }
    const nlohmann::json sea = material(dir.file("out"))["displacement"][0];
    EXPECT_EQ(sea["shift"], true);
    EXPECT_EQ(sea["choppiness"], 0.8);
    EXPECT_EQ(sea["loopPeriod"], 6.0);
    EXPECT_EQ(sea["tileSize"], 48.0);

    // A .ktx2 holds them as an array texture: layers heights, Dx, Dy, each level the very bytes pack
    // --shift writes into a .ktx2 of the same sea.
    std::string gpu = kChoppy;
    gpu.replace(gpu.find("choppiness = 0.8"), 16, "output = \"sea.ktx2\"");
    writeText(dir.file("gpu.toml"), gpu);
    const ProcessResult ktx = heightpackRun({"build", dir.file("gpu.toml"), "-q", "-o", dir.file("gpu")});
    ASSERT_EQ(ktx.code, 0) << ktx.err;
    ASSERT_EQ(heightpackRun({"pack", dir.file("cli/sea.exr"), "--shift", "-q", "-o", dir.file("cli/packed.ktx2")}).code, 0);
    for (const char* frame : {"0000", "0001"}) {
        auto built = readGpuTexture(dir.file(std::string("gpu/sea.") + frame + ".ktx2"));
        auto single = readGpuTexture(dir.file(std::string("cli/packed.") + frame + ".ktx2"));
        ASSERT_TRUE(built.ok() && single.ok()) << frame;
        EXPECT_EQ(built->layerNames, (std::vector<std::string>{"heights", "Dx", "Dy"}));
        EXPECT_EQ(built->layerNames, single->layerNames);
        ASSERT_EQ(built->levelBytes.size(), 7u);
        EXPECT_TRUE(built->levelBytes == single->levelBytes) << frame;
    }
    const nlohmann::json choppy = material(dir.file("gpu"))["displacement"][0];
    EXPECT_EQ(choppy["texture"]["file"], "sea.ktx2");
    EXPECT_EQ(choppy["shift"], true);
}

// cascades = 3: three layers sea_c0..2, at the tile sizes core's cascadeBands plans, scrolling at the
// first's metres per second, whose heights are the files synth --cascades writes for the same sea (the
// height offset added once, to the first).
TEST(SynthManifest, CascadesAreLayersOfSynthsTiles) {
    ScratchDir dir;
    writeText(dir.file("cascades.toml"), R"(format = 1
name = "cascades"

[[displacement]]
name = "sea"
tile_size = 100.0
scroll = [0.01, -0.02]
height_offset = 0.5

[displacement.synth]
spectrum = "pierson-moskowitz"
wind = 9.0
size = 32
seed = 4
cascades = 3
)");
    std::filesystem::create_directory(dir.file("cli"));
    const ProcessResult built = heightpackRun({"build", dir.file("cascades.toml"), "-q", "-o", dir.file("out")});
    ASSERT_EQ(built.code, 0) << built.err;
    ASSERT_EQ(heightpackRun({"synth", "--spectrum", "pierson-moskowitz", "--wind", "9m/s", "--tile-size", "100m", "--size", "32",
                   "--seed", "4", "--cascades", "3", "-q", "-o", dir.file("cli/sea.exr")}).code, 0);

    const std::vector<CascadeBand> bands = cascadeBands(100.0, 32, 3, 4);
    const nlohmann::json layers = material(dir.file("out"))["displacement"];
    ASSERT_EQ(layers.size(), 3u) << layers.dump(1);
    for (int c = 0; c < 3; ++c) {
        SCOPED_TRACE("cascade " + std::to_string(c));
        const std::string name = "sea_c" + std::to_string(c);
        const nlohmann::json& layer = layers[c];
        EXPECT_EQ(layer["name"], name);
        EXPECT_EQ(layer["texture"]["file"], name + ".exr");
        EXPECT_DOUBLE_EQ(layer["tileSize"].get<double>(), bands[c].tileSize);
        EXPECT_NEAR(layer["scroll"][0].get<double>() * bands[c].tileSize, 0.01 * 100.0, 1e-12) << "m/s as the first";
        EXPECT_NEAR(layer["scroll"][1].get<double>() * bands[c].tileSize, -0.02 * 100.0, 1e-12);
        const float offset = c == 0 ? 0.5f : 0.0f;
        EXPECT_EQ(layer["heightOffset"], offset);

        // Level 0's R is the height at the texel: synth's, plus the offset as pack adds it.
        const std::vector<Level> packed = readLevels(dir.file("out/" + name + ".exr"));
        const std::vector<Level> synthesised = readLevels(dir.file("cli/" + name + ".exr"));
        ASSERT_FALSE(packed.empty());
        ASSERT_EQ(synthesised.size(), 1u);
        ASSERT_EQ(packed[0].width, 32);
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x)
                ASSERT_EQ(packed[0].at("R", x, y), offset + 1.0f * synthesised[0].at("Y", x, y)) << x << "," << y;
        // The whole chain is what pack makes of synth's file with the same offset.
        ASSERT_EQ(heightpackRun({"pack", dir.file("cli/" + name + ".exr"), "--offset", c == 0 ? "0.5" : "0", "-q", "-o",
                       dir.file("cli/" + name + "_packed.exr")}).code, 0);
        expectSameTexels(dir.file("out/" + name + ".exr"), dir.file("cli/" + name + "_packed.exr"));
    }
    // The tiles' heights have the spectrum once: no two cascades are the same sea.
    EXPECT_NE(readLevels(dir.file("cli/sea_c0.exr"))[0].pixels, readLevels(dir.file("cli/sea_c1.exr"))[0].pixels);
}

// foam = true (issue 25): every frame of the build is, byte for byte and at every level, what `synth
// --shift --foam` at the asset's choppiness and foam options, then `pack --foam` (with
// --shift when shift = true), make of the same sea; and through the Ninja plan, whose
// frames are separate processes sharing the loop, the same bytes again.
TEST(SynthManifest, FoamIsWhatSynthThenPackMake) {
    ScratchDir dir;
    std::string foamy = kChoppy;
    foamy.replace(foamy.find("choppiness = 0.8"), 16, "choppiness = 1.3");
    foamy.replace(foamy.find("frames = 2"), 10, "frames = 3");
    foamy += "foam = true\nfoam_threshold = 0.8\nfoam_decay = 1.5\nfoam_build_up = 5.0\n";
    std::string foamOnly = foamy;
    foamOnly.replace(foamOnly.find("shift = true"), 12, "shift = false");
    writeText(dir.file("foamy.toml"), foamy);
    writeText(dir.file("foam_only.toml"), foamOnly);
    for (const char* folder : {"cli", "cli_foam_only"}) std::filesystem::create_directory(dir.file(folder));
    ASSERT_EQ(heightpackRun({"synth", "--spectrum", "jonswap", "--wind", "11m/s", "--fetch", "80km", "--direction", "25",
                   "--tile-size", "48m", "--size", "64", "--seed", "5", "--loop", "6s", "--frames", "3", "--shift",
                   "--foam", "--choppiness", "1.3", "--foam-threshold", "0.8", "--foam-decay", "1.5s", "--foam-build-up", "5",
                   "-q", "-o", dir.file("cli/sea.exr")}).code, 0);
    ASSERT_EQ(heightpackRun({"pack", dir.file("cli/sea.exr"), "--shift", "--foam", "-q", "-o",
                   dir.file("cli/packed.exr")}).code, 0);
    ASSERT_EQ(heightpackRun({"pack", dir.file("cli/sea.exr"), "--foam", "-q", "-o", dir.file("cli_foam_only/packed.exr")}).code, 0);

    const ProcessResult built = heightpackRun({"build", dir.file("foamy.toml"), "-q", "-o", dir.file("out")});
    ASSERT_EQ(built.code, 0) << built.err;
    const ProcessResult alone = heightpackRun({"build", dir.file("foam_only.toml"), "-q", "-o", dir.file("foam_only")});
    ASSERT_EQ(alone.code, 0) << alone.err;
    float most = 0.0f;
    for (const char* frame : {"0000", "0001", "0002"}) {
        SCOPED_TRACE(frame);
        const std::string name = std::string("sea.") + frame + ".exr", packed = std::string("packed.") + frame + ".exr";
        expectSameTexels(dir.file("out/" + name), dir.file("cli/" + packed));
        EXPECT_EQ(readBytes(dir.file("out/" + name)), readBytes(dir.file("cli/" + packed))) << "the header too";
        expectSameTexels(dir.file("foam_only/" + name), dir.file("cli_foam_only/" + packed));
        EXPECT_EQ(readBytes(dir.file("foam_only/" + name)), readBytes(dir.file("cli_foam_only/" + packed)));
        const std::vector<Level> levels = readLevels(dir.file("out/" + name));
        EXPECT_EQ(levels.at(0).names.size(), 16u) << "heights, Dx, Dy and foam, four neighbours each";
        EXPECT_EQ(readLevels(dir.file("foam_only/" + name)).at(0).names.size(), 8u) << "heights and foam";
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) most = std::max(most, levels[0].at("Foam.R", x, y));
    }
    EXPECT_GT(most, 0.1f) << "a sea with foam, so that the comparison compares some";
    for (const char* folder : {"out", "foam_only"}) {
        EXPECT_EQ(material(dir.file(folder))["displacement"][0]["foam"], true) << folder;
        EXPECT_FALSE(std::filesystem::exists(dir.file(std::string(folder) + "/.heightpack-synth"))) << folder;
    }
    EXPECT_EQ(material(dir.file("out"))["displacement"][0]["shift"], true);
    // Into a .ktx2: one array texture (heights, Dx, Dy, Foam), byte for byte pack's .ktx2 of the same frames.
    std::string gpu = foamy;
    gpu.replace(gpu.find("choppiness = 1.3"), 16, "choppiness = 1.3\noutput = \"sea.ktx2\"");
    writeText(dir.file("gpu.toml"), gpu);
    const ProcessResult ktx = heightpackRun({"build", dir.file("gpu.toml"), "-q", "-o", dir.file("gpu")});
    ASSERT_EQ(ktx.code, 0) << ktx.err;
    ASSERT_EQ(heightpackRun({"pack", dir.file("cli/sea.exr"), "--shift", "--foam", "-q", "-o",
                   dir.file("cli/packed.ktx2")}).code, 0);
    for (const char* frame : {"0000", "0001", "0002"}) {
        const auto array = readGpuTexture(dir.file(std::string("gpu/sea.") + frame + ".ktx2"));
        ASSERT_TRUE(array.ok()) << frame;
        EXPECT_EQ(array->layerNames, (std::vector<std::string>{"heights", "Dx", "Dy", "Foam"}));
        EXPECT_EQ(readBytes(dir.file(std::string("gpu/sea.") + frame + ".ktx2")),
                  readBytes(dir.file(std::string("cli/packed.") + frame + ".ktx2"))) << frame;
    }
    EXPECT_EQ(material(dir.file("gpu"))["displacement"][0]["foam"], true);

    if (runProcess({"ninja", "--version"}).code != 0) HEIGHTPACK_WITHOUT_ORACLE("no ninja to run the plan");
    const ProcessResult plan = heightpackRun({"build", dir.file("foamy.toml"), "-o", dir.file("planned"), "--plan", "ninja"});
    ASSERT_EQ(plan.code, 0) << plan.err;
    writeText(dir.file("plan.ninja"), plan.out);
    const ProcessResult ninja = runProcess({"ninja", "-C", dir.path().string(), "-f", "plan.ninja", "-j", "3"});
    ASSERT_EQ(ninja.code, 0) << ninja.out << ninja.err;
    for (const char* f : {"sea.0000.exr", "sea.0001.exr", "sea.0002.exr", "material.json"})
        EXPECT_EQ(readBytes(dir.file(std::string("planned/") + f)), readBytes(dir.file(std::string("out/") + f))) << f;
    EXPECT_FALSE(std::filesystem::exists(dir.file("planned/.heightpack-synth")));
}

// A bad value of a new key is the manifest's error: one line naming FILE:LINE and the key, exit 3, and
// the outputs of the previous build untouched (tests/bake/manifest_synth_test.cpp has every bad value).
TEST(SynthManifest, BadValuesNameTheKeyAndTouchNothing) {
    ScratchDir dir;
    writeText(dir.file("choppy.toml"), kChoppy);
    ASSERT_EQ(heightpackRun({"build", dir.file("choppy.toml"), "-q", "-o", dir.file("out")}).code, 0);
    const std::vector<unsigned char> before = readBytes(dir.file("out/sea.0001.exr"));
    const std::vector<unsigned char> json = readBytes(dir.file("out/material.json"));
    // Each case replaces a line of kChoppy (line 18 is shift = true) and appends one (line 19).
    const struct {
        std::string from, to, append, key;
        int line;
    } cases[] = {
        {"", "", "cascades = 5", "'displacement[0].synth.cascades'", 19},
        {"shift = true", "displacement = \"yes\"", "", "'displacement[0].synth.displacement'", 18},
    };
    for (const auto& c : cases) {
        std::string text = kChoppy;
        if (!c.from.empty()) text.replace(text.find(c.from), c.from.size(), c.to);
        text += c.append + "\n";
        writeText(dir.file("choppy.toml"), text);
        const ProcessResult r = heightpackRun({"build", dir.file("choppy.toml"), "-q", "-o", dir.file("out")});
        EXPECT_EQ(r.code, 3) << c.key;
        EXPECT_NE(r.err.find(dir.file("choppy.toml") + ":" + std::to_string(c.line) + ":"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(c.key), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_EQ(readBytes(dir.file("out/sea.0001.exr")), before) << c.key;
        EXPECT_EQ(readBytes(dir.file("out/material.json")), json) << c.key;
    }
}
