// Internal: writing a chain's levels, uncompressed, at the file offsets a container fixes in advance
// (KTX2 without supercompression, DDS), every layer of an array where the container puts it. Shared by
// both writers.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "texel_encode.hpp"

namespace heightpack::detail {

// Where one layer's image of one level goes: mipLevelSide(width, level) x mipLevelSide(height, level) texels
// of the plan's format, rows tightly packed (layer 0 for a texture that is not an array).
struct PlacedImage {
    int layer = 0;
    int level = 0;
    std::uint64_t offset = 0;
};

// Creates the file temporaryPath and writes header at its start, then each of images (in file order:
// increasing offsets, none before the header's end, none overlapping) at its offset, with zeros in any
// gap, and closes it. Every thread fills, encodes and writes (pwrite) bands of its own, in turn through
// the file, from buffers it keeps: the bytes depend on nothing but their place. The disk writes start as
// bands are written (EarlyWriteback), so the flush before the file is moved into place
// (TemporaryFile::commit) waits only for the last ones. path names the output in errors; progress (may
// be empty) is called on the calling thread with the fraction of rows written. Fails, naming the first
// level in file order that holds a non-finite value, or when the file cannot be written; the caller then
// discards the file.
Status writePlacedImages(const std::string& path, const std::string& temporaryPath, const std::vector<std::uint8_t>& header,
                         const std::vector<PlacedImage>& images, const ChainToWrite& content, const EncodePlan& plan,
                         int threads, const std::function<void(double)>& progress);

}  // namespace heightpack::detail
