// Internal: what the KTX2 and DDS writers share: the levels of a chain, the encoding of float rows into
// the chosen texel format, its inverse for the readers, and the attributes as text.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/core/block_compression.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/texture_write.hpp"

namespace heightpack::detail {

// Rows encoded (and written) at a time: a band of a level stays in cache between encoding and writing.
inline constexpr int kBandRows = 64;

// A little-endian 32-bit word of a container's header.
inline std::uint32_t readLe32(const std::uint8_t* p) {
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

// Closes a stdio file a writer holds in a std::unique_ptr.
struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};


// Whether every value is finite, by their exponent bits (a test that vectorises).
bool allFinite(const float* v, size_t n);

// The internal error for a level holding a non-finite value (the loader refuses them; a writer never
// stores one).
Error nonFiniteLevel(const std::string& path, int level);

// Fills rows of a level of content's layer: fillLayerRows for an array, fillRows (layer 0) otherwise.
void fillLayerRows(const ChainToWrite& content, int layer, int level, int y0, int rows, float* dst);

// The block format of a block TexelFormat (Bc4Unorm, Bc5Unorm, the ASTC sizes).
inline BlockFormat blockFormatOf(const TexelFormatInfo& format) {
    switch (format.format) {
        case TexelFormat::Bc4Unorm: return BlockFormat::Bc4;
        case TexelFormat::Astc4x4R:
        case TexelFormat::Astc4x4Rg: return BlockFormat::Astc4x4;
        case TexelFormat::Astc6x6R:
        case TexelFormat::Astc6x6Rg: return BlockFormat::Astc6x6;
        case TexelFormat::Astc8x8R:
        case TexelFormat::Astc8x8Rg: return BlockFormat::Astc8x8;
        case TexelFormat::AstcHdr4x4R: return BlockFormat::AstcHdr4x4;
        case TexelFormat::AstcHdr6x6R: return BlockFormat::AstcHdr6x6;
        case TexelFormat::AstcHdr8x8R: return BlockFormat::AstcHdr8x8;
        default: return BlockFormat::Bc5;
    }
}
// The bytes a width x height image takes in format.
inline size_t imageBytes(const TexelFormatInfo& format, int width, int height) {
    return format.isBlock() ? blockImageBytes(width, height, blockFormatOf(format))
                            : size_t(width) * height * format.bytesPerTexel();
}

struct EncodePlan {
    TexelFormatInfo format{};
    int sourceChannels = 0;
    int levels = 0;
    std::optional<Normalisation> normalisation;  // Unorm16 and block formats only
    std::shared_ptr<const BlockLevels> blocks;   // block formats: what the plan encoded
};

// The format and levels content is written in under plan, and plan's normalisation: no pass over the
// values (the writers take the plan as decided).
EncodePlan encodePlanOf(const ChainToWrite& content, const TextureWriteOptions& options, const WritePlan& plan);

// Chooses the format and, for uint16, the normalisation of options.storage.pixelType (one pass over the
// chain's values, on all threads); refuses values the pixel type cannot hold. path names the output in errors. sameValues, when
// given, are chains that hold, level by level, exactly the values content writes (see planTexelStorage):
// the pass then reads them rather than filling content's rows; the plan is the same.
Result<EncodePlan> planEncoding(const std::string& path, const ChainToWrite& content,
                                const TextureWriteOptions& options, const ChainValues& sameValues = {});

// Encodes every layer's every level of content into plan's block format (plan.normalisation maps values
// to unorms) and measures what they decode to against content's values. CannotWrite naming path when
// content's channels are not the format's (bc4 holds one, bc5 two).
Result<BlockLevels> encodeBlockLevels(const std::string& path, const ChainToWrite& content, const EncodePlan& plan,
                                      int threads);

// Encodes a chain a band of rows at a time, filling and encoding on all threads. Its buffers live as long
// as it does: one allocation for the chain instead of two a band (a library caller's malloc may hand a
// freed 4 MB band back to the system and fault it in again; the CLI keeps it in the heap).
class BandEncoder {
public:
    BandEncoder(const std::string& path, const ChainToWrite& content, const EncodePlan& plan, int threads)
        : path_(path), content_(content), plan_(plan), threads_(threads) {}
    // Fills rows [y0, y0 + rows) of level (of layer, in an array) and encodes them into bytes(), rows *
    // width * texel bytes.
    Status encode(int level, int y0, int rows, int layer = 0);
    const std::vector<std::uint8_t>& bytes() const { return bytes_; }

private:
    const std::string& path_;
    const ChainToWrite& content_;
    const EncodePlan& plan_;
    int threads_;
    std::vector<float> band_;          // the filled rows, unless they are filled straight into bytes_
    std::vector<std::uint8_t> bytes_;  // the encoded rows
};

// Round to nearest, ties to even, for |x| < 2^51: adding 1.5 * 2^52 leaves no fraction bits, so the FPU
// rounds (in its default mode, as std::nearbyint does), and subtracting it gives the integer back. Inline
// arithmetic that vectorises, where std::nearbyint is a library call a value.
inline double roundToEven(double x) {
    constexpr double shift = 6755399441055744.0;  // 1.5 * 2^52
    return (x + shift) - shift;
}

// One value as stored and as read back: the 16-bit codes (nearest code, clamped to the format's range)
// and their values. BandEncoder and decodeLevel use these, so what storeAndRead says is what a file holds.
// Clamping before rounding gives the codes that std::nearbyint then clamping gave (the same on 10^8 random
// values, ties and out-of-range ones included, when this replaced them), and keeps roundToEven in range.
inline std::uint16_t unormCode(double value, const Normalisation& n) {
    double u = (value - n.offset) * (65535.0 / n.scale);
    u = u < 0.0 ? 0.0 : u;
    u = u > 65535.0 ? 65535.0 : u;
    return static_cast<std::uint16_t>(static_cast<std::int32_t>(roundToEven(u)));
}
inline float unormValue(std::uint16_t code, const Normalisation& n) {
    return n.offset + n.scale * (float(code) / 65535.0f);
}
inline std::int16_t snormCode(float value) {
    double s = double(value);
    s = s < -1.0 ? -1.0 : s;
    s = s > 1.0 ? 1.0 : s;
    return static_cast<std::int16_t>(roundToEven(s * 32767.0));
}
float snormValue(std::int16_t code);
// What reading back value gives once stored in plan's format.
float storeAndRead(const EncodePlan& plan, float value);
// The same for n values, into readBack: bit for bit storeAndRead's, vectorised.
void storeAndReadRow(const EncodePlan& plan, const float* values, size_t n, float* readBack);

// Decodes a level's bytes (little-endian) into a float image of the format's channels.
Image decodeLevel(const TexelFormatInfo& format, const std::uint8_t* bytes, int width, int height,
                  const std::optional<Normalisation>& normalisation);

// Decodes a level that holds `layers` images of width x height one after the other (an array's level, as
// a KTX2 stores it) into one image whose texel holds every layer's channels in turn, layer 0's first.
Image decodeLayers(const TexelFormatInfo& format, const std::uint8_t* bytes, int width, int height, int layers,
                   const std::optional<Normalisation>& normalisation);

// The names of an array's `layers` layers from their recorded list (heightpack:layers, comma-separated);
// "layer1", "layer2", ... after the first ("heights") where nothing, or a list of another length, is recorded.
std::vector<std::string> layerNamesOf(const std::string& recorded, int layers);
// names comma-separated, as heightpack:layers records them.
std::string layerList(const std::vector<std::string>& names);

// A float as the shortest text that reads back to the same float: 1.333, not 1.33299994 (the text KTX2
// key/values, DDS's read-back and PNG text chunks hold, and info prints).
std::string floatText(float value);
// The attributes as the text key/values the containers record.
Attributes attributesAsText(const std::vector<ExrAttribute>& attributes);

// Reads a whole file; BadInput naming it when it cannot be read.
Result<std::vector<std::uint8_t>> readWholeFile(const std::string& path);

}  // namespace heightpack::detail
