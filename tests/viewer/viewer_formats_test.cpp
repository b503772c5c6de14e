// heightpack-view on every container and pixel type heightpack writes: each draws what the float EXR
// draws, within what its type can hold, from textures that keep that type on the GPU; and the gather
// lookup draws what the packed lookup and hardware bilinear filtering draw.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>
#include <tuple>

#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/info.hpp"
#include "heightpack/io/texture_write.hpp"
#include "support/heightpack_process.hpp"
#include "viewer_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// Texels of a full mip chain of a w x h map, down to 1x1.
long long chainTexels(int w, int h) {
    long long n = 0;
    for (;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
        n += static_cast<long long>(w) * h;
        if (w == 1 && h == 1) return n;
    }
}

// Texels of its gather atlas: level 0 with one more column and row; beside it a column as wide as
// level 1 plus one, as tall as the other levels with one more row each (or level 0, if taller).
long long atlasTexels(int w, int h) {
    long long column = 0;
    for (int lw = w / 2, lh = h / 2; lw >= 1 || lh >= 1; lw /= 2, lh /= 2) column += std::max(1, lh) + 1;
    return (w + 1 + w / 2 + 1) * std::max<long long>(h + 1, column);
}

struct Shot {
    Picture picture;
    nlohmann::json bench;
};

// One run: the picture, and what drew it with the GPU bytes of the textures (--json).
Shot shoot(const ScratchDir& dir, const std::string& name, std::vector<std::string> args) {
    args.insert(args.end(), {"--screenshot", dir.file(name), "--json"});
    const ViewRun r = view(args);
    EXPECT_EQ(r.code, 0) << name << ": " << r.err;
    Shot shot;
    shot.picture = readPicture(dir.file(name));
    shot.bench = nlohmann::json::parse(r.out, nullptr, false);
    return shot;
}

}  // namespace

TEST(ViewerFormats, EveryContainerAndPixelTypeDrawsTheHeightsOfTheFloatExr) {
    // The 16-bit swell map (512 x 512 over 64 m) seen from 60 m, 60 degrees down, as grey: trilinear
    // lookups on levels 2 to 3, so every level's storage counts, not level 0's alone.
    ScratchDir dir;
    const std::string map = kExamples + "swell.png";
    heightpackMustRun("pack", {map, "-o", dir.file("f.exr")});
    heightpackMustRun("pack", {map, "-o", dir.file("f.ktx2"), "--emit-plain", dir.file("f_plain.dds")});
    heightpackMustRun("pack", {map, "--pixel-type", "half", "-o", dir.file("h.ktx2"), "--emit-plain", dir.file("h_plain.dds")});
    heightpackMustRun("pack", {map, "--pixel-type", "uint16", "--compression", "zstd", "-o", dir.file("u.ktx2"), "--emit-plain",
                 dir.file("u_plain.ktx2")});
    heightpackMustRun("pack", {map, "--pixel-type", "uint16", "-o", dir.file("u.dds")});
    const std::vector<std::string> common = {"--view", "height", "--size", "160x120", "--time", "2", "--camera",
                                             "0,0,60,0,-60", "--amplitude", "4", "--tile-size", "64", "--grid", "128",
                                             "--segments", "128"};
    auto shot = [&](const std::string& file, const std::string& lookup = "trilinear") {
        std::vector<std::string> args = {dir.file(file), "--lookup", lookup};
        args.insert(args.end(), common.begin(), common.end());
        return shoot(dir, file + "." + lookup + ".png", args);
    };
    const Shot reference = shot("f.exr");
    // Grey = 255 (0.1 + 0.8 (h + 2 m) / 4 m) with h = 4 m (stored - mean): 204 grey levels a stored unit.
    // Half rounds a stored value in [0, 1] by at most 2^-12, the mean subtracted as much again: 0.1 grey
    // level at most, so a pixel differs by at most 1 and only where the float grey lies within 0.1 of a
    // rounding boundary (at most 2 x 0.1 of pixels). 16-bit codes of a unit range round by 2^-17: 0.003
    // levels. Geometry moves by the same 2 mm at most, under 0.01 pixel from 60 m.
    const long long texels = chainTexels(512, 512), atlas = atlasTexels(512, 512);
    struct Case {
        const char* file;
        int bytes;  // per component on the GPU
        double fractionOff;
    };
    // (f.ktx2 is skipped: the same float texels as f.exr through the same upload; its plain DDS is drawn.)
    for (const Case& c : {Case{"f.exr", 4, 0.0}, Case{"f_plain.dds", 4, 0.0}, Case{"h.ktx2", 2, 0.2},
                          Case{"h_plain.dds", 2, 0.2},
                          Case{"u.ktx2", 2, 0.01}, Case{"u_plain.ktx2", 2, 0.01}, Case{"u.dds", 2, 0.01}}) {
        const Shot s = std::string(c.file) == "f.exr" ? reference : shot(c.file);
        const Difference d = compare(reference.picture, s.picture, 0);
        EXPECT_LE(d.max, c.fractionOff > 0 ? 1 : 0) << c.file;
        EXPECT_LE(d.fractionOver, c.fractionOff) << c.file;
        const auto& bytes = s.bench["gpuBytes"];
        EXPECT_EQ(bytes["packed"], texels * 4 * c.bytes) << c.file;
        EXPECT_EQ(bytes["plain"], texels * c.bytes) << c.file;
        EXPECT_EQ(bytes["gather"], atlas * c.bytes) << c.file;
        EXPECT_EQ(bytes["total"], (5 * texels + atlas) * c.bytes) << c.file;
        EXPECT_EQ(s.bench["lookup"], "trilinear") << c.file;
    }
    // Not a blank picture: the waves vary the grey.
    const auto [lo, hi] = std::minmax_element(reference.picture.rgb.begin(), reference.picture.rgb.end());
    EXPECT_GT(*hi - *lo, 40);
}

