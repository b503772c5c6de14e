#include "png_fast.hpp"

#include <libdeflate.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "heightpack/core/parallel.hpp"

#include "png_format.hpp"

namespace heightpack::detail {

namespace {

uint32_t be32(const unsigned char* p) {
    return (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | uint32_t(p[3]);
}

// Undoes one row's filter. BPP bytes per pixel, known at compile time: byte i depends on byte i - BPP,
// so the BPP chains within a pixel are independent and the unrolled inner loop runs them side by side.
template <int BPP>
bool unfilterRow(int filter, unsigned char* cur, const unsigned char* up, size_t n) {
    auto byte = [](int v) { return static_cast<unsigned char>(v); };
    switch (filter) {
        case 0: return true;
        case 1:
            for (size_t i = BPP; i < n; i += BPP)
                for (int b = 0; b < BPP; ++b) cur[i + b] = byte(cur[i + b] + cur[i + b - BPP]);
            return true;
        case 2:
            for (size_t i = 0; i < n; ++i) cur[i] = byte(cur[i] + up[i]);
            return true;
        case 3:
            for (int b = 0; b < BPP; ++b) cur[b] = byte(cur[b] + (up[b] >> 1));
            for (size_t i = BPP; i < n; i += BPP)
                for (int b = 0; b < BPP; ++b) cur[i + b] = byte(cur[i + b] + ((int(cur[i + b - BPP]) + up[i + b]) >> 1));
            return true;
        case 4:
            for (int b = 0; b < BPP; ++b) cur[b] = byte(cur[b] + up[b]);
            for (size_t i = BPP; i < n; i += BPP)
                for (int b = 0; b < BPP; ++b)
                    cur[i + b] = byte(cur[i + b] + paeth(cur[i + b - BPP], up[i + b], up[i + b - BPP]));
            return true;
        default: return false;
    }
}

// Undoes PNG's per-row filters in place (spec section 9). rows holds, per row, a filter byte and rowBytes
// bytes (a whole number of pixels). The row above the first is all zeros.
template <int BPP>
bool unfilter(unsigned char* rows, int height, size_t rowBytes) {
    const std::vector<unsigned char> zeros(rowBytes, 0);
    const unsigned char* up = zeros.data();
    for (int y = 0; y < height; ++y) {
        unsigned char* row = rows + size_t(y) * (rowBytes + 1);
        if (!unfilterRow<BPP>(row[0], row + 1, up, rowBytes)) return false;
        up = row + 1;
    }
    return true;
}

bool unfilter(unsigned char* rows, int height, size_t rowBytes, int bpp) {
    switch (bpp) {
        case 1: return unfilter<1>(rows, height, rowBytes);
        case 2: return unfilter<2>(rows, height, rowBytes);
        case 4: return unfilter<4>(rows, height, rowBytes);
        default: return false;
    }
}

}  // namespace

std::optional<Image> decodeGreyPng(const std::vector<unsigned char>& file, int width, int height, int channel,
                                   int threads) {
    if (file.size() < 8 + 25 || std::memcmp(file.data(), kPngSignature, 8) != 0) return std::nullopt;
    const unsigned char* data = file.data();
    const size_t size = file.size();

    // Chunk order as the PNG specification (section 5.6) fixes it: IHDR first and once, the IDAT chunks
    // one unbroken run, IEND last. Anything else unusual (a critical chunk this decoder does not know,
    // a palette in a grey image) goes to the library decoder, which knows every rule.
    int bitDepth = 0, colourType = -1;
    std::vector<unsigned char> compressed;
    compressed.reserve(size);
    bool ended = false, sawHeader = false, inData = false, dataDone = false;
    for (size_t p = 8; p + 12 <= size && !ended;) {
        const uint32_t length = be32(data + p);
        if (length > 0x7fffffffu || length > size - p - 12) return std::nullopt;  // truncated
        const unsigned char* type = data + p + 4;
        const unsigned char* body = data + p + 8;
        if (libdeflate_crc32(0, type, length + 4) != be32(body + length)) return std::nullopt;
        const bool isHeader = std::memcmp(type, "IHDR", 4) == 0, isData = std::memcmp(type, "IDAT", 4) == 0;
        if (sawHeader == isHeader) return std::nullopt;  // IHDR not first, or a second one
        if (inData && !isData) dataDone = true;
        if (isData && dataDone) return std::nullopt;  // the IDAT run was interrupted
        inData = isData;
        if (isHeader) {
            sawHeader = true;
            if (length != 13 || be32(body) != uint32_t(width) || be32(body + 4) != uint32_t(height)) return std::nullopt;
            bitDepth = body[8];
            colourType = body[9];
            if (body[10] != 0 || body[11] != 0 || body[12] != 0) return std::nullopt;  // interlaced or unknown
        } else if (isData) {
            compressed.insert(compressed.end(), body, body + length);
        } else if (std::memcmp(type, "IEND", 4) == 0) {
            ended = true;
        } else if (!(type[0] & 0x20)) {
            return std::nullopt;  // a critical chunk (PLTE in a grey image, or one unknown here)
        }
        p += size_t(length) + 12;
    }
    const int samples = colourType == 0 ? 1 : colourType == 4 ? 2 : 0;
    if (!ended || samples == 0 || channel >= samples || (bitDepth != 8 && bitDepth != 16)) return std::nullopt;

    const int bytesPerSample = bitDepth / 8, bpp = samples * bytesPerSample;
    const size_t rowBytes = size_t(width) * bpp;
    std::vector<unsigned char> rows((rowBytes + 1) * height);
    std::unique_ptr<libdeflate_decompressor, void (*)(libdeflate_decompressor*)> inflater(
        libdeflate_alloc_decompressor(), libdeflate_free_decompressor);
    if (!inflater) return std::nullopt;
    // LIBDEFLATE_SUCCESS with a null actual size means the stream filled the buffer exactly.
    if (libdeflate_zlib_decompress(inflater.get(), compressed.data(), compressed.size(), rows.data(), rows.size(),
                                   nullptr) != LIBDEFLATE_SUCCESS)
        return std::nullopt;
    if (!unfilter(rows.data(), height, rowBytes, bpp)) return std::nullopt;

    Image image(width, height, 1);
    const float scale = bitDepth == 16 ? 1.0f / 65535.0f : 1.0f / 255.0f;
    parallelFor(height, threads, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            const unsigned char* row = rows.data() + size_t(y) * (rowBytes + 1) + 1 + channel * bytesPerSample;
            float* out = image.row(y);
            if (bitDepth == 16)
                for (int x = 0; x < width; ++x)
                    out[x] = float((row[size_t(x) * bpp] << 8) | row[size_t(x) * bpp + 1]) * scale;
            else
                for (int x = 0; x < width; ++x) out[x] = float(row[size_t(x) * bpp]) * scale;
        }
    });
    return image;
}

}  // namespace heightpack::detail
