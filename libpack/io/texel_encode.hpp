// Internal: what the KTX2 and DDS writers share: the levels of a chain, the encoding of float rows into
// the chosen texel format, its inverse for the readers, and the attributes as text.
#pragma once

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/io/gpu_texture.hpp"

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

inline int levelSide(int size, int level) { return size >> level > 0 ? size >> level : 1; }
// Levels of a full chain down to 1x1 (ROUND_DOWN, as the EXR writer).
int fullChainLevels(int width, int height);

struct EncodePlan {
    TexelFormatInfo format{};
    int sourceChannels = 0;
    int levels = 0;
    std::optional<Normalisation> normalisation;  // Unorm16 formats only
};

// Chooses the format and, for uint16, the normalisation (one pass over the chain); refuses values the
// pixel type cannot hold. path names the output in errors.
Result<EncodePlan> planEncoding(const std::string& path, const MipChainSource& content,
                                const TextureWriteOptions& options);

// Fills rows [y0, y0 + rows) of level and encodes them into dst, resized to rows * width * texel bytes.
Status encodeRows(const std::string& path, const MipChainSource& content, const EncodePlan& plan, int level, int y0,
                  int rows, int threads, std::vector<std::uint8_t>& dst);

// One value as stored and as read back: the 16-bit codes (nearest code, clamped to the format's range)
// and their values. encodeRows and decodeLevel use these, so what storeAndRead says is what a file holds.
std::uint16_t unormCode(double value, const Normalisation& n);
float unormValue(std::uint16_t code, const Normalisation& n);
std::int16_t snormCode(float value);
float snormValue(std::int16_t code);
// What reading back value gives once stored in plan's format.
float storeAndRead(const EncodePlan& plan, float value);

// Decodes a level's bytes (little-endian) into a float image of the format's channels.
Image decodeLevel(const TexelFormatInfo& format, const std::uint8_t* bytes, int width, int height,
                  const std::optional<Normalisation>& normalisation);

// A float as text that reads back to the same float.
std::string floatText(float value);
// The attributes as the text key/values the containers record.
Attributes attributesAsText(const std::vector<ExrAttribute>& attributes);

// Reads a whole file; BadInput naming it when it cannot be read.
Result<std::vector<std::uint8_t>> readWholeFile(const std::string& path);

}  // namespace heightpack::detail
