// OpenEXR files decoded by OpenEXR directly, presented as OpenImageIO 2.4 presents them (the channel order,
// the attributes and their names, the pixel type), so a process that reads only EXRs never loads the
// format module. A file with anything this does not present exactly as OpenImageIO would (several parts,
// deep data, subsampled or integer channels, ripmaps, an attribute OpenImageIO renames or converts) is
// left to OpenImageIO, and so is any file OpenEXR refuses here: what a bad file is told stays the same.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompressionAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfLineOrderAttribute.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTiledInputFile.h>
#include <OpenEXR/ImfVecAttribute.h>

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "exr_source.hpp"
#include "format_module_loader.hpp"

namespace heightpack::detail {

namespace {

// The file's bytes as an OpenEXR stream; a read past the end throws, as OpenEXR's own streams do.
class BytesStream final : public Imf::IStream {
public:
    BytesStream(const unsigned char* bytes, size_t size) : Imf::IStream("memory"), bytes_(bytes), size_(size) {}
    bool read(char c[], int n) override {
        if (n < 0 || at_ > size_ || size_t(n) > size_ - at_) throw std::runtime_error("early end of file");
        std::memcpy(c, bytes_ + at_, size_t(n));
        at_ += size_t(n);
        return at_ < size_;
    }
    uint64_t tellg() override { return at_; }
    void seekg(uint64_t pos) override { at_ = pos; }

private:
    const unsigned char* bytes_;
    size_t size_;
    uint64_t at_ = 0;
};

bool iequals(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
           });
}

// A channel in OpenImageIO's canonical order: by layer, then the reserved names (R, G, B, Y, A, ...) in
// their order, then by name.
struct SortedChannel {
    std::string full, layer, suffix;
    int special = 10000;
};

void sortChannels(std::vector<SortedChannel>& channels) {
    static const char* const usual[] = {"R",  "Red", "G",  "Green", "B",  "Blue", "Y", "real", "imag", "A", "Alpha",
                                        "AR", "RA",  "AG", "GA",    "AB", "BA",   "Z", "Depth", "Zback"};
    static const char* const xyz[] = {"R",  "Red", "G",  "Green", "B",  "Blue", "X",  "Y",     "Z",    "real", "imag",
                                      "A",  "Alpha", "AR", "RA",  "AG", "GA",   "AB", "BA",    "Depth", "Zback"};
    std::stable_sort(channels.begin(), channels.end(), [](const auto& a, const auto& b) { return a.layer < b.layer; });
    for (auto begin = channels.begin(); begin != channels.end();) {
        auto end = begin + 1;
        while (end != channels.end() && end->layer == begin->layer) ++end;
        auto has = [&](const char* name) {
            return std::any_of(begin, end, [&](const SortedChannel& c) { return iequals(c.suffix, name); });
        };
        const bool position = has("X") && (has("Y") || has("Z"));
        for (auto c = begin; c != end; ++c) {
            const auto& names = position ? std::vector<const char*>(std::begin(xyz), std::end(xyz))
                                         : std::vector<const char*>(std::begin(usual), std::end(usual));
            for (size_t i = 0; i < names.size(); ++i)
                if (iequals(c->suffix, names[i])) {
                    c->special = int(i);
                    break;
                }
        }
        std::sort(begin, end, [](const SortedChannel& a, const SortedChannel& b) {
            if (a.special != b.special) return a.special < b.special;
            return a.suffix < b.suffix;
        });
        begin = end;
    }
}

std::string numberText(float v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", double(v));
    return text;
}

SourceAttribute textAttribute(std::string name, std::string text) {
    SourceAttribute a;
    a.name = std::move(name);
    a.text = std::move(text);
    return a;
}

SourceAttribute floatAttribute(std::string name, float v) {
    SourceAttribute a;
    a.name = std::move(name);
    a.text = numberText(v);
    a.isFloat = a.hasNumber = true;
    a.number = v;
    return a;
}

const char* compressionName(Imf::Compression c) {
    switch (c) {
        case Imf::NO_COMPRESSION: return "none";
        case Imf::RLE_COMPRESSION: return "rle";
        case Imf::ZIPS_COMPRESSION: return "zips";
        case Imf::ZIP_COMPRESSION: return "zip";
        case Imf::PIZ_COMPRESSION: return "piz";
        default: return nullptr;
    }
}

