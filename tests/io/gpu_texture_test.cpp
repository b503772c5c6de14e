// The KTX2 and DDS writers and readers called directly: the two-channel formats (normal xy), half
// rounding against a conversion written from the definition, and damaged files refused, never crashing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/texture_write.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
using nlohmann::json;

namespace {

double nearestHalf(double v) {  // binary16 nearest to v, ties to even, subnormals at 2^-24
    if (v == 0.0) return 0.0;
    const int e = std::max(int(std::floor(std::log2(std::fabs(v)))), -14);
    const double ulp = std::ldexp(1.0, e - 10);
    return std::nearbyint(v / ulp) * ulp;
}

// A two-channel chain: level L's texel (x, y) holds a unit vector's x and y.
MipChainSource xyContent(int width, int height) {
    MipChainSource c;
    c.width = width;
    c.height = height;
    c.channelNames = {"X", "Y"};
    c.fillRows = [](int level, int y0, int rows, float* dst) {
        const int w = std::max(1, 32 >> level);
        for (int y = y0; y < y0 + rows; ++y)
            for (int x = 0; x < w; ++x) {
                const double a = 0.37 * x + 0.91 * y + level;
                *dst++ = float(0.8 * std::cos(a));
                *dst++ = float(0.8 * std::sin(a));
            }
    };
    c.attributes = {{"heightpack:layout", std::string("xy")}, {"heightpack:tileWidth", 8.0f}};
    return c;
}

}  // namespace

TEST(GpuTexture, HalfRoundsToNearestEvenAndKnowsItsRange) {
    std::vector<float> values = {0.0f, 1.0f, -2.5f, 65504.0f, 65519.0f, -65519.0f, 6.0e-8f, 3.0e-5f, 1.0f / 3.0f,
                                 1.0f + 1.0f / 2048.0f, 1.0f + 3.0f / 2048.0f, 2049.0f, 2051.0f};
    for (int i = 0; i < 20000; ++i) values.push_back(float(std::ldexp(std::sin(i * 12.9898) * 1.9, (i % 40) - 24)));
    for (float v : values) {
        ASSERT_TRUE(halfCanHold(v)) << v;
        EXPECT_EQ(double(halfToFloat(floatToHalf(v))), nearestHalf(v)) << v;
    }
    EXPECT_FALSE(halfCanHold(65520.0f));
    EXPECT_FALSE(halfCanHold(-1e9f));
    EXPECT_FALSE(halfCanHold(std::nanf("")));
}

TEST(GpuTexture, TwoChannelFormatsRoundTripThroughBothReaders) {
    const bool independent =
        std::filesystem::exists(std::string(HEIGHTPACK_NPM_DIR) + "/node_modules/ktx-parse/package.json");
    ScratchDir dir;
    const MipChainSource content = xyContent(32, 16);
    for (const char* ext : {".ktx2", ".dds"}) {
        for (PixelType type : {PixelType::Float, PixelType::Half, PixelType::Uint16}) {
            const std::string path = dir.file(std::string("xy_") + pixelTypeName(type) + ext);
            SCOPED_TRACE(path);
            TextureWriteOptions options;
            options.storage.pixelType = type;
            const auto output = textureOutput(path);
            ASSERT_TRUE(output.ok());
            ASSERT_TRUE(writeTexture(*output, content, options).ok());
            auto t = readGpuTexture(path);
            ASSERT_TRUE(t.ok()) << t.error().what;
            const TexelFormat expected = type == PixelType::Float  ? TexelFormat::Rg32F
                                         : type == PixelType::Half ? TexelFormat::Rg16F
                                                                   : TexelFormat::Rg16Snorm;
            EXPECT_EQ(t->format, expected);
            ASSERT_EQ(t->levels.size(), 6u);
            json other;
            if (independent) {
                const ProcessResult r = runProcess({"node", HEIGHTPACK_READER_MJS, path, HEIGHTPACK_NPM_DIR});
                ASSERT_EQ(r.code, 0) << r.err;
                other = json::parse(r.out);
                const TexelFormatInfo& f = texelFormatInfo(expected);
                EXPECT_EQ(other["format"], std::string(ext) == ".ktx2" ? f.vkName : f.dxgiName);
                ASSERT_EQ(other["levels"].size(), 6u);
            }
            for (int level = 0; level < 6; ++level) {
                const int w = std::max(1, 32 >> level), h = std::max(1, 16 >> level);
                std::vector<float> source(size_t(w) * h * 2);
                content.fillRows(level, 0, h, source.data());
                const Image& mine = t->levels[level];
                ASSERT_EQ(mine.pixels.size(), source.size());
                for (size_t i = 0; i < source.size(); ++i) {
                    const double want = type == PixelType::Float ? double(source[i])
                                        : type == PixelType::Half ? nearestHalf(source[i])
                                                                  : std::nearbyint(source[i] * 32767.0) / 32767.0;
                    ASSERT_NEAR(mine.pixels[i], want, 1e-7) << "level " << level << " #" << i;
                    if (independent) {
                        ASSERT_NEAR(other["levels"][level]["values"][i].get<double>(), want, 1e-7);
                    }
                }
            }
        }
    }
}

TEST(GpuTexture, DamagedFilesAreRefusedAsBadInput) {
    ScratchDir dir;
    const MipChainSource content = xyContent(32, 16);
    for (const char* name : {"d.ktx2", "d.dds", "z.ktx2"}) {
        TextureWriteOptions options;
        options.storage.pixelType = PixelType::Half;
        if (std::string(name) == "z.ktx2") options.storage.supercompression = Supercompression::Zstd;
        const auto output = textureOutput(dir.file(name));
        ASSERT_TRUE(output.ok());
        ASSERT_TRUE(writeTexture(*output, content, options).ok());
        const std::vector<unsigned char> whole = readBytes(dir.file(name));
        const std::string damaged = dir.file(std::string("damaged") + (name[0] == 'd' && name[2] == 'd' ? ".dds" : ".ktx2"));
        // Every truncation fails; so does any byte of the fixed headers set to 0xFF, or the reader returns
        // a texture of the size the file holds. Never a crash (the sanitizer build runs this too).
        for (size_t n = 0; n < whole.size(); n += (n < 200 ? 1 : 7)) {
            writeBytes(damaged, std::vector<unsigned char>(whole.begin(), whole.begin() + std::ptrdiff_t(n)));
            auto t = readGpuTexture(damaged);
            ASSERT_FALSE(t.ok()) << name << " cut at " << n;
            EXPECT_EQ(t.error().kind, ErrorKind::BadInput);
            EXPECT_EQ(t.error().path, damaged);
        }
        for (size_t i = 0; i < std::min<size_t>(whole.size(), 256); ++i) {
            std::vector<unsigned char> bytes = whole;
            bytes[i] = 0xFF;
            writeBytes(damaged, bytes);
            auto t = readGpuTexture(damaged);
            if (t.ok()) {
                ASSERT_FALSE(t->levels.empty());
            } else {
                EXPECT_EQ(t.error().kind, ErrorKind::BadInput);
            }
        }
    }
}
