#include "input_format.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "heightpack/io/files.hpp"
#include "heightpack/io/read.hpp"
#include "image_input.hpp"

namespace heightpack::detail {

namespace {

bool startsWith(const std::vector<unsigned char>& b, const char* magic, size_t n) {
    return b.size() >= n && std::memcmp(b.data(), magic, n) == 0;
}

// Formats heightpack recognises but does not read, so the refusal can name what the file is.
const char* refusedFormatName(const std::vector<unsigned char>& b) {
    if (startsWith(b, "SDPX", 4) || startsWith(b, "XPDS", 4)) return "a DPX file";
    if (startsWith(b, "GIF8", 4)) return "a GIF";
    if (b.size() >= 12 && startsWith(b, "RIFF", 4) && std::memcmp(b.data() + 8, "WEBP", 4) == 0) return "a WebP image";
    if (startsWith(b, "DDS ", 4)) return "a DDS texture";
    if (startsWith(b, "\xABKTX 20\xBB", 8)) return "a KTX2 texture";
    if (startsWith(b, "\x80\x2A\x5F\xD7", 4) || startsWith(b, "\xD7\x5F\x2A\x80", 4)) return "a Cineon file";
    if (startsWith(b, "\x00\x00\x00\x0CjP  ", 8) || startsWith(b, "\xFF\x4F\xFF\x51", 4)) return "a JPEG 2000 file";
    if (startsWith(b, "\x01\xDA", 2)) return "an SGI image";
    if (b.size() >= 12 && std::memcmp(b.data() + 4, "ftyp", 4) == 0) return "a HEIF/AVIF image or a video";
    return nullptr;
}

// Targa has no magic number: a .tga name and a header whose colour-map, image-type and depth fields hold
// values the format defines.
bool plausibleTarga(const std::string& path, const std::vector<unsigned char>& b) {
    const std::string ext = lowerExtension(path);
    if ((ext != ".tga" && ext != ".tpic") || b.size() < 18) return false;
    const unsigned colourMap = b[1], type = b[2], depth = b[16];
    const bool knownType = type == 1 || type == 2 || type == 3 || type == 9 || type == 10 || type == 11;
    return colourMap <= 1 && knownType && (depth == 8 || depth == 15 || depth == 16 || depth == 24 || depth == 32);
}

std::optional<InputFormat> sniff(const std::string& path, const std::vector<unsigned char>& b) {
    if (startsWith(b, "\x89PNG\r\n\x1A\n", 8)) return InputFormat::Png;
    if (startsWith(b, "\xFF\xD8\xFF", 3)) return InputFormat::Jpeg;
    if (startsWith(b, "II*\0", 4) || startsWith(b, "MM\0*", 4) || startsWith(b, "II+\0", 4) || startsWith(b, "MM\0+", 4))
        return InputFormat::Tiff;
    if (startsWith(b, "\x76\x2F\x31\x01", 4)) return InputFormat::Exr;
    if (startsWith(b, "BM", 2) && b.size() >= 26) return InputFormat::Bmp;
    if (startsWith(b, "8BPS", 4)) return InputFormat::Psd;
    if (startsWith(b, "#?RADIANCE", 10) || startsWith(b, "#?RGBE", 6)) return InputFormat::Hdr;
    // P1-P6 (PBM, PGM, PPM) and PF, Pf (PFM), each followed by white space.
    if (b.size() >= 3 && b[0] == 'P' && std::strchr("123456Ff", b[1]) && b[1] != 0 && std::strchr(" \t\r\n", b[2]) && b[2] != 0)
        return InputFormat::Pnm;
    if (plausibleTarga(path, b)) return InputFormat::Targa;
    return std::nullopt;
}

// ---- JPEG: marker segments --------------------------------------------------------------------------

// Copies a JPEG without the segments heights do not need: before the first scan only the ones libjpeg
// needs to decode (frame, tables, restart interval, JFIF's APP0 and Adobe's APP14, which says how colours
// were transformed) are kept; after it everything is kept but the metadata segments between scans, which
// libjpeg saves for OpenImageIO too when it reads a progressive file's every scan on opening it.
// OpenImageIO 2.4 parses EXIF (APP1), ICC (APP2) and IPTC (APP13) itself, and its IPTC parser reads past
// its buffer on a crafted segment; heights need none of them.
Status stripJpegMetadata(const std::string& path, std::vector<unsigned char>& bytes) {
    const size_t n = bytes.size();
    std::vector<unsigned char> out(bytes.begin(), bytes.begin() + 2);  // SOI
    size_t at = 2;
    bool inScans = false;
    const auto damaged = [&](const std::string& what) {
        return badInput(path, "is a damaged JPEG: " + what, "export it again");
    };
    const auto copy = [&](size_t from, size_t to) { out.insert(out.end(), bytes.begin() + from, bytes.begin() + to); };
    const auto finish = [&] {
        bytes = std::move(out);
        return Status(Done{});
    };
    while (true) {
        // Markers are found exactly as libjpeg's next_marker (and its entropy decoder, inside a scan) finds
        // them, so that the segments dropped here are the ones it would have read: bytes before a 0xFF are
        // skipped (a file that decodes elsewhere decodes here) or, in the scans, are the coded data; then
        // fill bytes; a 0xFF 0x00 is no marker at all: the search goes on.
        const size_t from = at;
        while (at < n && bytes[at] != 0xFF) ++at;
        if (inScans) copy(from, at);
        const size_t markerAt = at;
        while (at < n && bytes[at] == 0xFF) ++at;  // fill bytes
        if (at >= n) {
            if (!inScans) return damaged("it ends before its first scan");
            copy(markerAt, n);
            return finish();
        }
        const unsigned marker = bytes[at++];
        const bool standalone = marker == 0x00 || marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8);
        if (standalone) {
            if (inScans) copy(markerAt, at);
            else if (marker != 0x00) out.push_back(0xFF), out.push_back(static_cast<unsigned char>(marker));
            continue;
        }
        if (marker == 0xD9) {  // end of image: libjpeg reads nothing after it
            if (!inScans) return damaged("it ends before its first scan");
            copy(markerAt, n);
            return finish();
        }
        if (at + 2 > n) return damaged("a marker segment runs past the end of the file");
        const size_t length = size_t(bytes[at]) << 8 | bytes[at + 1];
        if (length < 2 || at + length > n) return damaged("a marker segment runs past the end of the file");
        const bool metadata = (marker >= 0xE1 && marker <= 0xEF && marker != 0xEE) || marker == 0xFE;
        if (!metadata) {
            out.push_back(0xFF), out.push_back(static_cast<unsigned char>(marker));
            copy(at, at + length);
        }
        at += length;
        if (marker == 0xDA) inScans = true;  // start of scan: its coded data follows
    }
}

// ---- PNG: chunk lengths ------------------------------------------------------------------------------

// Walks the chunks to IEND: each must fit in the bytes that follow it. libpng allocates a text or
// metadata chunk's claimed length before reading it, so a 1 kB file could ask for gigabytes.
Status judgePngChunks(const std::string& path, const std::vector<unsigned char>& bytes) {
    size_t at = 8;
    while (at + 8 <= bytes.size()) {
        const uint32_t length = uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 | uint32_t(bytes[at + 2]) << 8 | bytes[at + 3];
        const std::string type(reinterpret_cast<const char*>(bytes.data() + at + 4), 4);
        if (length > 0x7FFFFFFFu || uint64_t(length) + 12 > bytes.size() - at) {
            std::string printable;
            for (char ch : type) printable += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '?';
            return badInput(path,
                            "is a damaged or truncated PNG: chunk '" + printable + "' claims " + std::to_string(length) +
                                " bytes, the file has " + std::to_string(bytes.size() - at - 8) + " left",
                            "export it again");
        }
        if (type == "IEND") return Done{};
        at += size_t(length) + 12;
    }
    return badInput(path, "is a truncated PNG: it ends before its IEND chunk", "export it again");
}

}  // namespace

