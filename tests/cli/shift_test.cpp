// pack --shift end to end (issue 15, point 3): Dx, Dy kept beside the heights, bit-exact at level 0,
// mip-mapped as the heights are; refused where they cannot be kept; named by manifests and material.json.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "support/exr_levels.hpp"
#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// A float EXR with channels Y, Dx, Dy, as synth --shift writes them.
void writeSea(const std::string& path, const Image& y, const Image& dx, const Image& dy) {
    writeChannels(path, {"Y", "Dx", "Dy"}, {&y, &dx, &dy});
}

const Image kHeights = makeImage(32, 16, [](int x, int y) { return float(0.8 * std::sin(x * 0.39) * std::cos(y * 0.41)); });
const Image kDx = randomImage(32, 16, 7, -1.5f, 1.5f);
const Image kDy = randomImage(32, 16, 8, -0.5f, 0.5f);

}  // namespace

TEST(PackShift, KeepsDxDyBitExactAtLevelZeroPackedAsTheHeights) {
    ScratchDir dir;
    writeSea(dir.file("sea.exr"), kHeights, kDx, kDy);
    const ProcessResult packed = heightpackRun({"pack", dir.file("sea.exr"), "--shift", "--wrap", "clamp", "--json",
                                      "--emit-plain", dir.file("plain.exr"), "-o", dir.file("sea_packed.exr")});
    ASSERT_EQ(packed.code, 0) << packed.err;
    EXPECT_EQ(nlohmann::json::parse(packed.out)["displacement"], "neighbour4");
    const Level top = readLevel(dir.file("sea_packed.exr"), 0);
    ASSERT_EQ(top.names.size(), 12u);
    auto in = OIIO::ImageInput::open(dir.file("sea_packed.exr"));
    EXPECT_EQ(in->spec().get_string_attribute("heightpack:displacement"), "neighbour4");
    EXPECT_EQ(in->spec().get_string_attribute("heightpack:layout"), "neighbour4");
    // Texel (i,j): R = D(i,j), G = D(i+1,j), B = D(i,j+1), A = D(i+1,j+1), clamped at the edges, every bit kept.
    for (const auto& [layer, source] : {std::pair<std::string, const Image*>{"Dx", &kDx}, {"Dy", &kDy}, {"", &kHeights}}) {
        const std::string prefix = layer.empty() ? "" : layer + ".";
        for (int y = 0; y < 16; ++y) {
            for (int x = 0; x < 32; ++x) {
                const int x1 = std::min(x + 1, 31), y1 = std::min(y + 1, 15);
                ASSERT_EQ(top.at(prefix + "R", x, y), source->at(x, y)) << layer << " " << x << "," << y;
                ASSERT_EQ(top.at(prefix + "G", x, y), source->at(x1, y));
                ASSERT_EQ(top.at(prefix + "B", x, y), source->at(x, y1));
                ASSERT_EQ(top.at(prefix + "A", x, y), source->at(x1, y1));
            }
        }
    }
    // The unpacked chain carries them too, as channels Y, Dx, Dy.
    const Level plain = readLevel(dir.file("plain.exr"), 0);
    ASSERT_EQ(plain.names, (std::vector<std::string>{"Y", "Dx", "Dy"}));
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 32; ++x) {
            ASSERT_EQ(plain.at("Dx", x, y), kDx.at(x, y));
            ASSERT_EQ(plain.at("Dy", x, y), kDy.at(x, y));
        }
    // The heights are what pack writes without the displacement, at every level.
    ASSERT_EQ(heightpackRun({"pack", dir.file("sea.exr"), "--wrap", "clamp", "-q", "-o", dir.file("heights.exr")}).code, 0);
    for (int mip = 0; mip < 6; ++mip) {
        const Level with = readLevel(dir.file("sea_packed.exr"), mip), without = readLevel(dir.file("heights.exr"), mip);
        ASSERT_EQ(with.width, without.width);
        for (int y = 0; y < with.height; ++y)
            for (int x = 0; x < with.width; ++x)
                for (const char* c : {"R", "G", "B", "A"}) ASSERT_EQ(with.at(c, x, y), without.at(c, x, y)) << mip;
    }
}

