// ASTC on the GPU (the BlockUpload suite, beside BC4/BC5's): Mesa's own ASTC decoder (llvmpipe offers
// GL_KHR_texture_compression_astc_ldr; in this process through EGL) as an independent judge of the blocks
// heightpack writes, heightpack-view drawing ASTC heights and normals uploaded as their blocks as the float
// maps draw, within what the recorded errors allow, and a context without ASTC refused with exit 5.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

#include "headless_context.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/info.hpp"
#include "support/heightpack_process.hpp"
#include "viewer_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

// A named namespace: the viewer suites are compiled as one unity file, beside block_upload_test's helpers.
namespace astc_upload {

constexpr GLenum kAstc4x4 = 0x93B0, kAstc6x6 = 0x93B4, kAstc8x8 = 0x93B7;  // GL_COMPRESSED_RGBA_ASTC_NxN_KHR

bool contextHasAstc() {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i)
        if (std::string(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)))) ==
            "GL_KHR_texture_compression_astc_ldr")
            return true;
    return false;
}

// Level `level` of the file's blocks as the GPU decodes them: uploaded as they are, read back as RGBA floats.
std::vector<float> gpuAstcDecode(const GpuTexture& t, int level) {
    const PixelType type = pixelTypeOf(t.format);
    const GLenum format = type == PixelType::Astc4x4 ? kAstc4x4 : type == PixelType::Astc6x6 ? kAstc6x6 : kAstc8x8;
    const int w = std::max(1, t.width >> level), h = std::max(1, t.height >> level);
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glCompressedTexImage2D(GL_TEXTURE_2D, 0, format, w, h, 0, GLsizei(t.levelBytes[size_t(level)].size()),
                           t.levelBytes[size_t(level)].data());
    std::vector<float> rgba(size_t(w) * h * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, rgba.data());
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    glDeleteTextures(1, &texture);
    return rgba;
}

double angleDegrees(const double* a, const double* b) {
    auto z = [](const double* v) { return std::sqrt(std::max(0.0, 1.0 - v[0] * v[0] - v[1] * v[1])); };
    auto length = [&](const double* v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + z(v) * z(v)); };
    const double cosine = (a[0] * b[0] + a[1] * b[1] + z(a) * z(b)) / (length(a) * length(b));
    return std::acos(std::min(1.0, cosine)) * 180.0 / std::numbers::pi;
}

// As block_upload_test's: Mesa's allocations while its driver lives in this process are not leaks.
struct DriverAllocations {
#if defined(__SANITIZE_ADDRESS__)
    DriverAllocations() { __lsan_disable(); }
    ~DriverAllocations() { __lsan_enable(); }
#endif
};

}  // namespace astc_upload

using namespace astc_upload;