// The header's attributes as OpenImageIO 2.4 lists them; false where it would list one differently.
bool presentAttributes(const Imf::Header& header, bool mipmapped, bool roundDown, SourceSpec& spec) {
    auto& out = spec.extra_attribs;
    out.push_back(textAttribute("oiio:ColorSpace", "Linear"));
    if (mipmapped) {
        out.push_back(textAttribute("openexr:roundingmode", roundDown ? "0" : "1"));
        out.push_back(textAttribute("textureformat", "Plain Texture"));
    }
    const char* compression = compressionName(header.compression());
    if (!compression) return false;
    out.push_back(textAttribute("compression", compression));
    for (auto it = header.begin(); it != header.end(); ++it) {
        const std::string name = it.name();
        const std::string type = it.attribute().typeName();
        // Skipped by OpenImageIO too (the part's type was checked to match how it is read).
        if (name == "channels" || name == "compression" || name == "dataWindow" || name == "displayWindow" ||
            name == "tiles" || name == "type")
            continue;
        if (name == "lineOrder") {
            if (header.lineOrder() != Imf::INCREASING_Y) return false;
            continue;
        }
        if (name == "pixelAspectRatio" && type == "float") {
            out.push_back(floatAttribute("PixelAspectRatio", header.pixelAspectRatio()));
            continue;
        }
        if (name == "screenWindowCenter" && type == "v2f") {
            const Imath::V2f c = header.screenWindowCenter();
            out.push_back(textAttribute(name, numberText(c.x) + ", " + numberText(c.y)));
            continue;
        }
        // The capture date, which OpenImageIO's own writer records (from DateTime), goes back under that name.
        const std::string shown = name == "capDate" ? "DateTime" : name;
        // Names OpenImageIO renames or skips, and every other type, are its to present.
        static const char* const renamed[] = {"cameraTransform", "comments", "owner", "xDensity",
                                              "expTime", "aperture", "chunkCount", "maxSamplesPerPixel",
                                              "dwaCompressionLevel", "envmap", "tiledesc", "preview",
                                              "name", "timeCode", "keyCode"};
        if (std::any_of(std::begin(renamed), std::end(renamed), [&](const char* r) { return name == r; })) return false;
        if (type == "string") {
            const auto* s = header.findTypedAttribute<Imf::StringAttribute>(name);
            if (!s || s->value().empty()) return false;
            out.push_back(textAttribute(shown, s->value()));
        } else if (type == "float") {
            const auto* f = header.findTypedAttribute<Imf::FloatAttribute>(name);
            if (!f) return false;
            out.push_back(floatAttribute(shown, f->value()));
        } else if (type == "int") {
            const auto* i = header.findTypedAttribute<Imf::IntAttribute>(name);
            if (!i) return false;
            out.push_back(textAttribute(shown, std::to_string(i->value())));  // get_float gives no number for an int
        } else {
            return false;
        }
    }
    out.push_back(textAttribute("oiio:subimages", "1"));
    return true;
}

class ExrSource final : public ImageSource {
public:
    ExrSource(const unsigned char* bytes, size_t size, std::string path)
        : bytes_(bytes), size_(size), path_(std::move(path)), stream_(bytes, size) {}

    // Opens the file; false (nothing thrown) where OpenImageIO is to read it instead.
    bool open() {
        try {
            Imf::MultiPartInputFile parts(stream_);
            if (parts.parts() != 1) return false;
            stream_.seekg(0);
            const Imf::Header& probe = parts.header(0);
            tiled_ = probe.hasTileDescription();
            if (probe.hasType() && probe.type() != (tiled_ ? Imf::TILEDIMAGE : Imf::SCANLINEIMAGE)) return false;
            if (tiled_) tiles_ = std::make_unique<Imf::TiledInputFile>(stream_);
            else lines_ = std::make_unique<Imf::InputFile>(stream_);
            const Imf::Header& header = tiled_ ? tiles_->header() : lines_->header();
            bool mipmapped = false, roundDown = true;
            levels_ = 1;
            if (tiled_) {
                const Imf::TileDescription& td = tiles_->header().tileDescription();
                if (td.mode == Imf::RIPMAP_LEVELS) return false;
                mipmapped = td.mode == Imf::MIPMAP_LEVELS;
                roundDown = td.roundingMode == Imf::ROUND_DOWN;
                levels_ = tiles_->numLevels();
                top_.tile_width = int(td.xSize);
                top_.tile_height = int(td.ySize);
            }
            if (!channelsOf(header) || !presentAttributes(header, mipmapped, roundDown, top_)) return false;
            const Imath::Box2i dw = header.dataWindow();
            top_.width = dw.max.x - dw.min.x + 1;
            top_.height = dw.max.y - dw.min.y + 1;
            current_ = top_;
            return true;
        } catch (const std::exception&) {
            return false;
        }
    }

    const char* format_name() const override { return fallback_ ? fallback_->format_name() : "openexr"; }
    const char* decoder() const override { return fallback_ ? fallback_->decoder() : "openexr"; }
    const SourceSpec& spec() const override { return current_; }

