// Internal: a fast decoder for the PNGs height maps usually are (grey or grey + alpha, 8 or 16 bits,
// not interlaced). libpng inflates with zlib, which is most of the time `pack` spends on a large map;
// libdeflate inflates about three times faster. Anything else, or anything odd, is left to OpenImageIO.
#pragma once

#include <optional>
#include <vector>
#include <string>

#include "heightpack/core/image.hpp"

namespace heightpack::detail {

// Decodes sample `channel` (0 = grey, 1 = alpha) of every pixel of the PNG file's bytes as floats, converted
// exactly as OpenImageIO converts (8-bit: v * (1/255.f), 16-bit: v * (1/65535.f)). Returns nothing when
// the file is not such a PNG, does not match width x height, or is damaged in any way (every chunk's CRC
// is checked): the caller then reads it through OpenImageIO, which reports what is wrong. threads: for
// the conversion to float (0 = all cores); the result does not depend on it.
std::optional<Image> decodeGreyPng(const std::vector<unsigned char>& file, int width, int height, int channel,
                                   int threads);

}  // namespace heightpack::detail