// Heights (swell in 6x6 and 8x8) and xy normals (ripple in 4x4): every level as the GPU decodes it, mapped
// back through the recorded normalisation, against the float chain, within the recorded worst error (and
// angle) plus how far the GPU's decode strays from heightpack's (astcenc's); heights come back as
// luminance, normals with x in R, G and B and y in A.
TEST(BlockUpload, TheGpusAstcDecodeOfEveryLevelIsWithinTheRecordedError) {
    [[maybe_unused]] const DriverAllocations driver;
    view::HeadlessContext context;
    std::string why;
    ASSERT_TRUE(context.create(why)) << why;
    if (!contextHasAstc()) GTEST_SKIP() << "this GL context offers no GL_KHR_texture_compression_astc_ldr";
    ScratchDir dir;
    heightpackMustRun("pack", {kExamples + "swell.png", "--layout", "plain", "-o", dir.file("h.exr")});
    for (const std::string type : {"astc-6x6", "astc-8x8"})
        heightpackMustRun("pack", {kExamples + "swell.png", "--layout", "plain", "--pixel-type", type, "-o", dir.file(type + ".ktx2")});
    const std::vector<std::string> normal = {kExamples + "ripple.png", "--tile-size", "8m", "--height", "0.15m", "--layout", "xy"};
    for (const std::string type : {"float", "astc-4x4"}) {
        auto args = normal;
        args.insert(args.end(), {"--pixel-type", type, "-o", dir.file(type == "float" ? "n.exr" : "n.ktx2")});
        heightpackMustRun("normal", args);
    }
    for (const auto& [blocksFile, floatFile] : {std::pair{"astc-6x6.ktx2", "h.exr"}, std::pair{"astc-8x8.ktx2", "h.exr"},
                                                std::pair{"n.ktx2", "n.exr"}}) {
        auto blocks = readGpuTexture(dir.file(blocksFile));
        auto floats = readTextureFile(dir.file(floatFile));
        ASSERT_TRUE(blocks && floats) << blocksFile;
        ASSERT_TRUE(blocks->normalisation) << blocksFile;
        const Normalisation n = *blocks->normalisation;
        const TextureDescription& d = blocks->description;
        const bool normals = blocks->levels[0].channels == 2;
        ASSERT_EQ(d.lookupErrors.size(), blocks->levels.size());
        if (normals) {
            ASSERT_EQ(d.angleErrors.size(), blocks->levels.size());
        }
        for (int level = 0; level < int(blocks->levels.size()); ++level) {
            const std::vector<float> rgba = gpuAstcDecode(*blocks, level);
            const Image& reference = floats->levels[size_t(level)];
            const Image& core = blocks->levels[size_t(level)];
            double againstFloat = 0, againstCore = 0, angle = 0, flattestZ = 1, notStored = 0;
            for (size_t t = 0; t < core.texelCount(); ++t) {
                const float* texel = rgba.data() + 4 * t;
                double value[2] = {0, 0}, ref[2] = {0, 0};
                for (int c = 0; c < core.channels; ++c) {
                    value[c] = double(n.offset) + double(n.scale) * texel[c == 0 ? 0 : 3];
                    ref[c] = reference.pixels[t * size_t(reference.channels) + size_t(c)];
                    againstFloat = std::max(againstFloat, std::abs(value[c] - ref[c]));
                    againstCore = std::max(againstCore, std::abs(value[c] - core.pixels[t * size_t(core.channels) + size_t(c)]));
                }
                notStored = std::max({notStored, double(std::abs(texel[1] - texel[0])), double(std::abs(texel[2] - texel[0])),
                                      normals ? 0.0 : double(std::abs(texel[3] - 1.0f))});
                if (normals) {
                    angle = std::max(angle, angleDegrees(value, ref));
                    flattestZ = std::min(flattestZ, std::sqrt(std::max(0.0, 1.0 - ref[0] * ref[0] - ref[1] * ref[1])));
                }
            }
            // Mesa's llvmpipe decodes LDR ASTC to 8 bits a channel: it strays from astcenc's 16-bit decode by
            // under one 8-bit step (measured up to 0.99 on these files), where a wrong block size, channel or
            // swizzle misses by tens of steps.
            const double step = double(n.scale) / 255.0;
            EXPECT_LE(againstCore, step + 1e-5) << blocksFile << " level " << level;
            EXPECT_EQ(notStored, 0.0) << blocksFile << " level " << level;
            EXPECT_LE(againstFloat, d.lookupErrors[size_t(level)] + againstCore + 1e-5) << blocksFile << " level " << level;
            if (normals) {
                const double stray = std::sqrt(2.0) * againstCore / flattestZ * 180.0 / std::numbers::pi;
                EXPECT_LE(angle, d.angleErrors[size_t(level)] + stray + 1e-3) << blocksFile << " level " << level;
            }
        }
    }
}