TEST(ViewerFormats, GatherEqualsThePackedLookupAndHardwareBilinear) {
    ScratchDir dir;
    auto compareLookups = [&](const std::vector<std::string>& common, const std::string& a, const std::string& b) {
        auto first = common, second = common;
        first.insert(first.end(), {"--lookup", a});
        second.insert(second.end(), {"--lookup", b});
        return compare(screenshot(dir, a + ".png", first), screenshot(dir, b + ".png", second), 0);
    };
    // Straight down, then from high above where the far water uses coarse levels.
    const std::vector<std::string> down = {kExamples + "swell.png", "--view", "height", "--size", "160x120", "--time", "3",
                                           "--camera", "0,0,40,0,-89.9", "--amplitude", "4", "--tile-size", "64",
                                           "--grid", "128", "--segments", "128"};
    auto far = down;
    far[8] = "0,0,400,0,-30";
    // The same four texels and the same two lerps as the packed lookup: the same heights.
    for (const auto& [common, name] : {std::pair{down, "bilinear"}, std::pair{far, "trilinear"}}) {
        const Difference d = compareLookups(common, std::string("gather-") + name, name);
        EXPECT_LE(d.max, 1) << name;
        EXPECT_LT(d.fractionOver, 0.001) << name;
    }
    // Against GL_LINEAR on the plain map, as the packed lookup is (the hardware may filter with 8-bit
    // weights; llvmpipe draws the same picture).
    auto linear = down;
    linear.insert(linear.end(), {"--lookup", "reference-bilinear"});
    const Difference hardware = compare(readPicture(dir.file("gather-bilinear.png")), screenshot(dir, "linear.png", linear), 2);
    EXPECT_LE(hardware.max, 4);
    EXPECT_LT(hardware.fractionOver, 0.01);
    // A clamp-wrapped 16-bit map seen past its edges: the atlas's extra column and row hold the clamped
    // neighbours, as the packed texels do.
    heightpackMustRun("pack", {kExamples + "painted_not_tileable.png", "--wrap", "clamp", "--pixel-type", "uint16", "-o",
                 dir.file("clamp.ktx2")});
    const std::vector<std::string> edges = {dir.file("clamp.ktx2"), "--view", "height", "--size", "160x120", "--camera",
                                            "0,0,30,0,-89.9", "--amplitude", "4", "--tile-size", "24", "--grid", "128",
                                            "--segments", "128"};
    const Difference clamped = compareLookups(edges, "gather-trilinear", "trilinear");
    EXPECT_LE(clamped.max, 1);
    EXPECT_LT(clamped.fractionOver, 0.001);
}

TEST(ViewerFormats, GatherWithoutOpenGl4FallsBackToThePackedLookup) {
    // Mesa offers no more than 3.3 here: the 4.0 context is refused, 3.3 draws, gather says so in one line.
    ScratchDir dir;
    const std::vector<std::string> common = {kExamples + "choppy.png", "--view", "height", "--size", "160x120",
                                             "--camera", "0,0,20,0,-60"};
    auto gather = common;
    gather.insert(gather.end(), {"--lookup", "gather", "--screenshot", dir.file("gather.png"), "--json"});
    const ViewRun old = view(gather, {"MESA_GL_VERSION_OVERRIDE=3.3"});
    ASSERT_EQ(old.code, 0) << old.err;
    EXPECT_EQ(old.err,
              "heightpack-view: note: --lookup gather-trilinear: textureGather needs OpenGL 4.0 and this GLX window "
              "context is 3.3; drawing with the packed lookup instead\n");
    const auto j = nlohmann::json::parse(old.out);
    EXPECT_EQ(j["glVersion"].get<std::string>().rfind("3.3", 0), 0u) << j["glVersion"];
    EXPECT_EQ(j["lookup"], "trilinear");
    EXPECT_EQ(j["gpuBytes"]["gather"], 0);
    auto packed = common;
    packed.insert(packed.end(), {"--lookup", "trilinear"});
    EXPECT_EQ(compare(readPicture(dir.file("gather.png")), screenshot(dir, "packed.png", packed), 0).max, 0);
}

