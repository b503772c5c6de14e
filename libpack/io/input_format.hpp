// Internal: which image formats heightpack reads, decided from a file's first bytes before any
// third-party reader sees it, and the header checks that run before those readers allocate anything.
//
// OpenImageIO tries every reader it knows on a file that the one its name suggests refuses, and each of
// them is attack surface (OpenImageIO 2.4's DPX reader aborts on crafted headers; OpenEXR allocates a
// string attribute's claimed length). heightpack names the reader itself, from the magic bytes, and only
// for the formats height maps come in.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/core/names.hpp"
#include "heightpack/core/result.hpp"

namespace heightpack::detail {

struct SizeLimits;

// The formats heightpack reads. Everything else (DPX, GIF, WebP, DDS as an input, ...) is refused.
enum class InputFormat { Png, Jpeg, Tiff, Exr, Targa, Bmp, Psd, Hdr, Pnm };

}  // namespace heightpack::detail

namespace heightpack {
// Each format by the name of the OpenImageIO reader that decodes it, and as a person names it (help
// texts and the README list them: readableFormats). A JPEG's metadata segments are removed before decoding.
template <>
struct NameTable<detail::InputFormat> {
    static constexpr EnumName<detail::InputFormat> entries[] = {
        {detail::InputFormat::Png, "png", "PNG"},
        {detail::InputFormat::Jpeg, "jpeg", "JPEG"},
        {detail::InputFormat::Tiff, "tiff", "TIFF (and BigTIFF)"},
        {detail::InputFormat::Exr, "openexr", "OpenEXR (scanline or tiled)"},
        {detail::InputFormat::Targa, "targa", "Targa (.tga)"},
        {detail::InputFormat::Bmp, "bmp", "BMP (uncompressed)"},
        {detail::InputFormat::Psd, "psd", "Photoshop PSD"},
        {detail::InputFormat::Hdr, "hdr", "Radiance HDR"},
        {detail::InputFormat::Pnm, "pnm", "PGM/PPM/PBM/PFM"},
    };
};
}  // namespace heightpack

namespace heightpack::detail {

// The bytes of a file heightpack has already read for judging it, handed to the reader that decodes it
// (so the file is opened once, and what was judged is what is decoded).
struct InputBytes {
    InputFormat format = InputFormat::Png;
    std::vector<unsigned char> bytes;  // the whole file; a JPEG without its metadata segments
};

// A descriptor open for reading on path, a regular non-empty file this user may read (the caller closes
// it); otherwise BadInput saying what path is (missing, a folder, a FIFO or device, unreadable, empty).
// Nothing but a regular file is ever opened.
Result<int> openReadable(const std::string& path);

// Reads path whole (opened once, through openReadable) and decides its format from its first bytes (Targa, which has no magic, from its
// .tga name and a plausible header). Fails with BadInput naming a format heightpack does not read, or
// saying the bytes are no image heightpack knows.
Result<InputBytes> readInputBytes(const std::string& path);

// The hint for a file in a format, or a variant of one, that heightpack does not read.
inline constexpr const char* kExportHint = "export it as PNG, TIFF or EXR";

// For judgeHeader (exr_header.cpp): an OpenEXR file's headers, each attribute read as OpenEXR 3.1 reads it
// and required to end where its size says, the data windows against limits, the offset tables against the
// file's size.
Status judgeExrHeader(const std::string& path, const std::vector<unsigned char>& bytes, const SizeLimits& limits);

// Judges what a header claims before any reader allocates for it: for an EXR, every attribute's size
// against the bytes that follow and against what OpenEXR reads of it, the data window against limits,
// and the chunk offset table against the file's size; for a PNG, every chunk's length against the bytes left (libpng allocates a text chunk's
// claimed length); for a JPEG, the marker segments' lengths, and the metadata segments are dropped from
// input.bytes: no APPn but JFIF and Adobe, no comment, reaches the decoder. Fails with BadInput.
Status judgeHeader(const std::string& path, InputBytes& input, const SizeLimits& limits);

// Fails with BadInput when a file of fileBytes cannot hold an image of texels x channels: no codec
// heightpack reads (deflate's 1032:1 at best, on 1-bit samples) decodes a byte into more than 2^17 bytes
// of floats, so a 347-byte TIFF that claims 1.2 GB of samples is damaged, judged before it is decoded.
Status judgeDecodedSize(const std::string& path, int64_t texels, int channels, uint64_t fileBytes);

}  // namespace heightpack::detail
