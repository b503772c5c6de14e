// heightpack-view draws the KTX2 and DDS array textures of `pack --shift --foam` (issue 25): layer 0
// the heights, then Dx, Dy and Foam, each in the file's texel type. A choppy, foamy synthesised sea packed
// into an EXR and into both arrays, in float, half and uint16, is drawn with one camera and time: an
// array draws what the EXR of its type draws, pixel for pixel, and its grid (--grid-heights, the GPU's
// heights and shifts of every vertex) is the EXR's. The EXR's own picture changes when its foam or its
// shift is left out, and its Dx differs from its Dy, so an array whose layers were dropped or swapped fails.
// Plain arrays (--layout plain) give the packed one's grid, and a sequence of arrays blends as the EXRs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "heightpack/io/attributes.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "support/test_support.hpp"
#include "viewer_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

constexpr double kSeaAmplitude = 1.0, kSeaChoppiness = 1.5;
const std::vector<std::string> kSeaTypes = {"float", "half", "uint16"};

// The synthesised sea (64 texels, one frame, foam where the Jacobian of the sea moved by 1.5 D is below 0.8)
// packed into every
// into every container in every pixel type it takes: sea_TYPE.EXT (EXR holds float and half only).
void packSea(const ScratchDir& dir) {
    const ProcessResult synth = runProcess({HEIGHTPACK_EXE, "synth", "--wind", "14m/s", "--tile-size", "32m", "--size", "64",
                                            "--shift", "--foam", "--choppiness", "1.5", "--foam-threshold", "0.8", "-q", "-o",
                                            dir.file("sea.exr")});
    ASSERT_EQ(synth.code, 0) << synth.err;
    for (const std::string& type : kSeaTypes)
        for (const std::string ext : {"exr", "ktx2", "dds"}) {
            if (type == "uint16" && ext == "exr") continue;
            const std::string out = dir.file("sea_" + type + "." + ext);
            const ProcessResult pack = runProcess({HEIGHTPACK_EXE, "pack", dir.file("sea.exr"), "--shift", "--foam",
                                                   "--pixel-type", type, "-q", "-o", out});
            ASSERT_EQ(pack.code, 0) << out << ": " << pack.err;
        }
    // And plain (one channel a layer, packed in the viewer as it packs a plain file's heights), in float.
    for (const std::string ext : {"ktx2", "dds"}) {
        const ProcessResult pack = runProcess({HEIGHTPACK_EXE, "pack", dir.file("sea.exr"), "--shift", "--foam",
                                               "--layout", "plain", "-q", "-o", dir.file("sea_plain." + ext)});
        ASSERT_EQ(pack.code, 0) << pack.err;
    }
}

// The packed sea of packSea, made once in a test program and read by each case that draws it (a synth and
// ten packs, which under the sanitizers cost seconds, were run again for each).
const ScratchDir& packedSea() {
    static const ScratchDir dir;
    static const bool packed = [] {
        packSea(dir);
        return true;
    }();
    (void)packed;
    return dir;
}

// One camera and time, close over the choppy, foamy water; the map at 32 m a tile as synthesised.
std::vector<std::string> viewArgs(const std::string& map, const std::vector<std::string>& extra = {},
                                  double choppiness = kSeaChoppiness) {
    std::vector<std::string> args = {map, "--time", "1", "--camera", "10,6,5,30,-25", "--tile-size", "32", "--amplitude",
                                     std::to_string(kSeaAmplitude), "--choppiness", std::to_string(choppiness)};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

struct ArrayShot {
    Picture picture;
    nlohmann::json gpuBytes;
};

// Drawn headless (EGL): no X server to start for each of the many pictures.
ArrayShot shot(const ScratchDir& dir, const std::string& map, const std::vector<std::string>& extra = {},
               double choppiness = kSeaChoppiness) {
    auto args = viewArgs(dir.file(map), extra, choppiness);
    args.insert(args.end(), {"--size", "240x160", "--json", "--screenshot", dir.file("shot.png")});
    const ViewRun run = viewWithoutDisplay(args);
    EXPECT_EQ(run.code, 0) << map << ": " << run.err;
    ArrayShot s{readPicture(dir.file("shot.png")), {}};
    if (run.code == 0) s.gpuBytes = nlohmann::json::parse(run.out)["gpuBytes"];
    return s;
}

GridHeights grid(const ScratchDir& dir, const std::string& map) {
    auto args = viewArgs(dir.file(map));
    args.insert(args.end(), {"--size", "160x120", "--grid-heights", dir.file("grid.exr")});
    const ViewRun run = viewWithoutDisplay(args);
    EXPECT_EQ(run.code, 0) << map << ": " << run.err;
    return readGridHeights(dir.file("grid.exr"));
}

// The largest difference between two grids' heights, and between their shifts (either component).
struct GridDifference {
    double height = 0, shift = 0;
};

GridDifference differ(const GridHeights& a, const GridHeights& b) {
    GridDifference d;
    EXPECT_EQ(a.heights.size(), b.heights.size());
    EXPECT_FALSE(a.heights.empty());
    for (size_t i = 0; i < std::min(a.heights.size(), b.heights.size()); ++i) {
        d.height = std::max(d.height, double(std::abs(a.heights[i] - b.heights[i])));
        d.shift = std::max({d.shift, double(std::abs(a.shiftX[i] - b.shiftX[i])), double(std::abs(a.shiftY[i] - b.shiftY[i]))});
    }
    return d;
}

}  // namespace