TEST(ViewerFormats, NormalMapsAndRampsOfEveryLayoutAndTypeShadeLikeTheFloatExr) {
    ScratchDir dir;
    const std::vector<std::string> normal = {kExamples + "ripple.png", "--tile-size", "8m", "--height", "0.5m"};
    auto normalTo = [&](const std::string& file, const std::string& type) {
        auto args = normal;
        args.insert(args.end(), {"--pixel-type", type, "-o", dir.file(file)});
        heightpackMustRun("normal", args);
    };
    normalTo("n.exr", "float");
    normalTo("n_u.ktx2", "uint16");  // RGBA16 normalised to the map's range: decoded in the shader
    heightpackMustRun("fresnel", {"-o", dir.file("fr.exr")});
    heightpackMustRun("fresnel", {"--pixel-type", "uint16", "-o", dir.file("fr_u.ktx2")});
    // Two-channel normals (x, y; z rebuilt in the shader), written through the library from n.exr's chain.
    auto full = readTextureFile(dir.file("n.exr"));
    ASSERT_TRUE(full) << full.error().what;
    ChainToWrite xy;
    xy.width = full->levels[0].width;
    xy.height = full->levels[0].height;
    xy.channelNames = {"R", "G"};
    xy.attributes = {attribute(attr::layout, "normal"), attribute(attr::convention, NormalConvention::OpenGL)};
    xy.fillRows = [&](int level, int y0, int rows, float* dst) {
        const Image& l = full->levels[size_t(level)];
        for (int y = y0; y < y0 + rows; ++y)
            for (int x = 0; x < l.width; ++x, dst += 2) dst[0] = l.at(x, y, 0), dst[1] = l.at(x, y, 1);
    };
    for (const auto& [file, container, type] : {std::tuple{"n_rg16.ktx2", Container::Ktx2, PixelType::Uint16},
                                                std::tuple{"n_rg16f.dds", Container::Dds, PixelType::Half}}) {
        TextureWriteOptions o;
        o.storage.pixelType = type;
        ASSERT_TRUE(writeTexture({dir.file(file), container}, xy, o));
    }
    const std::vector<std::string> common = {kExamples + "swell.png", "--size", "160x90", "--time", "3", "--camera",
                                             "0,0,6,30,-15", "--grid", "128", "--segments", "128"};
    auto shot = [&](const std::string& normals, const std::string& ramp) {
        auto args = common;
        args.insert(args.end(), {"--normals", dir.file(normals), "--fresnel", dir.file(ramp)});
        return screenshot(dir, normals + "." + ramp + ".png", args);
    };
    const Picture reference = shot("n.exr", "fr.exr");
    // 16-bit codes and halves move a normal's components by 2^-16 and 2^-11 at most, and a ramp's
    // values by as little: a tilt of under a thousandth of a radian, which the 8-bit picture can
    // show only as a step of one level where a pixel sat next to a rounding boundary. (Half normals
    // and heights go through the same RGBA16F upload as the half ramp.)
    struct Case {
        const char *normals, *ramp;
        double fractionOff;
    };
    // (The half ramp is drawn by the material test below; the RG32F map goes through the RG16F upload's
    // code with the float table entry, and is left out to keep the suite short.)
    for (const Case& c : {Case{"n_u.ktx2", "fr_u.ktx2", 0.01}, Case{"n_rg16.ktx2", "fr.exr", 0.01},
                          Case{"n_rg16f.dds", "fr.exr", 0.05}}) {
        const Difference d = compare(reference, shot(c.normals, c.ramp), 0);
        EXPECT_LE(d.max, c.fractionOff > 0 ? 1 : 0) << c.normals << " " << c.ramp;
        EXPECT_LE(d.fractionOver, c.fractionOff) << c.normals << " " << c.ramp;
    }
}

