// pack --foam end to end (issue 15, point 4): synth's looping foam coverage kept beside the heights, bit-exact
// at level 0, mip-mapped as the heights are; refused where it cannot be kept; named by manifests and
// material.json.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "heightpack/bake/material_sampler.hpp"
#include "support/exr_levels.hpp"
#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// A small choppy sea whose foam covers a good part of it: a threshold of 0.9 on the Jacobian marks every
// texel the waves squeeze by a tenth.
const std::vector<std::string> kSynth = {"synth", "--wind", "14m/s", "--tile-size", "32m", "--size", "32",
                                         "--choppiness", "1.5", "--foam", "--foam-threshold", "0.9", "-q"};

}  // namespace

TEST(PackFoam, KeepsSynthsCoverageBitExactAndItsMipsAreItsBoxMeans) {
    ScratchDir dir;
    auto synth = kSynth;
    synth.insert(synth.end(), {"-o", dir.file("sea.exr")});
    ASSERT_EQ(heightpackRun(synth).code, 0);
    const Level sea = readLevel(dir.file("sea.exr"), 0);
    ASSERT_EQ(sea.width, 32);
    double lo = 1, hi = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) lo = std::min<double>(lo, sea.at("Foam", x, y)), hi = std::max<double>(hi, sea.at("Foam", x, y));
    ASSERT_LT(lo, 0.5 * hi) << "the sea must have foam in some places and less in others";

    const ProcessResult packed = heightpackRun({"pack", dir.file("sea.exr"), "--shift", "--foam", "--filter", "box", "--json",
                                      "--emit-plain", dir.file("plain.exr"), "-o", dir.file("packed.exr")});
    ASSERT_EQ(packed.code, 0) << packed.err;
    EXPECT_EQ(nlohmann::json::parse(packed.out)["foam"], "neighbour4");
    auto in = OIIO::ImageInput::open(dir.file("packed.exr"));
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_string_attribute("heightpack:foam"), "neighbour4");
    // Level 0: Foam.R = F(i,j), G = F(i+1,j), B = F(i,j+1), A = F(i+1,j+1), wrapped (a synthesised sea is
    // periodic), every bit of synth's Foam channel kept; Dx, Dy and the heights are there as without foam.
    const Level top = readLevel(dir.file("packed.exr"), 0);
    ASSERT_EQ(top.names.size(), 16u);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const int x1 = (x + 1) % 32, y1 = (y + 1) % 32;
            ASSERT_EQ(top.at("Foam.R", x, y), sea.at("Foam", x, y)) << x << "," << y;
            ASSERT_EQ(top.at("Foam.G", x, y), sea.at("Foam", x1, y));
            ASSERT_EQ(top.at("Foam.B", x, y), sea.at("Foam", x, y1));
            ASSERT_EQ(top.at("Foam.A", x, y), sea.at("Foam", x1, y1));
            ASSERT_EQ(top.at("Dx.R", x, y), sea.at("Dx", x, y));
            ASSERT_EQ(top.at("R", x, y), sea.at("Y", x, y));
        }
    // Box mips: level m's texel is the mean of the 2^m x 2^m block of level 0 under it, summed here.
    for (const int mip : {1, 3}) {
        const Level level = readLevel(dir.file("packed.exr"), mip);
        const int block = 1 << mip;
        ASSERT_EQ(level.width, 32 / block);
        for (int y = 0; y < level.height; ++y)
            for (int x = 0; x < level.width; ++x) {
                double sum = 0;
                for (int j = 0; j < block; ++j)
                    for (int i = 0; i < block; ++i) sum += sea.at("Foam", x * block + i, y * block + j);
                ASSERT_NEAR(level.at("Foam.R", x, y), sum / (block * block), 1e-6) << mip << " " << x << "," << y;
            }
    }
    // The unpacked twin carries it as channel Foam.
    const Level plain = readLevel(dir.file("plain.exr"), 0);
    ASSERT_EQ(plain.names, (std::vector<std::string>{"Y", "Dx", "Dy", "Foam"}));
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) ASSERT_EQ(plain.at("Foam", x, y), sea.at("Foam", x, y));
}

