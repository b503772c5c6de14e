// ASTC blocks through ARM's astcenc (libastcenc): one channel stored as luminance (RRR1), two as x in RGB
// and y in alpha (astcenc's normal-map mode, as its command line's -normal stores them). The HDR formats
// (AstcHdr4x4 ...) use astcenc's HDR profile (RGB HDR, alpha LDR) and hold one channel.
#pragma once

#include <cstdint>
#include <vector>

#include "heightpack/core/block_compression.hpp"

namespace heightpack {

// The preset every ASTC texture is encoded with (astcenc's -medium), so the bytes depend on the values
// alone.
inline constexpr float kAstcQuality = 60.0f;

// Encodes values in [0, 1] (image.channels 1 or 2; values outside are clamped) into ASTC blocks of
// format (Astc4x4 ... AstcHdr8x8), row by row of blocks, with astcenc at kAstcQuality; normalMap: two
// channels as a normal's x and y, astcenc weighing the angle. Texels past the image repeat its edge.
// `threads` threads (0: all cores) work on each band of block rows; astcenc codes each block on its own,
// so the bytes do not depend on it.
std::vector<std::uint8_t> encodeAstc(ImageView image, BlockFormat format, int threads, bool normalMap);

// Decodes ASTC blocks of format into a width x height image of `channels` channels (1: R; 2: R and A),
// each value the decoded UNORM16 / 65535 as astcenc's decoder gives it (HDR: the decoded half float).
Image decodeAstc(const std::uint8_t* bytes, int width, int height, BlockFormat format, int channels);

}  // namespace heightpack
