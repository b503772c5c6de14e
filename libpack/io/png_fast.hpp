// Internal: a fast decoder for the PNGs height maps usually are (grey or grey + alpha, 8 or 16 bits,
// not interlaced). libpng inflates with zlib, which is most of the time `pack` spends on a large map;
// libdeflate inflates about three times faster. Anything else, or anything odd, is left to OpenImageIO.
#pragma once

#include <optional>
#include <vector>
#include <string>

#include "heightpack/core/image.hpp"

namespace heightpack::detail {

// What decodeGreyPng needs of a PNG it can decode, found by planGreyPng.
struct GreyPngPlan {
    int width = 0, height = 0;
    int channel = 0;   // the sample decoded: 0 grey, 1 alpha
    int samples = 0;   // 1 grey, 2 grey + alpha
    int bitDepth = 0;  // 8 or 16
    size_t dataBegin = 0, dataEnd = 0;  // the run of IDAT chunks, as byte offsets into the file
};

// Whether the PNG file's bytes are such a PNG that sample `channel` (0 = grey, 1 = alpha) of width x height
// pixels can be decoded here: every chunk's CRC checked, the chunks in the order the specification fixes,
// the header matching. Nothing when not: the caller then reads it through OpenImageIO, which reports what
// is wrong.
std::optional<GreyPngPlan> planGreyPng(const std::vector<unsigned char>& file, int width, int height, int channel);

// Decodes the planned sample of every pixel as floats, converted exactly as OpenImageIO converts (8-bit:
// v * (1/255.f), 16-bit: v * (1/65535.f)). Takes the file's bytes (planGreyPng's, unchanged) and frees
// them once inflated, so that no more than the bytes and the floats are held at once. Nothing when the
// image data does not inflate or unfilter (a damaged stream under valid CRCs). threads: for undoing the
// row filters and the conversion to float (0 = all cores); the result does not depend on it.
std::optional<Image> decodeGreyPng(std::vector<unsigned char> file, const GreyPngPlan& plan, int threads);

}  // namespace heightpack::detail