TEST(ViewerArrays, AChoppyFoamySeaDrawsAsItsExrFromEveryArray) {
    const ScratchDir& dir = packedSea();
    std::map<std::string, ArrayShot> exr;
    for (const std::string type : {"float", "half"}) exr[type] = shot(dir, "sea_" + type + ".exr");
    // The picture depends on the foam and on the shift: an array that lost either layer would not match.
    const Difference noFoam = compare(exr["float"].picture, shot(dir, "sea_float.exr", {"--no-baked-foam"}).picture, 2);
    const Difference noShift = compare(exr["float"].picture, shot(dir, "sea_float.exr", {}, 0.0).picture, 2);
    std::printf("without the baked foam %.1f%%, without the shift %.1f%% of the channel values change by more than 2\n",
                100 * noFoam.fractionOver, 100 * noShift.fractionOver);
    EXPECT_GT(noFoam.fractionOver, 0.02);
    EXPECT_GT(noShift.fractionOver, 0.2);
    const nlohmann::json& floatBytes = exr["float"].gpuBytes;
    for (const std::string& type : kSeaTypes) {
        for (const std::string ext : {"ktx2", "dds"}) {
            const std::string map = "sea_" + type + "." + ext;
            const ArrayShot array = shot(dir, map);
            // Float and half against the EXR of their type: the same values on the GPU, the same picture. The
            // EXR's half heights go up as floats, the array's as RGBA16F: each half widens exactly.
            const Difference same = compare(exr[type == "uint16" ? "float" : type].picture, array.picture, 0);
            // Half and uint16 against the float EXR: the types' rounding (heights within 2.4e-4 m and 1.3e-5 m
            // here), which moves a few edges of foam and glints.
            const Difference toFloat = compare(exr["float"].picture, array.picture, 3);
            std::printf("%s: against its type's EXR at most %d; against the float EXR at most %d, %.3f%% over 3\n",
                        map.c_str(), same.max, toFloat.max, 100 * toFloat.fractionOver);
            if (type != "uint16") {
                EXPECT_EQ(same.max, 0) << map;
            }
            EXPECT_LT(toFloat.fractionOver, type == "float" ? 1e-9 : 0.001) << map;
            // Every layer on the GPU in the file's type: half and uint16 take half the bytes of float.
            const int divisor = type == "float" ? 1 : 2;
            for (const char* what : {"packed", "plain", "shift", "foamCoverage"})
                EXPECT_EQ(array.gpuBytes[what].get<long long>() * divisor, floatBytes[what].get<long long>()) << map << " " << what;
        }
    }
    EXPECT_GT(floatBytes["shift"].get<long long>(), 0);
    EXPECT_GT(floatBytes["foamCoverage"].get<long long>(), 0);
}

