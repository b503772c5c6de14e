#include "image_input.hpp"

#include <OpenImageIO/filesystem.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>

#include "input_format.hpp"
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

// The file's bytes as OpenImageIO's readers see them: its memory reader (the JPEG reader takes the buffer
// from it directly), with reads that stay inside the bytes. OpenImageIO 2.4's own pread copies from before
// the buffer when a damaged EXR offset table seeks to a negative position (found by fuzz_load_image).
class BytesReader final : public OIIO::Filesystem::IOMemReader {
public:
    using IOMemReader::IOMemReader;
    bool seek(int64_t offset) override {
        m_pos = offset;
        return offset >= 0 && offset <= int64_t(m_buf.size());
    }
    size_t read(void* buf, size_t size) override {
        const size_t n = pread(buf, size, m_pos);
        m_pos += int64_t(n);
        return n;
    }
    size_t pread(void* buf, size_t size, int64_t offset) override {
        if (offset < 0 || offset >= int64_t(m_buf.size()) || size == 0) return 0;
        const size_t n = std::min<size_t>(size, m_buf.size() - size_t(offset));
        std::memcpy(buf, m_buf.data() + offset, n);
        return n;
    }
};

}  // namespace

Status judgeSize(const std::string& path, const OIIO::ImageSpec& spec, const SizeLimits& limits) {
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
    proxy_.reset();
    return std::move(bytes_);
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
    // The reader the magic bytes chose, and no other: OpenImageIO would otherwise try every format it
    // knows on a file its first choice refuses.
    opened.proxy_ = std::make_unique<BytesReader>(opened.bytes_.data(), opened.bytes_.size());
    opened.input_ = OIIO::ImageInput::create(nameOf(judged.format), false, nullptr, opened.proxy_.get());
    if (!opened.input_)
        return badInput(path, "cannot be read: " + firstLine(OIIO::geterror()), "export it as PNG, TIFF or EXR");
    // Keep colour and alpha as stored: an RGBA height map's channels are data, not premultiplied colour.
    OIIO::ImageSpec config, spec;
    config.attribute("oiio:UnassociatedAlpha", 1);
    void* proxy = opened.proxy_.get();
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    if (!opened.input_->open(path, spec, config)) {
        const std::string why = opened.input_->geterror();
        return badInput(path, "cannot be read as " + std::string(nameOf(judged.format)) + ": " +
                                  firstLine(why.empty() ? OIIO::geterror() : why),
                        "export it again as PNG, TIFF or EXR");
    }
    const OIIO::ImageSpec& top = opened.input_->spec();
    if (Status s = judgeSize(path, top, limits); !s) return s.error();
    if (Status s = judgeDecodedSize(path, int64_t(top.width) * top.height, top.nchannels, fileBytes); !s) return s.error();
    return opened;
}

Status readPixels(OIIO::ImageInput& in, const std::string& path, int subimage, int level, int chBegin, int chEnd,
                  float* dst, const std::string& what) {
    (void)in.geterror();  // forget anything said while opening: only this read's errors count
    const bool ok = in.read_image(subimage, level, chBegin, chEnd, OIIO::TypeDesc::FLOAT, dst);
    const std::string error = in.geterror();
    if (!ok || !error.empty())
        return badInput(path, what + ": " + firstLine(error.empty() ? "the decoder failed" : error),
                        "export the file again");
    return Done{};
}

}  // namespace heightpack::detail