    bool seekLevel(int level) override {
        if (level < 0 || level >= levels_) return false;
        current_ = top_;
        if (tiled_) {
            current_.width = tiles_->levelWidth(level);
            current_.height = tiles_->levelHeight(level);
        }
        return true;
    }

    bool read(int level, int chBegin, int chEnd, float* dst, std::string& error) override {
        if (fallback_) return fallback_->read(level, chBegin, chEnd, dst, error);
        try {
            const Imath::Box2i dw = tiled_ ? tiles_->dataWindowForLevel(level) : lines_->header().dataWindow();
            const size_t xStride = sizeof(float) * size_t(chEnd - chBegin);
            const size_t yStride = xStride * size_t(dw.max.x - dw.min.x + 1);
            char* origin = reinterpret_cast<char*>(dst) - ptrdiff_t(dw.min.x) * ptrdiff_t(xStride) -
                           ptrdiff_t(dw.min.y) * ptrdiff_t(yStride);
            Imf::FrameBuffer frame;
            for (int c = chBegin; c < chEnd; ++c)
                frame.insert(order_[size_t(c)], Imf::Slice(Imf::FLOAT, origin + sizeof(float) * size_t(c - chBegin),
                                                           xStride, yStride));
            if (tiled_) {
                tiles_->setFrameBuffer(frame);
                tiles_->readTiles(0, tiles_->numXTiles(level) - 1, 0, tiles_->numYTiles(level) - 1, level);
            } else {
                lines_->setFrameBuffer(frame);
                lines_->readPixels(dw.min.y, dw.max.y);
            }
            return true;
        } catch (const std::exception&) {
            // A file OpenEXR refuses part way: OpenImageIO reads it again and says what is wrong, as it
            // always has.
            tiles_.reset();
            lines_.reset();
            bool createFailed = false;
            auto module = formatModule(path_, "cannot be read");
            if (!module) {
                error = module.error().what;
                return false;
            }
            fallback_ = (*module)->open("openexr", bytes_, size_, path_, error, createFailed);
            if (!fallback_) return false;
            return fallback_->read(level, chBegin, chEnd, dst, error);
        }
    }

    void close() override {
        if (fallback_) fallback_->close();
        tiles_.reset();
        lines_.reset();
    }

private:
    bool channelsOf(const Imf::Header& header) {
        std::vector<SortedChannel> channels;
        Imf::PixelType type = Imf::NUM_PIXELTYPES;
        for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
            const Imf::Channel& c = it.channel();
            if (c.xSampling != 1 || c.ySampling != 1 || (c.type != Imf::HALF && c.type != Imf::FLOAT)) return false;
            if (type != Imf::NUM_PIXELTYPES && c.type != type) return false;
            type = c.type;
            SortedChannel s;
            s.full = it.name();
            const size_t dot = s.full.rfind('.');
            s.layer = dot == std::string::npos ? std::string() : s.full.substr(0, dot);
            s.suffix = dot == std::string::npos ? s.full : s.full.substr(dot + 1);
            channels.push_back(std::move(s));
        }
        if (channels.empty()) return false;
        const auto luma = [&](const char* n) {
            return std::any_of(channels.begin(), channels.end(), [&](const auto& c) { return iequals(c.suffix, n); });
        };
        if (luma("RY") || luma("BY")) return false;  // luminance-chroma: OpenImageIO converts it to RGB
        sortChannels(channels);
        top_.nchannels = int(channels.size());
        top_.format = type == Imf::HALF ? "half" : "float";
        for (const SortedChannel& c : channels) {
            if (top_.alpha_channel < 0 && (iequals(c.suffix, "A") || iequals(c.suffix, "Alpha")))
                top_.alpha_channel = int(top_.channelnames.size());
            top_.channelnames.push_back(c.full);
            order_.push_back(c.full);
        }
        return true;
    }

    const unsigned char* bytes_;
    size_t size_;
    std::string path_;
    BytesStream stream_;
    bool tiled_ = false;
    int levels_ = 1;
    std::unique_ptr<Imf::TiledInputFile> tiles_;
    std::unique_ptr<Imf::InputFile> lines_;
    std::vector<std::string> order_;
    SourceSpec top_, current_;
    std::unique_ptr<ImageSource> fallback_;
};

}  // namespace

std::unique_ptr<ImageSource> openExrDirectly(const unsigned char* bytes, size_t size, const std::string& path) {
    auto source = std::make_unique<ExrSource>(bytes, size, path);
    if (!source->open()) return nullptr;
    return source;
}

}  // namespace heightpack::detail