TEST(ViewerArrays, EveryArraysGridStandsAndShiftsAsItsExrs) {
    const ScratchDir& dir = packedSea();
    const GridHeights exrFloat = grid(dir, "sea_float.exr"), exrHalf = grid(dir, "sea_half.exr");
    // Dx and Dy differ enough that a viewer reading one for the other would fail.
    double largestShift = 0, xy = 0;
    for (size_t i = 0; i < exrFloat.shiftX.size(); ++i) {
        largestShift = std::max(largestShift, double(std::hypot(exrFloat.shiftX[i], exrFloat.shiftY[i])));
        xy = std::max(xy, double(std::abs(exrFloat.shiftX[i] - exrFloat.shiftY[i])));
    }
    EXPECT_GT(largestShift, 0.2);
    EXPECT_GT(xy, 0.2);
    for (const std::string& type : kSeaTypes) {
        // The recorded worst lookup error over every layer and level (a DDS has no room for it: the KTX2
        // of the same type has the same texels). A height is a lookup less the map's mean (its 1x1 level,
        // rounded as well), so it may differ by twice that; a shift is a lookup alone, times choppiness.
        auto ktx2 = readGpuTexture(dir.file("sea_" + type + ".ktx2"));
        ASSERT_TRUE(ktx2);
        const double rounding = type == "float" ? 0.0 : std::stod(findAttribute(ktx2->keyValues, attr::maxLookupError));
        const double heightBound = 2 * kSeaAmplitude * rounding * 1.001 + 1e-6;
        const double shiftBound = kSeaChoppiness * kSeaAmplitude * rounding * 1.001 + 1e-6;
        for (const std::string ext : {"ktx2", "dds"}) {
            const std::string map = "sea_" + type + "." + ext;
            const GridHeights g = grid(dir, map);
            const GridDifference toFloat = differ(exrFloat, g);
            std::printf("%s: heights within %.3g m (bound %.3g), shifts within %.3g m (bound %.3g) of the float EXR's\n",
                        map.c_str(), toFloat.height, heightBound, toFloat.shift, shiftBound);
            EXPECT_LE(toFloat.height, heightBound) << map;
            EXPECT_LE(toFloat.shift, shiftBound) << map;
            if (type == "uint16") continue;
            const GridDifference same = differ(type == "float" ? exrFloat : exrHalf, g);
            EXPECT_EQ(same.height, 0.0) << map << ": the EXR of its type";
            EXPECT_EQ(same.shift, 0.0) << map << ": the EXR of its type";
        }
    }
    for (const std::string map : {"sea_plain.ktx2", "sea_plain.dds"}) {
        const GridDifference d = differ(exrFloat, grid(dir, map));
        EXPECT_EQ(d.height, 0.0) << map << ": packed in the viewer, the values pack wrote";
        EXPECT_EQ(d.shift, 0.0) << map;
    }
}

// A manifest's choppy, foamy sea ([displacement.synth] with displacement and foam) built into .ktx2 and
// .dds arrays opens from its material.json and draws as the same manifest built into an .exr.
TEST(ViewerArrays, AManifestsArraysOpenFromMaterialJsonAndDrawAsItsExr) {
    ScratchDir dir;
    std::map<std::string, GridHeights> grids;
    std::map<std::string, Picture> pictures;
    for (const std::string container : {"exr", "ktx2", "dds"}) {
        const std::string name = "m_" + container;
        std::ofstream(dir.file(name + ".toml"))
            << "format = 1\nname = \"m\"\n[defaults]\ncontainer = \"" << container << "\"\n"
            << "[[displacement]]\nname = \"sea\"\ntile_size = 32.0\nscroll = [0.010, 0.004]\nchoppiness = 1.5\n"
            << "[displacement.synth]\nwind = 14.0\nsize = 64\nseed = 3\nshift = true\nfoam = true\n";
        const ProcessResult built = runProcess({HEIGHTPACK_EXE, "build", dir.file(name + ".toml"), "-q", "-o", dir.file(name)});
        ASSERT_EQ(built.code, 0) << built.err;
        const std::string material = name + "/material.json";
        if (container != "exr") {
            auto texture = readGpuTextureFile(dir.file(name + "/sea." + container));
            ASSERT_TRUE(texture) << texture.error().what;
            EXPECT_EQ(texture->layerNames, (std::vector<std::string>{"heights", "Dx", "Dy", "Foam"})) << container;
        }
        const std::vector<std::string> camera = {"--time", "2", "--camera", "10,6,5,30,-25"};
        auto args = camera;
        args.insert(args.begin(), dir.file(material));
        args.insert(args.end(), {"--size", "160x120", "--grid-heights", dir.file("grid.exr")});
        const ViewRun run = viewWithoutDisplay(args);
        ASSERT_EQ(run.code, 0) << material << ": " << run.err;
        grids[container] = readGridHeights(dir.file("grid.exr"));
        args = camera;
        args.insert(args.begin(), dir.file(material));
        args.insert(args.end(), {"--size", "240x160", "--screenshot", dir.file("shot.png")});
        const ViewRun drawn = viewWithoutDisplay(args);
        ASSERT_EQ(drawn.code, 0) << material << ": " << drawn.err;
        pictures[container] = readPicture(dir.file("shot.png"));
    }
    double largestShift = 0;
    for (size_t i = 0; i < grids["exr"].shiftX.size(); ++i)
        largestShift = std::max(largestShift, double(std::hypot(grids["exr"].shiftX[i], grids["exr"].shiftY[i])));
    EXPECT_GT(largestShift, 0.2) << "material.json's choppiness moves the water sideways";
    for (const std::string container : {"ktx2", "dds"}) {
        const GridDifference g = differ(grids["exr"], grids[container]);
        const Difference p = compare(pictures["exr"], pictures[container], 0);
        std::printf("material in %s: heights within %g m, shifts within %g m, pixels within %d of the EXR's\n",
                    container.c_str(), g.height, g.shift, p.max);
        EXPECT_EQ(g.height, 0.0) << container;
        EXPECT_EQ(g.shift, 0.0) << container;
        EXPECT_EQ(p.max, 0) << container;
    }
}

