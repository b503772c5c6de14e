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
// 16): each sample is v * (2^bits - 1) rounded to nearest (halves up). Each
// row gets the filter whose output has the least sum of magnitudes (libpng's heuristic); `text` becomes tEXt
// chunks (keyword, value) in order. threads: for the filtering (0 = all cores); the bytes do not depend on it.
std::vector<unsigned char> encodeGreyPng(const Image& image, int bits, const std::vector<std::pair<std::string, std::string>>& text,
                                         int threads);

// encodeGreyPng in two steps, so the costly one can run ahead of knowing the text (tile compresses a
// candidate while it judges it): the zlib stream of the filtered rows, then the file around it.
struct GreyPngPixels {
    int width = 0, height = 0, bits = 0;
    std::vector<unsigned char> compressed;
};
GreyPngPixels compressGreyPngPixels(const Image& image, int bits, int threads);
std::vector<unsigned char> assembleGreyPng(const GreyPngPixels& pixels, const std::vector<std::pair<std::string, std::string>>& text);

}  // namespace heightpack::detail
