// Internal: the one place an input image file is opened, so every reader (height maps, textures, info)
// refuses the same things the same way before a pixel is read.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "heightpack/core/result.hpp"
#include "heightpack/io/read.hpp"
#include "heightpack/io/texture_description.hpp"

#include "image_source.hpp"

namespace heightpack::detail {

// Largest image a reader accepts, judged from the header before anything is allocated.
struct SizeLimits {
    int maxSide = 32768;
    int64_t maxTexels = int64_t(1) << 28;  // per level
    int64_t maxSamples = int64_t(1) << 30; // texels * channels per level: 4 GiB of floats
};

// The limits a height-map load asks for (LoadOptions' maxSide and maxTexels), for every reader of one.
inline SizeLimits sizeLimitsOf(const LoadOptions& options) {
    SizeLimits limits;
    limits.maxSide = options.maxSide;
    limits.maxTexels = options.maxTexels;
    return limits;
}

// Fails with BadInput when spec (one level of path) is empty, 3D, or larger than limits.
Status judgeSize(const std::string& path, const SourceSpec& spec, const SizeLimits& limits);

// An image being read: a decoder (OpenEXR's, or OpenImageIO's through the format module) over the file's
// bytes, which heightpack read and judged itself (input_format.hpp). Use it as the decoder (->, *); the
// bytes live as long as it does.
class OpenedImage {
public:
    OpenedImage() = default;
    OpenedImage(OpenedImage&&) noexcept;
    OpenedImage& operator=(OpenedImage&&) noexcept;
    ~OpenedImage();

    ImageSource* operator->() const { return input_.get(); }
    ImageSource& operator*() const { return *input_; }
    // The file's bytes, read once: decoders of heightpack's own (png_fast.hpp) take them from here.
    const std::vector<unsigned char>& bytes() const { return bytes_; }
    // Closes the reader and hands over the file's bytes, for a decoder that frees them as it goes. The
    // image is closed afterwards: open the file again to read it through its decoder.
    std::vector<unsigned char> releaseBytes();

private:
    friend Result<OpenedImage> openImage(const std::string& path, const SizeLimits& limits);
    std::vector<unsigned char> bytes_;
    std::unique_ptr<ImageSource> input_;
};

// Opens path for reading, after checking that it is a readable, non-empty regular file (checkReadable)
// in a format heightpack reads, told by its first bytes and decoded by that format's reader alone
// (input_format.hpp), whose header claims nothing its bytes cannot hold, in a form heightpack decodes
// faithfully (no RLE-compressed BMP), and judging the first level's size against limits. Every failure
// is BadInput naming path, with a hint.
Result<OpenedImage> openImage(const std::string& path, const SizeLimits& limits);

// Reads channels [chBegin, chEnd) of mip level `level` as floats into dst, failing with BadInput when the
// decoder reports any error, even one it did not fail on (OpenImageIO 2.4 returns true for a TIFF with
// missing strips and fills them with zeros).
Status readPixels(ImageSource& in, const std::string& path, int level, int chBegin, int chEnd,
                  float* dst, const std::string& what = "is damaged or truncated");

// What spec's header says (its heightpack:* attributes, channel names and sample type), typed; BadInput
// naming path and the key for a damaged value.
Result<TextureDescription> describeSpec(const std::string& path, const SourceSpec& spec);

}  // namespace heightpack::detail
