// The KTX2 and DDS writers and readers called directly: the two-channel formats (normal xy), half
// rounding against a conversion written from the definition, xy normals in uint16 against analytic normals,
// and damaged files refused, never crashing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "heightpack/io/attributes.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/texture_write.hpp"
#include "support/heightpack_process.hpp"
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
ChainToWrite xyContent(int width, int height) {
    ChainToWrite c;
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
    c.attributes = {{"heightpack:layout", std::string(attributeText(Layout::Xy))}, {"heightpack:tileWidth", 8.0f}};
    return c;
}

// A one-channel chain of plain heights, as BC4 takes.
ChainToWrite plainContent(int width, int height) {
    ChainToWrite c;
    c.width = width;
    c.height = height;
    c.channelNames = {"Y"};
    c.fillRows = [](int level, int y0, int rows, float* dst) {
        const int w = std::max(1, 32 >> level);
        for (int y = y0; y < y0 + rows; ++y)
            for (int x = 0; x < w; ++x) *dst++ = float(0.5 + 0.4 * std::sin(0.37 * x + 0.91 * y + level));
    };
    c.attributes = {{"heightpack:layout", std::string(attributeText(Layout::Plain))}, {"heightpack:tileWidth", 8.0f}};
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
    const ChainToWrite content = xyContent(32, 16);
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
                                                                   : TexelFormat::Rg16Unorm;
            EXPECT_EQ(t->format, expected);
            ASSERT_EQ(t->levels.size(), 6u);
            // uint16: the chain's range, value = offset + scale * u / 65535, as an RGBA16 file records it.
            double lo = 1e9, hi = -1e9;
            for (int level = 0; level < 6; ++level) {
                std::vector<float> values(size_t(std::max(1, 32 >> level)) * std::max(1, 16 >> level) * 2);
                content.fillRows(level, 0, std::max(1, 16 >> level), values.data());
                for (float v : values) lo = std::min(lo, double(v)), hi = std::max(hi, double(v));
            }
            const Normalisation n = t->normalisation.value_or(Normalisation{});
            if (type == PixelType::Uint16) {
                ASSERT_TRUE(t->normalisation.has_value());
                EXPECT_EQ(n.offset, float(lo));
                EXPECT_NEAR(n.offset + n.scale, hi, 1e-6);
            }
            json other;
            Normalisation otherN;
            if (independent) {
                const ProcessResult r = runProcess({"node", HEIGHTPACK_READER_MJS, path, HEIGHTPACK_NPM_DIR});
                ASSERT_EQ(r.code, 0) << r.err;
                other = json::parse(r.out);
                const TexelFormatInfo& f = texelFormatInfo(expected);
                EXPECT_EQ(other["format"], std::string(ext) == ".ktx2" ? f.vkName : f.dxgiName);
                ASSERT_EQ(other["levels"].size(), 6u);
                if (type == PixelType::Uint16) {  // from the file's key/values, or the DDS record's words
                    otherN.offset = std::stof(other["keyValues"].value("heightpack:normalisedOffset", "nan"));
                    otherN.scale = std::stof(other["keyValues"].value("heightpack:normalisedScale", "nan"));
                }
            }
            auto unorm = [](double v, const Normalisation& m) {
                return m.offset + m.scale * (std::nearbyint((v - m.offset) * 65535.0 / m.scale) / 65535.0);
            };
            for (int level = 0; level < 6; ++level) {
                const int w = std::max(1, 32 >> level), h = std::max(1, 16 >> level);
                std::vector<float> source(size_t(w) * h * 2);
                content.fillRows(level, 0, h, source.data());
                const Image& mine = t->levels[level];
                ASSERT_EQ(mine.pixels.size(), source.size());
                for (size_t i = 0; i < source.size(); ++i) {
                    const double want = type == PixelType::Float ? double(source[i])
                                        : type == PixelType::Half ? nearestHalf(source[i])
                                                                  : unorm(source[i], n);
                    ASSERT_NEAR(mine.pixels[i], want, 1e-6) << "level " << level << " #" << i;
                    if (independent) {
                        double theirs = other["levels"][level]["values"][i].get<double>();
                        if (type == PixelType::Uint16) theirs = otherN.offset + otherN.scale * (theirs / 65535.0);
                        ASSERT_NEAR(theirs, want, 1e-6);
                    }
                }
            }
        }
    }
}

