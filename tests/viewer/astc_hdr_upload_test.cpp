// ASTC HDR heights on the GPU (the BlockUpload suite): where the context offers
// GL_KHR_texture_compression_astc_hdr, the GPU's decode of every level (uploaded as the file's blocks, read
// back as floats) against the half floats astcenc's decoder gives (heightpack's reader, which
// tests/io/astc_hdr_test.cpp holds to astcenc -dh); a context without it (Mesa's llvmpipe has only the LDR
// profile) refuses an HDR file with exit 5 and one line.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

#include "headless_context.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "support/heightpack_process.hpp"
#include "viewer_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

// A named namespace: the viewer suites are compiled as one unity file, beside astc_upload_test's helpers.
namespace astc_hdr_upload {

bool contextHasAstcHdr() {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i)
        if (std::string(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)))) ==
            "GL_KHR_texture_compression_astc_hdr")
            return true;
    return false;
}

// GL_COMPRESSED_RGBA_ASTC_NxN_KHR: the LDR and HDR profiles share the formats.
GLenum glFormatOf(PixelType type) {
    return type == PixelType::AstcHdr4x4 ? 0x93B0 : type == PixelType::AstcHdr6x6 ? 0x93B4 : 0x93B7;
}

// As block_upload_test's: Mesa's allocations while its driver lives in this process are not leaks.
struct HdrDriverAllocations {
#if defined(__SANITIZE_ADDRESS__)
    HdrDriverAllocations() { __lsan_disable(); }
    ~HdrDriverAllocations() { __lsan_enable(); }
#endif
};

}  // namespace astc_hdr_upload

using namespace astc_hdr_upload;

// Every level of swell in each HDR size as the GPU decodes it equals the reader's decode to the half
// float (both give the block's half floats), R holding the value.
TEST(BlockUpload, TheGpusAstcHdrDecodeOfEveryLevelMatchesAstcencs) {
    [[maybe_unused]] const HdrDriverAllocations driver;
    view::HeadlessContext context;
    std::string why;
    ASSERT_TRUE(context.create(why)) << why;
    if (!contextHasAstcHdr())
        GTEST_SKIP() << "this GL context offers no GL_KHR_texture_compression_astc_hdr (Mesa's llvmpipe has the LDR profile only)";
    ScratchDir dir;
    for (const std::string type : {"astc-hdr-4x4", "astc-hdr-6x6", "astc-hdr-8x8"}) {
        heightpackMustRun("pack", {kExamples + "swell.png", "--layout", "plain", "--pixel-type", type, "-o", dir.file(type + ".ktx2")});
        auto blocks = readGpuTexture(dir.file(type + ".ktx2"));
        ASSERT_TRUE(blocks) << type;
        for (int level = 0; level < int(blocks->levels.size()); ++level) {
            const int w = std::max(1, blocks->width >> level), h = std::max(1, blocks->height >> level);
            GLuint texture = 0;
            glGenTextures(1, &texture);
            glBindTexture(GL_TEXTURE_2D, texture);
            glCompressedTexImage2D(GL_TEXTURE_2D, 0, glFormatOf(pixelTypeOf(blocks->format)), w, h, 0,
                                   GLsizei(blocks->levelBytes[size_t(level)].size()), blocks->levelBytes[size_t(level)].data());
            std::vector<float> rgba(size_t(w) * size_t(h) * 4);
            glPixelStorei(GL_PACK_ALIGNMENT, 1);
            glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, rgba.data());
            EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
            glDeleteTextures(1, &texture);
            const Image& reader = blocks->levels[size_t(level)];
            double most = 0.0;
            for (size_t t = 0; t < reader.texelCount(); ++t) most = std::max(most, double(std::fabs(rgba[4 * t] - reader.pixels[t])));
            EXPECT_LE(most, 1.0 / 2048.0) << type << " level " << level;  // one half step below 1
        }
    }
}

// A context without the HDR profile cannot draw an HDR file: exit 5 with one line naming the extension and
// what to write instead, no picture. Mesa is told to hide the extension, so the test also holds on a
// driver that has it.
TEST(BlockUpload, AContextWithoutAstcHdrRefusesAnHdrFileWithExit5) {
    ScratchDir dir;
    heightpackMustRun("pack", {kExamples + "ripple.png", "--layout", "plain", "--pixel-type", "astc-hdr-6x6", "-o", dir.file("h.ktx2")});
    const ViewRun r = test::viewWithoutDisplay({dir.file("h.ktx2"), "--headless", "--size", "64x48", "--screenshot", dir.file("h.png")},
                                               {"MESA_EXTENSION_OVERRIDE=-GL_KHR_texture_compression_astc_hdr"});
    EXPECT_EQ(r.code, 5) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("GL_KHR_texture_compression_astc_hdr"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("astc-4x4/6x6/8x8"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("h.png")));
}
