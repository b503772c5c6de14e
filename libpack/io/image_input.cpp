#include "image_input.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>

#include "exr_source.hpp"
#include "format_module_loader.hpp"
#include "input_format.hpp"
#include "png_source.hpp"
#include "text.hpp"

namespace heightpack::detail {

namespace {

std::string sizeText(long long w, long long h) { return std::to_string(w) + "x" + std::to_string(h); }

// BMP's RLE8 and RLE4 (compression 1 and 2 in the info header): OpenImageIO 2.4 decodes them wrongly.
bool isRleBmp(const std::vector<unsigned char>& h) {
    if (h.size() < 34 || h[0] != 'B' || h[1] != 'M') return false;
    auto le32 = [&](int at) {
        return uint32_t(h[at]) | uint32_t(h[at + 1]) << 8 | uint32_t(h[at + 2]) << 16 | uint32_t(h[at + 3]) << 24;
    };
    const uint32_t infoSize = le32(14), compression = le32(30);
    return infoSize >= 40 && (compression == 1 || compression == 2);
}

}  // namespace

Status judgeSize(const std::string& path, const SourceSpec& spec, const SizeLimits& limits) {
    if (spec.width <= 0 || spec.height <= 0 || spec.depth > 1 || spec.nchannels <= 0)
        return badInput(path, "has no 2D pixel data", "export it as a flat 2D image");
    const int64_t texels = int64_t(spec.width) * spec.height;
    if (spec.width > limits.maxSide || spec.height > limits.maxSide || texels > limits.maxTexels ||
        texels * spec.nchannels > limits.maxSamples) {
        return badInput(path, "is " + sizeText(spec.width, spec.height) + " with " + std::to_string(spec.nchannels) +
                                  " channels, larger than heightpack accepts (" + std::to_string(limits.maxSide) +
                                  " texels a side, " + std::to_string(limits.maxTexels) + " texels in all)",
                        "split or downsize the map");
    }
    return Done{};
}

OpenedImage::OpenedImage(OpenedImage&&) noexcept = default;
OpenedImage& OpenedImage::operator=(OpenedImage&&) noexcept = default;
OpenedImage::~OpenedImage() {
    input_.reset();  // the reader goes before the bytes it reads
}

std::vector<unsigned char> OpenedImage::releaseBytes() {
    input_.reset();  // the reader goes before the bytes it reads
    return std::move(bytes_);
}

Result<OpenedImage> judgeOpened(const std::string& path, OpenedImage opened, const SizeLimits& limits,
                                uint64_t fileBytes) {
    const SourceSpec& top = opened->spec();
    if (Status s = judgeSize(path, top, limits); !s) return s.error();
    if (Status s = judgeDecodedSize(path, int64_t(top.width) * top.height, top.nchannels, fileBytes); !s) return s.error();
    return opened;
}

Result<OpenedImage> openImage(const std::string& path, const SizeLimits& limits) {
    auto read = readInputBytes(path);
    if (!read) return read.error();
    OpenedImage opened;
    opened.bytes_ = std::move(read->bytes);
    InputBytes judged{read->format, {}};
    judged.bytes.swap(opened.bytes_);
    if (Status s = judgeHeader(path, judged, limits); !s) return s.error();
    judged.bytes.swap(opened.bytes_);
    const uint64_t fileBytes = opened.bytes_.size();
    if (judged.format == InputFormat::Bmp && isRleBmp(opened.bytes_))
        return badInput(path, "is an RLE-compressed BMP, which heightpack cannot decode faithfully",
                        "re-export it as PNG (or as an uncompressed BMP)");
    // OpenEXR reads an EXR, and heightpack a grey PNG, where they present it as OpenImageIO would: the
    // module is not loaded.
    if (judged.format == InputFormat::Exr)
        opened.input_ = openExrDirectly(opened.bytes_.data(), opened.bytes_.size(), path);
    if (judged.format == InputFormat::Png) opened.input_ = openPngDirectly(opened.bytes_, path);
    if (opened.input_) return judgeOpened(path, std::move(opened), limits, fileBytes);
    auto module = formatModule(path, "cannot be read");
    if (!module) return module.error();
    std::string why;
    bool createFailed = false;
    opened.input_ = (*module)->open(nameOf(judged.format), opened.bytes_.data(), opened.bytes_.size(), path, why, createFailed);
    if (!opened.input_ && createFailed)
        return badInput(path, "cannot be read: " + firstLine(why), "export it as PNG, TIFF or EXR");
    if (!opened.input_)
        return badInput(path, "cannot be read as " + std::string(nameOf(judged.format)) + ": " + firstLine(why),
                        "export it again as PNG, TIFF or EXR");
    return judgeOpened(path, std::move(opened), limits, fileBytes);
}

Status readPixels(ImageSource& in, const std::string& path, int level, int chBegin, int chEnd, float* dst,
                  const std::string& what) {
    std::string error;
    if (!in.read(level, chBegin, chEnd, dst, error) || !error.empty())
        return badInput(path, what + ": " + firstLine(error.empty() ? "the decoder failed" : error),
                        "export the file again");
    return Done{};
}

Result<TextureDescription> describeSpec(const std::string& path, const SourceSpec& spec) {
    // Float in an EXR, text in a PNG: heightpack's attributes as text, read into typed values once.
    Attributes recorded;
    for (const SourceAttribute& p : spec.extra_attribs)
        if (p.name.rfind(attr::kPrefix, 0) == 0) recorded.emplace_back(p.name, p.text);
    return describeTexture(path, recorded, spec.channelnames, spec.format);
}

}  // namespace heightpack::detail