Result<InputBytes> readInputBytes(const std::string& path) {
    InputBytes input;
    auto fd = openReadable(path);
    if (!fd) return fd.error();
    std::unique_ptr<FILE, int (*)(FILE*)> f(::fdopen(*fd, "rb"), std::fclose);
    if (!f) ::close(*fd);
    struct stat st {};
    if (!f || ::fstat(::fileno(f.get()), &st) != 0)
        return badInput(path, std::string("cannot be opened: ") + std::strerror(errno), "check the file");
    try {
        input.bytes.resize(size_t(st.st_size));
    } catch (const std::bad_alloc&) {
        return badInput(path, "is too large for this machine's memory", "split or downsize the map");
    }
    if (std::fread(input.bytes.data(), 1, input.bytes.size(), f.get()) != input.bytes.size())
        return badInput(path, "could not be read whole (did it change while being read?)", "check the file");
    if (const auto format = sniff(path, input.bytes)) {
        input.format = *format;
        return input;
    }
    if (const char* what = refusedFormatName(input.bytes))
        return badInput(path, std::string("is ") + what + ", a format heightpack does not read", kExportHint);
    return badInput(path, "is not an image in a format heightpack reads (" + joinedNames<InputFormat>() + ")", kExportHint);
}

Status judgeHeader(const std::string& path, InputBytes& input, const SizeLimits& limits) {
    switch (input.format) {
        case InputFormat::Exr: return judgeExrHeader(path, input.bytes, limits);
        case InputFormat::Jpeg: return stripJpegMetadata(path, input.bytes);
        case InputFormat::Png: return judgePngChunks(path, input.bytes);
        default: return Done{};
    }
}

Status judgeDecodedSize(const std::string& path, int64_t texels, int channels, uint64_t fileBytes) {
    const uint64_t floats = uint64_t(texels) * uint64_t(std::max(channels, 1)) * sizeof(float);
    if (floats / (uint64_t(1) << 17) <= fileBytes) return Done{};
    return badInput(path,
                    "claims " + std::to_string(texels) + " texels of " + std::to_string(channels) + " channels, more than its " +
                        std::to_string(fileBytes) + " bytes can hold",
                    "the file is damaged: export it again");
}

}  // namespace heightpack::detail

namespace heightpack {

std::string readableFormats() {
    std::string text;
    for (const EnumName<detail::InputFormat>& e : NameTable<detail::InputFormat>::entries)
        text += (text.empty() ? "" : ", ") + std::string(e.description);
    return text;
}

}  // namespace heightpack
