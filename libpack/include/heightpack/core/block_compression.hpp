// BC4 and BC5 (RGTC) blocks: 4x4 texels of one or two unsigned normalised channels in 8 or 16 bytes, as
// the Khronos Data Format Specification's "RGTC Compressed Texture Image Formats" defines them; ASTC LDR
// blocks (4x4, 6x6 or 8x8 texels in 16 bytes) through ARM's astcenc (core/astc_compression.cpp).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "heightpack/core/image.hpp"

namespace heightpack {

// BC4: one channel, 8 bytes a block; BC5: two channels, each a BC4 block, 16 bytes a block.
// ASTC: one channel (plain heights, stored as luminance RRR1) or two (xy normals, stored as x in RGB and y
// in alpha, astcenc's normal-map mode), 16 bytes a block of 4x4, 6x6 or 8x8 texels. AstcHdr: the same
// sizes in ASTC's HDR profile (decoded as half floats), one channel only (plain heights).
enum class BlockFormat { Bc4, Bc5, Astc4x4, Astc6x6, Astc8x8, AstcHdr4x4, AstcHdr6x6, AstcHdr8x8 };
inline bool isAstc(BlockFormat format) { return format != BlockFormat::Bc4 && format != BlockFormat::Bc5; }
inline bool isAstcHdr(BlockFormat format) {
    return format == BlockFormat::AstcHdr4x4 || format == BlockFormat::AstcHdr6x6 || format == BlockFormat::AstcHdr8x8;
}
// BC4 and BC5 only (an ASTC block holds whichever the image has).
inline int blockChannels(BlockFormat format) { return format == BlockFormat::Bc4 ? 1 : 2; }
inline int blockBytes(BlockFormat format) { return format == BlockFormat::Bc4 ? 8 : 16; }
// A block's width and height in texels.
inline int blockSide(BlockFormat format) {
    if (format == BlockFormat::Astc6x6 || format == BlockFormat::AstcHdr6x6) return 6;
    return format == BlockFormat::Astc8x8 || format == BlockFormat::AstcHdr8x8 ? 8 : 4;
}
// The bytes of a width x height image: whole blocks, a block's texels past the image padding it (a level
// smaller than a block is one block).
inline size_t blockImageBytes(int width, int height, BlockFormat format) {
    const int side = blockSide(format);
    return size_t((width + side - 1) / side) * size_t((height + side - 1) / side) * size_t(blockBytes(format));
}

// Encodes values in [0, 1] (image.channels == blockChannels(format); values outside are clamped) into
// blocks, row by row of blocks, in two passes. Every block quickly: endpoint pairs at the values' range and
// at the least-squares fit to the float values, the pair of least squared error kept. Then again,
// thoroughly, the blocks whose worst error is within 75% of the image's worst (the few that decide it):
// pairs around the range and the fit in both of BC4's modes (eight interpolated values; six with 0 and
// 1); of those whose worst error is within a quarter code of the least, the one of least squared error.
// A block's texels past the image repeat its edge texels.
// BC5 with `normals` (how unit values map to a normal's x and y: offset + scale * u): the worst error is
// the angle between the decoded normal and the given one (z rebuilt); thorough blocks choose x and y
// together among each channel's candidates of least squared error, by that angle summed over the block
// and its worst, then the codes of the texels that decide the worst angle by the angle. Without
// `normals`, each channel as BC4's.
// ASTC: image.channels 1 or 2, through astcenc (see astc_compression.hpp); `normals` picks its normal-map mode.
// Block rows on `threads` threads (0: all cores); the bytes do not depend on it.
struct NormalUnits {
    double offset = 0.0, scale = 1.0;
};
std::vector<std::uint8_t> encodeBlocks(ImageView image, BlockFormat format, int threads = 0,
                                       std::optional<NormalUnits> normals = std::nullopt);

// Decodes blocks into a width x height image, by the specification's rules: RED_0 = red_0 / 255, the
// interpolated values (6 RED_0 + RED_1) / 7 ... in float, blockChannels(format) channels; ASTC by astcenc's
// decoder into `channels` channels (1: R; 2: R and A), which BC4 and BC5 ignore.
Image decodeBlocks(const std::uint8_t* bytes, int width, int height, BlockFormat format, int channels = 1);

// One BC4 block's 16 values (texel (x, y) at 4y + x) from its 8 bytes.
void decodeBc4Block(const std::uint8_t* block, float values[16]);

}  // namespace heightpack
