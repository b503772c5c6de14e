// Internal: the parts of a KTX 2.0 file both of heightpack's KTX2 writers lay out alike (texel formats in
// ktx2.cpp, block formats in ktx2_blocks.cpp): identifier, little-endian words, key/value data.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "heightpack/io/attributes.hpp"
#include "texel_encode.hpp"

namespace heightpack::detail::ktx2 {

inline constexpr std::uint8_t kIdentifier[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
inline constexpr std::uint32_t kSupercompressionZstd = 2;
inline constexpr std::uint64_t kZstdMostBlockBytes = 128 << 10;  // ZSTD_BLOCKSIZE_MAX
inline constexpr size_t kHeaderBytes = 80;  // identifier + header + index
inline constexpr const char* kOffsetKey = attr::normalisedOffset.name;
inline constexpr const char* kScaleKey = attr::normalisedScale.name;
// The KTX 2.0 key that tells a loader which stored channels give R, G, B and A. An ASTC file of plain
// heights stores them as luminance (R = G = B, A = 1): "r001"; of xy normals x in RGB and y in A: "ra01".
inline constexpr const char* kSwizzleKey = "KTXswizzle";
inline const char* astcSwizzle(int channels) { return channels == 2 ? "ra01" : "r001"; }

inline void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
inline void put64(std::vector<std::uint8_t>& out, std::uint64_t v) {
    for (int i = 0; i < 8; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
inline std::uint64_t get64(const std::uint8_t* p) {
    return std::uint64_t(readLe32(p)) | std::uint64_t(readLe32(p + 4)) << 32;
}
inline size_t alignUp(size_t v, size_t a) { return (v + a - 1) / a * a; }

// Key/value data: entries sorted by key, each keyAndValueByteLength, key NUL, value NUL, padded to 4.
inline std::vector<std::uint8_t> keyValueData(Attributes keyValues) {
    std::stable_sort(keyValues.begin(), keyValues.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<std::uint8_t> out;
    for (const auto& [key, value] : keyValues) {
        put32(out, static_cast<std::uint32_t>(key.size() + 1 + value.size() + 1));
        out.insert(out.end(), key.begin(), key.end());
        out.push_back(0);
        out.insert(out.end(), value.begin(), value.end());
        out.push_back(0);
        while (out.size() % 4) out.push_back(0);
    }
    return out;
}

}  // namespace heightpack::detail::ktx2

namespace heightpack::detail {

// Writes content in plan's block format (plan.blocks, encoded when it was planned) as a KTX2 at path with
// keyValues, every level of every layer, Zstandard-supercompressed when options ask. Levels whose side is
// under 4 texels are whole 4x4 blocks, as the format stores them.
Status writeKtx2Blocks(const std::string& path, const ChainToWrite& content, const TextureWriteOptions& options,
                       const EncodePlan& plan, const Attributes& keyValues);

}  // namespace heightpack::detail