TEST(ViewerFormats, OpensAMaterialWhoseTexturesAreKtx2AndDds) {
    // A built material, and the same material.json naming KTX2 and DDS files made with the same options.
    ScratchDir dir;
    std::ofstream(dir.file("m.toml")) << "format = 1\nname = \"m\"\n[[displacement]]\nname = \"swell\"\nsource = \""
                                      << kExamples << "swell.png\"\ntile_size = 40.0\namplitude = 2.0\n"
                                      << "[normals]\nsource = \"" << kExamples << "ripple.png\"\ntile_size = 8.0\nheight = 0.05\n"
                                      << "[fresnel]\nior = 1.333\n";
    heightpackMustRun("build", {dir.file("m.toml"), "-o", dir.file("m")});
    heightpackMustRun("pack", {kExamples + "swell.png", "--pixel-type", "uint16", "-o", dir.file("m/swell.ktx2")});
    heightpackMustRun("normal", {kExamples + "ripple.png", "--tile-size", "8m", "--height", "0.05m", "--pixel-type", "uint16", "-o",
                   dir.file("m/normals.dds")});
    heightpackMustRun("fresnel", {"--pixel-type", "half", "-o", dir.file("m/fresnel.ktx2")});
    std::stringstream text;
    text << std::ifstream(dir.file("m/material.json")).rdbuf();
    std::string json = text.str();
    for (const auto& [from, to] : {std::pair{"swell.exr", "swell.ktx2"}, std::pair{"normals.exr", "normals.dds"},
                                   std::pair{"fresnel.exr", "fresnel.ktx2"}}) {
        const size_t at = json.find(from);
        ASSERT_NE(at, std::string::npos) << from << " in\n" << json;
        json.replace(at, std::string(from).size(), to);
    }
    std::ofstream(dir.file("m/material_gpu.json")) << json;
    const std::vector<std::string> shot = {"--size", "160x90", "--time", "5", "--camera", "0,0,6,30,-15", "--grid", "128",
                                           "--segments", "128"};
    auto exr = shot, gpu = shot;
    exr.insert(exr.begin(), dir.file("m/material.json"));
    gpu.insert(gpu.begin(), dir.file("m/material_gpu.json"));
    // 16-bit heights (2^-17 of a unit range) and normals, half ramp: as in the test above.
    const Difference d = compare(screenshot(dir, "exr.png", exr), screenshot(dir, "gpu.png", gpu), 0);
    EXPECT_LE(d.max, 1);
    EXPECT_LT(d.fractionOver, 0.05);
}

// A manifest's block formats (issue 39): plain heights in bc4 (astc-6x6) and xy normals in bc5 (astc-6x6),
// built by heightpack build, draw the picture of the same material with float plain heights and xy normals,
// far closer than the picture of another sea; heights read as packed, or not read, would draw another sea.
TEST(ViewerFormats, AManifestsBlockCompressedMaterialDrawsItsFloatPicture) {
    ScratchDir dir;
    auto material = [&](const std::string& name, const std::string& heights, const std::string& normals,
                        const std::string& source = "swell.png") {
        std::ofstream(dir.file(name + ".toml"))
            << "format = 1\nname = \"m\"\n[defaults]\ncontainer = \"ktx2\"\n[[displacement]]\nname = \"swell\"\nsource = \""
            << kExamples << source << "\"\ntile_size = 40.0\namplitude = 2.0\nlayout = \"plain\"\n" << heights << "\n"
            << "[normals]\nsource = \"" << kExamples << "ripple.png\"\ntile_size = 8.0\nheight = 0.05\nlayout = \"xy\"\n"
            << normals << "\n";
        heightpackMustRun("build", {dir.file(name + ".toml"), "-o", dir.file(name)});
        return std::vector<std::string>{dir.file(name + "/material.json"), "--size", "160x90", "--time", "5", "--camera",
                                        "0,0,6,30,-15", "--grid", "128", "--segments", "128"};
    };
    const Picture floats = screenshot(dir, "float.png", material("float", "", ""));
    // Another sea under the same normals: how far apart pictures of different heights are.
    const Picture other = screenshot(dir, "other.png", material("other", "", "", "choppy.png"));
    const Difference waves = compare(floats, other, 8);
    EXPECT_GT(waves.fractionOver, 0.2) << "the heights show in the picture";
    for (const auto& [heights, normals] : {std::pair{"bc4", "bc5"}, std::pair{"astc-6x6", "astc-6x6"}}) {
        SCOPED_TRACE(heights);
        const Picture blocks = screenshot(dir, std::string(heights) + ".png",
                                          material(heights, std::string("pixel_type = \"") + heights + "\"",
                                                   std::string("pixel_type = \"") + normals + "\""));
        const Difference d = compare(floats, blocks, 8);
        std::printf("%s heights, %s normals: %.4f of pixels differ by more than 8 from the float picture (max %d); "
                    "another sea: %.4f\n", heights, normals, d.fractionOver, d.max, waves.fractionOver);
        EXPECT_LT(d.fractionOver, 0.25 * waves.fractionOver) << "max " << d.max;
    }
}
