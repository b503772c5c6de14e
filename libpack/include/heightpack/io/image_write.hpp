// Flat (one-level) image files: PNG, TIFF, scanline EXR, chosen by the extension, written atomically.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/attributes.hpp"
#include "heightpack/io/exr_write.hpp"

namespace heightpack {

namespace detail {
struct GreyPngPixels;
}

// An image's pixels compressed ahead of writing, where heightpack encodes the format itself (a one-channel
// 8- or 16-bit PNG): tile compresses a candidate while it judges it, and writes it once judged. Empty for
// any other output, which writeFlatImage then encodes as it writes.
struct PreparedPixels {
    std::shared_ptr<const detail::GreyPngPixels> png;
};

// The extensions writeFlatImage writes, lower case (any case is taken): a PNG, a TIFF, a scanline EXR.
inline constexpr std::array<const char*, 4> kFlatImageExtensions = {".png", ".tif", ".tiff", ".exr"};

// A flat (single-level, scanline) image file: a PNG, a TIFF, a scanline EXR, chosen by the extension.
struct FlatImageOptions {
    int bits = 32;          // 8 or 16 (unsigned integer) or 32 (float)
    bool half = false;      // with bits 32, in an EXR: 16-bit half channels instead of 32-bit float
    int srgbChannels = 0;   // the first this many channels are linear colours to encode as sRGB (8/16-bit)
    std::vector<ExrAttribute> attributes;  // metadata; a PNG holds numbers as text
    std::vector<std::string> channelNames; // empty: Y, RGB or RGBA by count
    int threads = 0;        // for compressing a float EXR (0 = all cores); the bytes do not depend on it
    Compression compression = Compression::Zip;  // a float EXR's: zip, zips or none
    PreparedPixels prepared;  // preparePixels' of this very image with these options, if made ahead
};

// The pixels of image as writeFlatImage(path, image, options) would compress them, made now (see
// PreparedPixels); empty where it would not encode them itself. The bytes do not depend on threads.
PreparedPixels preparePixels(const std::string& path, const Image& image, const FlatImageOptions& options);

// Writes image (1 to 4 channels: Y, RGB or RGBA) atomically, as writeTiledExr does. Integer formats clamp
// to [0,1] and round to nearest; alpha is stored unassociated. A float (or half) EXR is a ZIP scanline
// file from writeScanlineExr; the rest go through OpenImageIO.
Status writeFlatImage(const std::string& path, const Image& image, const FlatImageOptions& options);

}  // namespace heightpack
