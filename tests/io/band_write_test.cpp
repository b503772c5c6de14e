// The uncompressed KTX2 and DDS writers put every level's bands where the header says, from every thread:
// their files must hold exactly what writing the levels one after another gives. That serial encoding is
// made here from the definitions (IEEE 754 binary16, nearest 16-bit code of the recorded normalisation),
// in each container's order (KTX2: smallest level first, each aligned, its layers in turn; DDS: each
// layer's whole chain in turn), on sizes that split into uneven bands and odd levels, at 1 and 3 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <numeric>
#include <string>
#include <tuple>
#include <vector>

#include "heightpack/io/attributes.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

int side(int size, int level) { return std::max(size >> level, 1); }

// A smooth value per layer, level, texel and channel, within [-3, 5]: no two levels or layers alike.
float valueAt(int layer, int level, int x, int y, int c) {
    return float(1.0 + 4.0 * std::sin(0.013 * x + 0.029 * y + 0.7 * c + 1.3 * layer + 0.4 * level) *
                           std::cos(0.005 * x * (c + 1) - 0.011 * y));
}

// Every level of every layer of a chain, computed once from valueAt: the writer's fills and the serial
// encoding below read the same values, and the twelve files of a case (containers x pixel types x
// thread counts) do not each take the sines again.
struct BandChainValues {
    int width = 0, height = 0, channels = 0, levels = 0;
    std::vector<std::vector<float>> images;  // [layer * levels + level], rows of side(width) * channels floats

    BandChainValues(int w, int h, int c, int layers) : width(w), height(h), channels(c) {
        while ((w >> levels) > 0 || (h >> levels) > 0) ++levels;
        for (int layer = 0; layer < layers; ++layer)
            for (int level = 0; level < levels; ++level) {
                const int lw = side(w, level), lh = side(h, level);
                std::vector<float> image(size_t(lw) * lh * c);
                float* dst = image.data();
                for (int y = 0; y < lh; ++y)
                    for (int x = 0; x < lw; ++x)
                        for (int ch = 0; ch < c; ++ch) *dst++ = valueAt(layer, level, x, y, ch);
                images.push_back(std::move(image));
            }
    }
    void fill(int layer, int level, int y0, int rows, float* dst) const {
        const size_t row = size_t(side(width, level)) * channels;
        const std::vector<float>& image = images.at(size_t(layer) * levels + level);
        std::copy_n(image.begin() + std::ptrdiff_t(row * y0), row * rows, dst);
    }
};

ChainToWrite bandChain(const std::shared_ptr<const BandChainValues>& values, int layers) {
    ChainToWrite c;
    c.width = values->width;
    c.height = values->height;
    const int channels = values->channels;
    c.channelNames.assign(size_t(channels), "");
    for (int i = 0; i < channels; ++i) c.channelNames[size_t(i)] = std::string(1, "RGBA"[i]);
    if (layers > 1) {
        // Layers a DDS can record: heights, then Dx and Dy, then Foam.
        c.layerNames = layers == 4 ? std::vector<std::string>{"heights", "Dx", "Dy", "Foam"}
                                   : std::vector<std::string>{"heights", "Foam"};
        c.fillLayerRows = [values](int layer, int level, int y0, int rows, float* dst) { values->fill(layer, level, y0, rows, dst); };
    } else {
        c.fillRows = [values](int level, int y0, int rows, float* dst) { values->fill(0, level, y0, rows, dst); };
    }
    // The layout pack would record for such texels (four channels are packed heights), so a reader that
    // holds the header to its schema reads the file.
    c.attributes = {{"heightpack:layout", std::string(channels == 4 ? "neighbour4" : "plain")}};
    return c;
}

// binary16 bits of the half nearest to v (ties to even), from the format's definition; |v| < 65504.
std::uint16_t halfBits(float v) {
    const double a = std::fabs(double(v));
    const std::uint16_t sign = std::signbit(v) ? 0x8000 : 0;
    if (a < std::ldexp(1.0, -14)) return std::uint16_t(sign | std::uint16_t(std::nearbyint(a * std::ldexp(1.0, 24))));
    int e = int(std::floor(std::log2(a)));
    double m = std::nearbyint(a / std::ldexp(1.0, e - 10));  // 1024 .. 2048
    if (m == 2048.0) m = 1024.0, ++e;
    return std::uint16_t(sign | (e + 15) << 10 | (int(m) - 1024));
}

// One layer's image of one level as the file should hold it: texels of four components (alpha 1 added to
// three channels), each float, half or the nearest code of value = offset + scale * u / 65535.
std::vector<std::uint8_t> encoded(const ChainToWrite& c, int layer, int level, PixelType type,
                                  const Normalisation& n) {
    const int w = side(c.width, level), h = side(c.height, level), from = int(c.channelNames.size());
    std::vector<float> values(size_t(w) * h * from);
    if (c.layerNames.empty()) c.fillRows(level, 0, h, values.data());
    else c.fillLayerRows(layer, level, 0, h, values.data());
    const int to = from == 3 ? 4 : from;
    std::vector<std::uint8_t> out;
    for (size_t t = 0; t < size_t(w) * h; ++t)
        for (int ch = 0; ch < to; ++ch) {
            const float v = ch < from ? values[t * from + ch] : 1.0f;
            std::uint8_t b[4];
            size_t bytes = 2;
            if (type == PixelType::Float) std::memcpy(b, &v, bytes = 4);
            else {
                std::uint16_t u = 0;
                if (type == PixelType::Half) u = halfBits(v);
                else u = std::uint16_t(std::nearbyint(std::clamp((double(v) - n.offset) / n.scale * 65535.0, 0.0, 65535.0)));
                std::memcpy(b, &u, 2);
            }
            out.insert(out.end(), b, b + bytes);
        }
    return out;
}

