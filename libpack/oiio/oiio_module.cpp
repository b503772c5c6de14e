// The OpenImageIO module: the formats heightpack does not decode or write itself (TIFF, JPEG, TGA, BMP,
// PSD, HDR, PNM, ...), behind image_source.hpp. Built as a library of its own that libpack/io loads the
// first time a file needs it (oiio_loader.cpp), so a process that reads and writes only PNG, EXR, KTX2
// and DDS never maps OpenImageIO and the ~260 libraries it brings.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>

#include "../io/image_source.hpp"

namespace heightpack::detail {

namespace {

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

SourceSpec specOf(const OIIO::ImageSpec& spec) {
    SourceSpec out;
    out.width = spec.width;
    out.height = spec.height;
    out.depth = spec.depth;
    out.nchannels = spec.nchannels;
    out.channelnames = spec.channelnames;
    out.alpha_channel = spec.alpha_channel;
    out.format = spec.format.c_str();
    out.tile_width = spec.tile_width;
    out.tile_height = spec.tile_height;
    for (const OIIO::ParamValue& p : spec.extra_attribs) {
        SourceAttribute a;
        a.name = p.name().string();
        a.text = p.get_string();
        a.isFloat = p.type() == OIIO::TypeFloat;
        // get_float gives its default for a value it cannot convert: two defaults tell the cases apart.
        a.number = p.get_float(0.0f);
        a.hasNumber = a.number == p.get_float(1.0f);
        out.extra_attribs.push_back(std::move(a));
    }
    return out;
}

class OiioSource final : public ImageSource {
public:
    std::unique_ptr<BytesReader> proxy;
    std::unique_ptr<OIIO::ImageInput> input;
    SourceSpec current;
    std::string formatName;

    ~OiioSource() override { input.reset(); }  // the reader goes before the proxy it reads
    const char* format_name() const override { return formatName.c_str(); }
    const char* decoder() const override { return "openimageio"; }
    const SourceSpec& spec() const override { return current; }
    bool seekLevel(int level) override {
        if (!input->seek_subimage(0, level)) return false;
        current = specOf(input->spec());
        return true;
    }
    bool read(int level, int chBegin, int chEnd, float* dst, std::string& error) override {
        (void)input->geterror();  // forget anything said while opening: only this read's errors count
        const bool ok = input->read_image(0, level, chBegin, chEnd, OIIO::TypeDesc::FLOAT, dst);
        error = input->geterror();
        return ok && error.empty();
    }
    void close() override { input->close(); }
};

class OiioModule final : public ImageModule {
public:
    int interfaceVersion() const override { return kModuleInterface; }
    std::string libraryVersion() const override { return OIIO_VERSION_STRING; }

    std::unique_ptr<ImageSource> open(const std::string& formatName, const unsigned char* bytes, size_t size,
                                      const std::string& path, std::string& error, bool& createFailed) override {
        auto source = std::make_unique<OiioSource>();
        source->proxy = std::make_unique<BytesReader>(const_cast<unsigned char*>(bytes), size);
        // The reader the magic bytes chose, and no other: OpenImageIO would otherwise try every format it
        // knows on a file its first choice refuses.
        source->input = OIIO::ImageInput::create(formatName, false, nullptr, source->proxy.get());
        if (!source->input) {
            error = OIIO::geterror();
            createFailed = true;
            return nullptr;
        }
        createFailed = false;
        // Keep colour and alpha as stored: an RGBA height map's channels are data, not premultiplied colour.
        OIIO::ImageSpec config, spec;
        config.attribute("oiio:UnassociatedAlpha", 1);
        void* proxy = source->proxy.get();
        config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
        if (!source->input->open(path, spec, config)) {
            const std::string why = source->input->geterror();
            error = why.empty() ? OIIO::geterror() : why;
            return nullptr;
        }
        source->formatName = source->input->format_name();
        source->current = specOf(source->input->spec());
        return source;
    }

    bool write(const ModuleWrite& request, std::string& error, bool& createFailed) override {
        const OIIO::TypeDesc type = request.bits == 8    ? OIIO::TypeDesc::UINT8
                                    : request.bits == 16 ? OIIO::TypeDesc::UINT16
                                    : request.half       ? OIIO::TypeDesc::HALF
                                                         : OIIO::TypeDesc::FLOAT;
        OIIO::ImageSpec spec(request.width, request.height, request.channels, type);
        spec.channelnames = request.channelNames;
        spec.alpha_channel = request.alphaChannel;
        spec.attribute("oiio:UnassociatedAlpha", 1);
        // OpenImageIO's EXR writer stamps the current time (capDate) when no DateTime is given; a fixed,
        // empty one keeps the same inputs giving the same bytes.
        spec.attribute("DateTime", "");
        if (request.srgb) spec.attribute("oiio:ColorSpace", "sRGB");
        for (const ModuleWrite::Attribute& a : request.attributes) {
            if (a.isFloat) spec.attribute(a.name, a.number);
            else spec.attribute(a.name, a.text);
        }
        auto out = OIIO::ImageOutput::create(request.path);
        createFailed = !out;
        if (!out) {
            error = OIIO::geterror();
            return false;
        }
        if (!out->open(request.path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, request.pixels) || !out->close()) {
            error = out->geterror();
            return false;
        }
        return true;
    }

    void setThreads(int threads) override { OIIO::attribute("threads", threads); }
};

}  // namespace

}  // namespace heightpack::detail

extern "C" __attribute__((visibility("default"))) heightpack::detail::ImageModule* heightpack_image_module() {
    static heightpack::detail::OiioModule module;
    return &module;
}
