// Grey PNGs, the height maps painters and heightpack write, decoded by heightpack's own PNG decoder
// (png_fast.hpp) and presented as OpenImageIO 2.4 presents them (channel Y, colour space sRGB, each text
// chunk an attribute in file order), so a process that reads only such PNGs never loads the format module.
// Anything else (colour, alpha, a palette, a chunk OpenImageIO turns into attributes of its own, a text key
// it renames or decodes, a damaged chunk) is left to OpenImageIO, and so is data that does not inflate: what a bad
// file is told stays the same.
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "format_module_loader.hpp"
#include "png_fast.hpp"
#include "png_source.hpp"

namespace heightpack::detail {

namespace {

uint32_t pngBe32(const unsigned char* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }

// A text chunk's value as OpenImageIO's get_float reads it: a number only when the whole text is one.
SourceAttribute pngTextAttribute(std::string name, std::string text) {
    SourceAttribute a;
    a.name = std::move(name);
    a.text = std::move(text);
    char* end = nullptr;
    const float v = std::strtof(a.text.c_str(), &end);
    a.hasNumber = !a.text.empty() && end == a.text.c_str() + a.text.size();
    a.number = a.hasNumber ? v : 0.0f;
    return a;
}

bool sameIgnoringCase(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
           });
}

// Whether OpenImageIO makes the text chunk key = value an attribute of that name and text, after those
// before it (`so far`): not a key it renames or decodes (a description, author, title, XMP or Exif), not a
// name already there (it would replace that one in place, ignoring case), not text libpng cuts at a NUL,
// and within what libpng keeps (keys of 1 to 79 bytes; a few chunks of modest size). oiiotool's Software
// and Exif:ImageHistory are kept, so the maps it writes are read here.
bool keptAsWritten(const std::string& key, const std::string& value, const std::vector<SourceAttribute>& soFar) {
    constexpr size_t kMostTextChunks = 64, kLongestText = 1 << 16;
    if (key.empty() || key.size() > 79 || value.size() > kLongestText || soFar.size() > kMostTextChunks) return false;
    if (value.find('\0') != std::string::npos) return false;
    for (const char* special : {"Description", "Author", "Title", "XML:com.adobe.xmp", "Raw profile type exif",
                                "oiio:UnassociatedAlpha"})
        if (sameIgnoringCase(key, special)) return false;
    return std::none_of(soFar.begin(), soFar.end(), [&](const SourceAttribute& a) { return sameIgnoringCase(a.name, key); });
}

class PngSource final : public ImageSource {
public:
    explicit PngSource(std::string path) : path_(std::move(path)) {}

    // Reads the header and the text chunks of b; false where OpenImageIO is to read the file instead.
    bool open(const std::vector<unsigned char>& b) {
        data_ = b.data();
        size_ = b.size();
        static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
        if (b.size() < 8 + 25 || std::memcmp(b.data(), signature, 8) != 0) return false;
        spec_.extra_attribs.push_back(pngTextAttribute("oiio:ColorSpace", "sRGB"));
        bool seenData = false;
        for (size_t at = 8; at + 12 <= b.size();) {
            const uint32_t length = pngBe32(&b[at]);
            if (length > b.size() - at - 12) return false;
            const std::string type(reinterpret_cast<const char*>(&b[at + 4]), 4);
            const unsigned char* data = &b[at + 8];
            if (type == "IHDR") {
                if (at != 8 || length != 13) return false;
                spec_.width = int(pngBe32(data));
                spec_.height = int(pngBe32(data + 4));
                const int depth = data[8], colour = data[9], interlace = data[12];
                if (colour != 0 || (depth != 8 && depth != 16) || interlace != 0) return false;
                spec_.format = depth == 8 ? "uint8" : "uint16";
            } else if (type == "tEXt") {
                // Before the image data: OpenImageIO reads the header's chunks only.
                if (seenData) return false;
                const auto* text = reinterpret_cast<const char*>(data);
                const size_t keyLength = strnlen(text, length);
                if (keyLength == length) return false;
                const std::string key(text, keyLength);
                std::string value(text + keyLength + 1, length - keyLength - 1);
                if (!keptAsWritten(key, value, spec_.extra_attribs)) return false;
                spec_.extra_attribs.push_back(pngTextAttribute(key, std::move(value)));
            } else if (type == "oFFs") {
                if (seenData) return false;  // the image's offset, which OpenImageIO keeps out of the attributes
            } else if (type == "IDAT") {
                seenData = true;
            } else if (type == "IEND") {
                break;
            } else {
                return false;
            }
            at += 12 + size_t(length);
        }
        if (spec_.width <= 0 || spec_.height <= 0) return false;
        spec_.nchannels = 1;
        spec_.channelnames = {"Y"};
        spec_.extra_attribs.push_back(pngTextAttribute("oiio:UnassociatedAlpha", "1"));  // as asked of OpenImageIO
        spec_.extra_attribs.back().hasNumber = false;  // an int, which get_float does not convert
        // Every chunk's CRC, their order and the header: what OpenImageIO refuses at open is refused here.
        plan_ = planGreyPng(b, spec_.width, spec_.height, 0);
        return plan_.has_value();
    }

    const char* format_name() const override { return "png"; }
    const char* decoder() const override { return fallback_ ? fallback_->decoder() : "heightpack-png"; }
    const SourceSpec& spec() const override { return spec_; }
    bool seekLevel(int level) override { return level == 0; }

    bool read(int level, int chBegin, int chEnd, float* dst, std::string& error) override {
        if (!fallback_ && level == 0 && chBegin == 0 && chEnd == 1) {
            if (auto image = decodeGreyPng(std::vector<unsigned char>(data_, data_ + size_), *plan_, libraryThreads())) {
                std::memcpy(dst, image->pixels.data(), image->pixels.size() * sizeof(float));
                return true;
            }
        }
        // Data that does not inflate: OpenImageIO reads the file again and says what is wrong, as always.
        if (!fallback_) {
            auto module = formatModule(path_, "cannot be read");
            if (!module) {
                error = module.error().what;
                return false;
            }
            bool createFailed = false;
            fallback_ = (*module)->open("png", data_, size_, path_, error, createFailed);
            if (!fallback_) return false;
        }
        return fallback_->read(level, chBegin, chEnd, dst, error);
    }

    void close() override {
        if (fallback_) fallback_->close();
    }

private:
    const unsigned char* data_ = nullptr;  // the file's bytes, owned by the caller
    size_t size_ = 0;
    std::string path_;
    SourceSpec spec_;
    std::optional<GreyPngPlan> plan_;
    std::unique_ptr<ImageSource> fallback_;
};

}  // namespace

std::unique_ptr<ImageSource> openPngDirectly(const std::vector<unsigned char>& bytes, const std::string& path) {
    auto source = std::make_unique<PngSource>(path);
    if (!source->open(bytes)) return nullptr;
    return source;
}

}  // namespace heightpack::detail