// heightpack-view draws ASTC heights (6x6) filtered in hardware and through the gather lookup as the
// float map draws, within the recorded error, and holds them as 16 bytes a 6x6 block; ASTC normals
// (4x4) shade as the float normals do (y read from alpha) at 16 bytes a 4x4 block.
TEST(BlockUpload, AstcHeightsAndNormalsDrawAsTheFloatMapsWithinTheirDecodedError) {
    ScratchDir dir;
    const std::string map = kExamples + "swell.png";
    heightpackMustRun("pack", {map, "--layout", "plain", "-o", dir.file("f.exr")});
    heightpackMustRun("pack", {map, "--layout", "plain", "--pixel-type", "astc-6x6", "-o", dir.file("a.ktx2")});
    auto record = readGpuTexture(dir.file("a.ktx2"));
    ASSERT_TRUE(record);
    const TextureDescription& d = record->description;
    // The levels a trilinear lookup from this camera reads (2 and 3, as block_upload_test's BC4 test).
    const double worst = std::max(d.lookupErrors[2], d.lookupErrors[3]), rms = std::max(d.rmsErrors[2], d.rmsErrors[3]);
    const std::vector<std::string> common = {"--view", "height", "--size", "160x120", "--time", "2", "--camera",
                                             "0,0,60,0,-60", "--amplitude", "4", "--tile-size", "64", "--grid", "128",
                                             "--segments", "128"};
    auto shoot = [&](const std::vector<std::string>& files, const std::string& lookup, const std::string& name) {
        std::vector<std::string> args = files;
        args.insert(args.end(), {"--lookup", lookup, "--screenshot", dir.file(name + ".png"), "--json"});
        args.insert(args.end(), common.begin(), common.end());
        const ViewRun r = test::view(args);
        EXPECT_EQ(r.code, 0) << r.err;
        return std::pair{readPicture(dir.file(name + ".png")), nlohmann::json::parse(r.out, nullptr, false)};
    };
    const auto [reference, floatBench] = shoot({dir.file("f.exr")}, "reference-trilinear", "f");
    for (const std::string lookup : {"reference-trilinear", "gather"}) {
        const auto [picture, bench] = shoot({dir.file("a.ktx2")}, lookup, "a" + lookup);
        const Difference diff = compare(reference, picture, 0);
        EXPECT_LE(diff.max, int(std::ceil(204.0 * worst)) + 1) << lookup;
        double sum = 0;
        for (size_t i = 0; i < reference.rgb.size(); ++i) sum += std::abs(int(reference.rgb[i]) - int(picture.rgb[i]));
        EXPECT_LE(sum / double(reference.rgb.size()), 204.0 * rms) << lookup;
        EXPECT_GT(diff.max, 0) << lookup;  // the blocks are drawn, not the float chain
        long long blockBytes = 0;
        for (int s = 512; s >= 1; s /= 2) blockBytes += 16LL * ((s + 5) / 6) * ((s + 5) / 6);
        EXPECT_EQ(bench["gpuBytes"]["plain"], blockBytes) << lookup;
    }
    // Normals: the same heights shaded by float normals and by ASTC 4x4 ones.
    const std::vector<std::string> normal = {kExamples + "ripple.png", "--tile-size", "8m", "--height", "0.15m", "--layout", "xy"};
    for (const std::string type : {"float", "astc-4x4"}) {
        auto args = normal;
        args.insert(args.end(), {"--pixel-type", type, "-o", dir.file(type == "float" ? "n.exr" : "n.ktx2")});
        heightpackMustRun("normal", args);
    }
    auto shade = [&](const std::string& normals) {
        const ViewRun r = test::view({dir.file("f.exr"), "--normals", dir.file(normals), "--size", "128x96", "--screenshot",
                                      dir.file(normals + ".png"), "--json"});
        EXPECT_EQ(r.code, 0) << r.err;
        return std::pair{readPicture(dir.file(normals + ".png")), nlohmann::json::parse(r.out, nullptr, false)};
    };
    const auto [floatShaded, floatShadedBench] = shade("n.exr");
    const auto [astcShaded, astcShadedBench] = shade("n.ktx2");
    long long normalBytes = 0;
    for (int s = 256; s >= 1; s /= 2) normalBytes += 16LL * std::max(1, s / 4) * std::max(1, s / 4);
    EXPECT_EQ(astcShadedBench["gpuBytes"]["normals"], normalBytes);
    double sum = 0;
    for (size_t i = 0; i < floatShaded.rgb.size(); ++i) sum += std::abs(int(floatShaded.rgb[i]) - int(astcShaded.rgb[i]));
    const double meanDifference = sum / double(floatShaded.rgb.size());
    std::printf("ASTC 4x4 normals against float normals: mean difference %.3f grey levels, max %d\n", meanDifference,
                compare(floatShaded, astcShaded, 0).max);
    EXPECT_LE(meanDifference, 1.0);
}

// A context without ASTC cannot draw an ASTC file: exit 5 (no usable OpenGL) with one line, no picture.
// Mesa hides the extension when told to (MESA_EXTENSION_OVERRIDE); drawn through EGL, with no X server whose
// wrapper could add lines of its own.
TEST(BlockUpload, AContextWithoutAstcRefusesAnAstcFileWithExit5) {
    ScratchDir dir;
    heightpackMustRun("pack", {kExamples + "ripple.png", "--layout", "plain", "--pixel-type", "astc-8x8", "-o", dir.file("a.ktx2")});
    const ViewRun r = test::viewWithoutDisplay({dir.file("a.ktx2"), "--headless", "--size", "64x48", "--screenshot", dir.file("a.png")},
                                 {"MESA_EXTENSION_OVERRIDE=-GL_KHR_texture_compression_astc_ldr"});
    EXPECT_EQ(r.code, 5) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("GL_KHR_texture_compression_astc_ldr"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("bc4"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("a.png")));
}