// A looping sequence of arrays plays as the EXR sequence does: at a time between two frames the grid blends
// both, each decoded with its own file's range (uint16 frames are normalised one by one).
TEST(ViewerArrays, ASequenceOfArraysBlendsItsFramesAsTheExrSequence) {
    ScratchDir dir;
    const ProcessResult synth = runProcess({HEIGHTPACK_EXE, "synth", "--wind", "14m/s", "--tile-size", "32m", "--size", "64",
                                            "--frames", "2", "--loop", "8s", "--shift", "--foam", "-q", "-o",
                                            dir.file("seq.exr")});
    ASSERT_EQ(synth.code, 0) << synth.err;
    for (const std::string out : {"seq_float.exr", "seq_float.ktx2", "seq_uint16.ktx2"}) {
        const std::string type = out.substr(4, out.find('.') - 4);
        const ProcessResult pack = runProcess({HEIGHTPACK_EXE, "pack", dir.file("seq.exr"), "--shift", "--foam",
                                               "--pixel-type", type, "-q", "-o", dir.file(out)});
        ASSERT_EQ(pack.code, 0) << out << ": " << pack.err;
    }
    double rounding = 0;  // the worst recorded lookup error of the uint16 frames
    for (const char* frame : {"seq_uint16.0000.ktx2", "seq_uint16.0001.ktx2"}) {
        auto ktx2 = readGpuTexture(dir.file(frame));
        ASSERT_TRUE(ktx2);
        rounding = std::max(rounding, std::stod(findAttribute(ktx2->keyValues, attr::maxLookupError)));
    }
    // t = 2.5 s of the 8 s loop: 62% of the way from frame 0 to frame 1.
    const auto sequenceGrid = [&](const std::string& sequence) {
        const ViewRun run = viewWithoutDisplay({dir.file(sequence), "--time", "2.5", "--camera", "10,6,5,30,-25", "--tile-size",
                                                "32", "--amplitude", "1", "--choppiness", "1.5", "--size", "160x120",
                                                "--grid-heights", dir.file("grid.exr")});
        EXPECT_EQ(run.code, 0) << sequence << ": " << run.err;
        return readGridHeights(dir.file("grid.exr"));
    };
    const GridHeights exr = sequenceGrid("seq_float.####.exr");
    const GridDifference same = differ(exr, sequenceGrid("seq_float.####.ktx2"));
    const GridDifference uint16 = differ(exr, sequenceGrid("seq_uint16.####.ktx2"));
    std::printf("sequence: float KTX2 within %g m and %g m, uint16 KTX2 within %.3g m and %.3g m (recorded %.3g) of the EXR's\n",
                same.height, same.shift, uint16.height, uint16.shift, rounding);
    EXPECT_EQ(same.height, 0.0);
    EXPECT_EQ(same.shift, 0.0);
    EXPECT_LE(uint16.height, 2 * rounding * 1.001 + 1e-6);
    EXPECT_LE(uint16.shift, 1.5 * rounding * 1.001 + 1e-6);
    EXPECT_GT(uint16.height, 0.0) << "uint16 rounds: a grid equal to the float one would mean the test compared nothing";
}
