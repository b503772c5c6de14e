// Internal: an encoder for the PNGs heightpack writes most (one grey channel, 8 or 16 bits), the twin of
// png_fast's decoder. OpenImageIO writes PNGs through libpng, which deflates with zlib on one thread: for a
// 4096^2 16-bit map that is 1.6 s, most of `tile`'s writing. libdeflate at the same level takes a quarter of
// the time for a file no larger, and the rows are filtered on all threads.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "heightpack/core/image.hpp"

namespace heightpack::detail {

// The bytes of a PNG of image's one channel (samples in [0,1]; anything beyond is clamped) at `bits` (8 or
// 16): each sample is round(v * (2^bits - 1)), rounded to nearest, ties to even, as OpenImageIO converts. Each
// row gets the filter whose output has the least sum of magnitudes (libpng's heuristic); `text` becomes tEXt
// chunks (keyword, value) in order. threads: for the filtering (0 = all cores); the bytes do not depend on it.
std::vector<unsigned char> encodeGreyPng(const Image& image, int bits, const std::vector<std::pair<std::string, std::string>>& text,
                                         int threads);

}  // namespace heightpack::detail