TEST(GpuTexture, DamagedFilesAreRefusedAsBadInput) {
    ScratchDir dir;
    const ChainToWrite xy = xyContent(32, 16), plain = plainContent(32, 16);
    struct Case {
        const char* name;
        PixelType type;
        const ChainToWrite& content;
    };
    // Block streams too (issue 39): BC4 heights and BC5 normals in both containers, whose level sizes
    // count whole blocks.
    for (const Case& c : {Case{"d.ktx2", PixelType::Half, xy}, Case{"d.dds", PixelType::Half, xy}, Case{"z.ktx2", PixelType::Half, xy},
                          Case{"bc4.ktx2", PixelType::Bc4, plain}, Case{"bc4.dds", PixelType::Bc4, plain},
                          Case{"bc5.ktx2", PixelType::Bc5, xy}, Case{"bc5.dds", PixelType::Bc5, xy}}) {
        const std::string name = c.name;
        TextureWriteOptions options;
        options.storage.pixelType = c.type;
        if (name == "z.ktx2") options.storage.supercompression = Supercompression::Zstd;
        const auto output = textureOutput(dir.file(name));
        ASSERT_TRUE(output.ok());
        const auto written = writeTexture(*output, c.content, options);
        ASSERT_TRUE(written.ok()) << name << ": " << written.error().what;
        const std::vector<unsigned char> whole = readBytes(dir.file(name));
        const std::string damaged = dir.file("damaged" + std::filesystem::path(name).extension().string());
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

// xy normals in uint16 are stored as rgb normals are (issue 25): R16G16_UNORM over the chain's range,
// the offset and scale recorded. Read by the independent readers (ktx-parse; the DDS header decoded from
// its documented layout), level 0 is the normals of a sine field's central differences, worked out here
// in closed form, to within half a 16-bit step of the recorded range.
TEST(GpuTexture, XyNormalsInUint16AreUnsignedNormalisedAndMatchTheAnalyticNormals) {
    if (!std::filesystem::exists(std::string(HEIGHTPACK_NPM_DIR) + "/node_modules/ktx-parse/package.json"))
        HEIGHTPACK_WITHOUT_ORACLE("the independent readers are not installed: run scripts/test.sh");
    ScratchDir dir;
    // h = a sin(k x) cos(k y) metres, stored as 0.5 + 0.5 sin cos over a range of 2a, on an 8 m tile.
    const int size = 64;
    const double tile = 8.0, a = 0.1, k = 2 * std::numbers::pi / 2.0, texel = tile / size;
    writeImage(dir.file("sine.exr"), makeImage(size, size, [&](int i, int j) {
                   return float(0.5 + 0.5 * std::sin(k * (i + 0.5) * texel) * std::cos(k * (j + 0.5) * texel));
               }), OIIO::TypeDesc::FLOAT);
    for (const char* ext : {".ktx2", ".dds"}) {
        const std::string path = dir.file(std::string("n") + ext);
        SCOPED_TRACE(path);
        ASSERT_EQ(heightpackRun({"normal", dir.file("sine.exr"), "--tile-size", "8m", "--height", "0.2m", "--layout", "xy",
                                 "--pixel-type", "uint16", "-q", "-o", path}).code, 0);
        const ProcessResult r = runProcess({"node", HEIGHTPACK_READER_MJS, path, HEIGHTPACK_NPM_DIR});
        ASSERT_EQ(r.code, 0) << r.err;
        const json other = json::parse(r.out);
        EXPECT_EQ(other["format"], std::string(ext) == ".ktx2" ? "VK_FORMAT_R16G16_UNORM" : "DXGI_FORMAT_R16G16_UNORM");
        EXPECT_EQ(other["keyValues"].value("heightpack:layout", ""), "normalXY");
        if (std::string(ext) == ".ktx2")
            for (const json& sample : other["dfd"]["samples"]) {  // unsigned, 0 to 65535
                EXPECT_EQ(sample["channelType"].get<int>() & 0x40, 0);
                EXPECT_EQ(sample["lower"], 0);
                EXPECT_EQ(sample["upper"], 65535);
            }
        const double offset = std::stod(other["keyValues"].value("heightpack:normalisedOffset", "nan"));
        const double scale = std::stod(other["keyValues"].value("heightpack:normalisedScale", "nan"));
        ASSERT_GT(scale, 0.0);
        const json& level0 = other["levels"][0]["values"];
        ASSERT_EQ(level0.size(), size_t(size) * size * 2);
        // Central differences of a sampled sine: the derivative times sin(k texel) / (k texel), exactly.
        // (The stored 0.5 sin cos spans the height range 2a: a sin cos metres.)
        const double gain = a * std::sin(k * texel) / texel;
        double worst = 0.0;
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i) {
                const double x = (i + 0.5) * texel, y = (j + 0.5) * texel;
                const double sx = gain * std::cos(k * x) * std::cos(k * y), sy = -gain * std::sin(k * x) * std::sin(k * y);
                const double inv = 1.0 / std::sqrt(sx * sx + sy * sy + 1.0);
                const double want[2] = {-sx * inv, sy * inv};  // OpenGL: green along +dh/dy down the rows
                for (int c = 0; c < 2; ++c) {
                    const double got = offset + scale * level0[(size_t(j) * size + i) * 2 + c].get<double>() / 65535.0;
                    worst = std::max(worst, std::abs(got - want[c]));
                }
            }
        EXPECT_LE(worst, 0.5 * scale / 65535.0 + 1e-6) << "half a step of the recorded range";
        EXPECT_GT(worst, 0.0);
    }
}