// encoded() of a case's layers and levels, each computed once: the two containers and the two thread
// counts hold the same encoded images wherever the pixel type and the normalisation read back are the same.
class SerialImages {
public:
    explicit SerialImages(const ChainToWrite& c) : c_(c) {}
    const std::vector<std::uint8_t>& of(int layer, int level, PixelType type, const Normalisation& n) {
        const auto key = std::make_tuple(layer, level, static_cast<int>(type), n.offset, n.scale);
        auto found = images_.find(key);
        if (found == images_.end()) found = images_.emplace(key, encoded(c_, layer, level, type, n)).first;
        return found->second;
    }

private:
    const ChainToWrite& c_;
    std::map<std::tuple<int, int, int, float, float>, std::vector<std::uint8_t>> images_;
};

std::uint64_t le64(const std::vector<unsigned char>& b, size_t at) {
    std::uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = v << 8 | b.at(at + size_t(i));
    return v;
}

// The whole file a serial writer gives: the file's own header (checked elsewhere against independent
// readers), then the levels in the container's order.
std::vector<unsigned char> serialFile(const std::vector<unsigned char>& file, bool ktx2, const ChainToWrite& c,
                                      PixelType type, const Normalisation& n, int levels, SerialImages& images) {
    const int layers = c.layerCount();
    std::vector<unsigned char> expected;
    if (!ktx2) {
        expected.assign(file.begin(), file.begin() + std::min<size_t>(file.size(), 4 + 124 + 20));
        for (int layer = 0; layer < layers; ++layer)
            for (int level = 0; level < levels; ++level) {
                const std::vector<std::uint8_t>& bytes = images.of(layer, level, type, n);
                expected.insert(expected.end(), bytes.begin(), bytes.end());
            }
        return expected;
    }
    // After the identifier and header: dfdByteOffset/Length at 48, kvdByteOffset/Length at 56.
    const std::uint64_t dfdEnd = (le64(file, 48) & 0xffffffff) + (le64(file, 48) >> 32);
    const std::uint64_t kvdEnd = (le64(file, 56) & 0xffffffff) + (le64(file, 56) >> 32);
    expected.assign(file.begin(), file.begin() + std::ptrdiff_t(std::max(dfdEnd, kvdEnd)));
    const size_t texelBytes = (type == PixelType::Float ? 4 : 2) * size_t(c.channelNames.size() == 3 ? 4 : c.channelNames.size());
    const size_t alignment = std::lcm(texelBytes, size_t(4));
    for (int level = levels - 1; level >= 0; --level) {
        expected.resize((expected.size() + alignment - 1) / alignment * alignment, 0);
        EXPECT_EQ(le64(file, 80 + 24 * size_t(level)), expected.size()) << "level " << level << "'s offset";
        for (int layer = 0; layer < layers; ++layer) {
            const std::vector<std::uint8_t>& bytes = images.of(layer, level, type, n);
            expected.insert(expected.end(), bytes.begin(), bytes.end());
        }
    }
    return expected;
}

}  // namespace

TEST(BandWrite, FilesHoldTheLevelsAsASerialWriterLaysThemOut) {
    ScratchDir dir;
    struct Case {
        int width, height, channels, layers, levels;
    };
    // An array of four RGBA layers in bands of 65 rows; a three-channel texture (alpha added) whose 1 MiB
    // bands end mid-level; one channel, two levels only; an array of two layers one texel wide.
    const Case cases[] = {{1000, 301, 4, 4, 0}, {777, 523, 3, 1, 0}, {1531, 999, 1, 1, 2}, {1, 37, 4, 2, 0}};
    for (const Case& k : cases) {
        const auto values = std::make_shared<const BandChainValues>(k.width, k.height, k.channels, k.layers);
        const ChainToWrite c = bandChain(values, k.layers);
        SerialImages images(c);
        const int levels = k.levels > 0 ? k.levels : values->levels;
        for (const char* ext : {".ktx2", ".dds"}) {
            for (PixelType type : {PixelType::Float, PixelType::Half, PixelType::Uint16}) {
                for (int threads : {1, 3}) {
                    const std::string path = dir.file("band" + std::to_string(threads) + ext);
                    SCOPED_TRACE(std::to_string(k.width) + "x" + std::to_string(k.height) + " " + pixelTypeName(type) +
                                 " " + path);
                    TextureWriteOptions options;
                    options.storage.pixelType = type;
                    options.threads = threads;
                    options.levels = k.levels;
                    const bool ktx2 = std::string(ext) == ".ktx2";
                    ASSERT_TRUE((ktx2 ? writeKtx2(path, c, options) : writeDds(path, c, options)).ok());
                    auto read = readGpuTexture(path);
                    ASSERT_TRUE(read.ok()) << read.error().what;
                    ASSERT_EQ(read->normalisation.has_value(), type == PixelType::Uint16);
                    const Normalisation n = read->normalisation.value_or(Normalisation{});
                    const std::vector<unsigned char> file = readBytes(path);
                    const std::vector<unsigned char> expected = serialFile(file, ktx2, c, type, n, levels, images);
                    ASSERT_EQ(file.size(), expected.size());
                    // The first differing byte, rather than two files' worth of bytes, when they differ.
                    const auto diff = std::mismatch(file.begin(), file.end(), expected.begin());
                    EXPECT_TRUE(diff.first == file.end()) << "first difference at byte " << (diff.first - file.begin());
                }
            }
        }
    }
}