TEST(PackShift, MipLevelsAreTheFiltersOfDxDy) {
    ScratchDir dir;
    writeSea(dir.file("sea.exr"), kHeights, kDx, kDy);
    ASSERT_EQ(heightpackRun({"pack", dir.file("sea.exr"), "--shift", "--filter", "box", "-q", "-o", dir.file("box.exr")}).code, 0);
    // Box: each texel of level 1 is the mean of the 2x2 below it, computed here from the input.
    const Level one = readLevel(dir.file("box.exr"), 1);
    ASSERT_EQ(one.width, 16);
    for (const auto& [layer, source] : {std::pair<std::string, const Image*>{"Dx", &kDx}, {"Dy", &kDy}}) {
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 16; ++x) {
                const double mean = (double(source->at(2 * x, 2 * y)) + source->at(2 * x + 1, 2 * y) +
                                     source->at(2 * x, 2 * y + 1) + source->at(2 * x + 1, 2 * y + 1)) / 4;
                ASSERT_NEAR(one.at(layer + ".R", x, y), mean, 1e-6) << layer << " " << x << "," << y;
            }
    }
    // Kaiser: Dx's chain is the chain pack makes of the same values given as heights.
    writeSea(dir.file("dx_as_heights.exr"), kDx, kDy, kDy);
    ASSERT_EQ(heightpackRun({"pack", dir.file("sea.exr"), "--shift", "-q", "-o", dir.file("kaiser.exr")}).code, 0);
    ASSERT_EQ(heightpackRun({"pack", dir.file("dx_as_heights.exr"), "-q", "-o", dir.file("dx.exr")}).code, 0);
    for (int mip = 1; mip < 6; ++mip) {
        const Level a = readLevel(dir.file("kaiser.exr"), mip), b = readLevel(dir.file("dx.exr"), mip);
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x)
                for (const char* c : {"R", "G", "B", "A"})
                    ASSERT_EQ(a.at(std::string("Dx.") + c, x, y), b.at(c, x, y)) << mip << " " << x << "," << y;
    }
}

TEST(PackShift, RefusesWhatCannotHoldIt) {
    ScratchDir dir;
    writeImage(dir.file("painted.png"), makeImage(16, 16, [](int x, int) { return x / 16.0f; }), OIIO::TypeDesc::UINT8);
    const ProcessResult none = heightpackRun({"pack", dir.file("painted.png"), "--shift", "-o", dir.file("p.exr")});
    EXPECT_EQ(none.code, 3) << none.err;
    EXPECT_EQ(none.err.rfind("heightpack: error: " + dir.file("painted.png") + ": ", 0), 0u) << none.err;
    EXPECT_EQ(std::count(none.err.begin(), none.err.end(), '\n'), 1) << none.err;
    EXPECT_NE(none.err.find("--shift"), std::string::npos) << none.err;  // the hint names the way out
    // A KTX2 or DDS output holds Dx, Dy as array layers: the input is judged the same way.
    for (const char* output : {"s.ktx2", "s.dds"}) {
        const ProcessResult gpu = heightpackRun({"pack", dir.file("painted.png"), "--shift", "-o", dir.file(output)});
        EXPECT_EQ(gpu.code, 3) << gpu.err;
        EXPECT_EQ(std::count(gpu.err.begin(), gpu.err.end(), '\n'), 1) << gpu.err;
    }
    EXPECT_EQ(dir.listing(), (std::vector<std::string>{"painted.png"}));
}