TEST(PackFoam, RefusesWhatCannotHoldIt) {
    ScratchDir dir;
    // A sea with Dx, Dy but no foam: bad input, exit 3, one line, nothing written.
    ASSERT_EQ(heightpackRun({"synth", "--wind", "9m/s", "--tile-size", "32m", "--size", "16", "--shift", "-q", "-o",
                   dir.file("sea.exr")}).code, 0);
    const ProcessResult none = heightpackRun({"pack", dir.file("sea.exr"), "--foam", "-o", dir.file("p.exr")});
    EXPECT_EQ(none.code, 3) << none.err;
    EXPECT_EQ(none.err.rfind("heightpack: error: " + dir.file("sea.exr") + ": ", 0), 0u) << none.err;
    EXPECT_EQ(std::count(none.err.begin(), none.err.end(), '\n'), 1) << none.err;
    EXPECT_NE(none.err.find("Foam"), std::string::npos) << none.err;
    // A KTX2 or DDS output holds foam as an array layer: the input is judged the same way.
    for (const char* output : {"s.ktx2", "s.dds"}) {
        const ProcessResult gpu = heightpackRun({"pack", dir.file("sea.exr"), "--foam", "-o", dir.file(output)});
        EXPECT_EQ(gpu.code, 3) << gpu.err;
        EXPECT_EQ(std::count(gpu.err.begin(), gpu.err.end(), '\n'), 1) << gpu.err;
    }
    EXPECT_EQ(dir.listing(), (std::vector<std::string>{"sea.exr"}));
}

TEST(PackFoam, ManifestsCarryItAndMaterialJsonSaysSo) {
    ScratchDir dir;
    auto synth = kSynth;
    synth.insert(synth.end(), {"-o", dir.file("sea.exr")});
    ASSERT_EQ(heightpackRun(synth).code, 0);
    auto manifest = [&](const std::string& name, const std::string& extra) {
        std::ofstream(dir.file(name + ".toml")) << "format = 1\nname = \"" << name
                                                << "\"\n[[displacement]]\nname = \"sea\"\nsource = \"sea.exr\"\n"
                                                   "tile_size = 32.0\n"
                                                << extra;
        const ProcessResult b = heightpackRun({"build", dir.file(name + ".toml"), "-q", "-o", dir.file(name)});
        EXPECT_EQ(b.code, 0) << b.err;
        std::ifstream json(dir.file(name + "/material.json"));
        return nlohmann::json::parse(json)["displacement"][0];
    };
    const auto foamy = manifest("foamy", "");
    EXPECT_EQ(foamy["foam"], true);
    EXPECT_EQ(readLevel(dir.file("foamy/sea.exr"), 0).names.size(), 16u);  // heights, Dx, Dy, Foam
    const auto plain = manifest("plain", "foam = false\n");
    EXPECT_FALSE(plain.contains("foam"));
    EXPECT_EQ(readLevel(dir.file("plain/sea.exr"), 0).names.size(), 12u);
    // Without Dx, Dy (choppiness = 0) the texture holds heights and foam: the CPU sampler reads its heights,
    // which are those of the texture built without the foam.
    manifest("foamAlone", "choppiness = 0\n");
    manifest("bare", "choppiness = 0\nfoam = false\n");
    EXPECT_EQ(readLevel(dir.file("foamAlone/sea.exr"), 0).names.size(), 8u);
    auto withFoam = loadMaterialSampler(dir.file("foamAlone/material.json"));
    auto without = loadMaterialSampler(dir.file("bare/material.json"));
    ASSERT_TRUE(withFoam) << withFoam.error().what;
    ASSERT_TRUE(without) << without.error().what;
    for (const float x : {0.3f, 7.9f, 21.4f})
        EXPECT_EQ(sampleWaterHeight(*withFoam, x, 0.7f * x, 1.5f), sampleWaterHeight(*without, x, 0.7f * x, 1.5f)) << x;
}