TEST(PackShift, SequencesAndManifestsCarryIt) {
    ScratchDir dir;
    ASSERT_EQ(heightpackRun({"synth", "--wind", "9m/s", "--tile-size", "32m", "--size", "32", "--frames", "2", "--loop", "4s",
                   "--shift", "-q", "-o", dir.file("sea.exr")}).code, 0);
    ASSERT_EQ(heightpackRun({"pack", dir.file("sea.exr"), "--shift", "-q", "-o", dir.file("packed.exr")}).code, 0);
    for (const char* frame : {"packed.0000.exr", "packed.0001.exr"}) {
        auto in = OIIO::ImageInput::open(dir.file(frame));
        ASSERT_TRUE(in) << frame;
        EXPECT_EQ(in->spec().nchannels, 12);
        EXPECT_FLOAT_EQ(in->spec().get_float_attribute("heightpack:loopPeriod"), 4.0f);
    }
    // NAME.####.EXT, as compositing tools spell a sequence (and the issue's example), is NAME.EXT: the
    // same frames read, the same files written (packed.####.exr is packed.0000.exr ...), byte for byte
    // but for the header's source name.
    const ProcessResult hashes = heightpackRun({"pack", dir.file("sea.####.exr"), "--shift", "-q", "-o",
                                      dir.file("hashes.####.exr")});
    ASSERT_EQ(hashes.code, 0) << hashes.err;
    for (const char* frame : {"0000", "0001"}) {
        const Level a = readLevel(dir.file(std::string("packed.") + frame + ".exr"), 1);
        const Level b = readLevel(dir.file(std::string("hashes.") + frame + ".exr"), 1);
        EXPECT_EQ(a.names, b.names);
        EXPECT_EQ(a.pixels, b.pixels) << frame;
    }
    EXPECT_FALSE(std::filesystem::exists(dir.file("hashes.####.exr")));
    EXPECT_FALSE(std::filesystem::exists(dir.file("hashes.0002.exr")));
    // A manifest packs Dx, Dy of a source that has them; choppiness = 0 leaves them out.
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
    const auto choppy = manifest("choppy", "choppiness = 0.75\n");
    EXPECT_EQ(choppy["shift"], true);
    EXPECT_EQ(choppy["choppiness"], 0.75);
    EXPECT_EQ(readLevel(dir.file("choppy/sea.0001.exr"), 0).names.size(), 12u);
    const auto flat = manifest("flat", "choppiness = 0\n");
    EXPECT_FALSE(flat.contains("shift"));
    EXPECT_FALSE(flat.contains("choppiness"));
    EXPECT_EQ(readLevel(dir.file("flat/sea.0000.exr"), 0).names.size(), 4u);
}

// --displacement, the flag's name before it was called shift, still asks for the same thing: synth writes
// channels Dx, Dy with it and pack keeps them, the same bytes as under --shift.
TEST(PackShift, TheOldFlagNameStillWorks) {
    ScratchDir dir;
    for (const char* flag : {"--shift", "--displacement"}) {
        const std::string name = std::string(flag).substr(2);
        const ProcessResult synth = heightpackRun({"synth", "--wind", "9m/s", "--tile-size", "32m", "--size", "16", flag,
                                                   "-q", "-o", dir.file(name + "_sea.exr")});
        ASSERT_EQ(synth.code, 0) << flag << ": " << synth.err;
        auto in = OIIO::ImageInput::open(dir.file(name + "_sea.exr"));
        ASSERT_TRUE(in) << flag;
        std::vector<std::string> channels;
        for (const std::string& c : in->spec().channelnames) channels.push_back(c);
        EXPECT_EQ(channels, (std::vector<std::string>{"Y", "Dx", "Dy"})) << flag;
    }
    EXPECT_EQ(readBytes(dir.file("shift_sea.exr")), readBytes(dir.file("displacement_sea.exr")));
    writeSea(dir.file("sea.exr"), kHeights, kDx, kDy);
    for (const char* flag : {"--shift", "--displacement"}) {
        const ProcessResult packed = heightpackRun({"pack", dir.file("sea.exr"), flag, "-q", "-o",
                                                    dir.file(std::string(flag).substr(2) + ".exr")});
        ASSERT_EQ(packed.code, 0) << flag << ": " << packed.err;
        EXPECT_EQ(readLevel(dir.file(std::string(flag).substr(2) + ".exr"), 0).names.size(), 12u) << flag;
    }
    EXPECT_EQ(readBytes(dir.file("shift.exr")), readBytes(dir.file("displacement.exr")));
}
