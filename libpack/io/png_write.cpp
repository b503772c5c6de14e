#include "png_write.hpp"

#include <libdeflate.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iterator>
#include <memory>
#include <stdexcept>

#include "heightpack/core/parallel.hpp"

#include "png_format.hpp"

namespace heightpack::detail {

namespace {

// libpng's and OpenImageIO's default zlib level; libdeflate's level 6 makes a file a little smaller.
constexpr int kDeflateLevel = 6;
// IDAT chunks of this many bytes at most (any size is valid; smaller ones cost 12 bytes each).
constexpr size_t kIdatBytes = size_t(1) << 20;

void put32(std::vector<unsigned char>& out, uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<unsigned char>(v >> shift));
}

void chunk(std::vector<unsigned char>& out, const char type[4], const unsigned char* data, size_t length) {
    put32(out, static_cast<uint32_t>(length));
    const size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data, data + length);
    put32(out, libdeflate_crc32(0, out.data() + start, length + 4));
}

// Row y's filter type byte and filtered bytes into out (1 + stride bytes): the filter of the five with the
// least sum of the filtered bytes taken as signed magnitudes. bpp: bytes per pixel.
void filterRow(const unsigned char* row, const unsigned char* above, size_t stride, int bpp, unsigned char* out,
               std::vector<unsigned char>& trial) {
    trial.resize(stride);
    uint64_t best = UINT64_MAX;
    for (int type = 0; type < 5; ++type) {
        uint64_t sum = 0;
        for (size_t i = 0; i < stride; ++i) {
            const int a = i >= size_t(bpp) ? row[i - bpp] : 0, b = above ? above[i] : 0,
                      c = above && i >= size_t(bpp) ? above[i - bpp] : 0;
            const int predicted = type == 0 ? 0 : type == 1 ? a : type == 2 ? b : type == 3 ? (a + b) / 2 : paeth(a, b, c);
            const unsigned char v = static_cast<unsigned char>(row[i] - predicted);
            trial[i] = v;
            sum += v < 128 ? v : 256 - v;
        }
        if (sum < best) {
            best = sum;
            out[0] = static_cast<unsigned char>(type);
            std::copy(trial.begin(), trial.end(), out + 1);
        }
    }
}

}  // namespace

std::vector<unsigned char> encodeGreyPng(const Image& image, int bits, const std::vector<std::pair<std::string, std::string>>& text,
                                         int threads) {
    const int w = image.width, h = image.height, bpp = bits / 8;
    const size_t stride = size_t(w) * bpp;
    const float top = bits == 8 ? 255.0f : 65535.0f;
    // The samples, big-endian, one row after another; then each row filtered against the raw row above.
    std::vector<unsigned char> samples(stride * h), filtered((stride + 1) * h);
    parallelFor(h, threads, [&](int begin, int end) {
        std::vector<unsigned char> trial;
        for (int y = begin; y < end; ++y) {
            unsigned char* row = &samples[stride * y];
            for (int x = 0; x < w; ++x) {
                const unsigned v = static_cast<unsigned>(std::round(std::clamp(image.at(x, y) * top, 0.0f, top)));
                if (bits == 8) {
                    row[x] = static_cast<unsigned char>(v);
                } else {
                    row[2 * x] = static_cast<unsigned char>(v >> 8);
                    row[2 * x + 1] = static_cast<unsigned char>(v & 0xff);
                }
            }
        }
    });
    parallelFor(h, threads, [&](int begin, int end) {
        std::vector<unsigned char> trial;
        for (int y = begin; y < end; ++y)
            filterRow(&samples[stride * y], y > 0 ? &samples[stride * (y - 1)] : nullptr, stride, bpp,
                      &filtered[(stride + 1) * y], trial);
    });
    samples = {};
    std::unique_ptr<libdeflate_compressor, void (*)(libdeflate_compressor*)> deflater(
        libdeflate_alloc_compressor(kDeflateLevel), libdeflate_free_compressor);
    if (!deflater) throw std::bad_alloc();
    std::vector<unsigned char> compressed(libdeflate_zlib_compress_bound(deflater.get(), filtered.size()));
    compressed.resize(libdeflate_zlib_compress(deflater.get(), filtered.data(), filtered.size(), compressed.data(), compressed.size()));
    filtered = {};

    std::vector<unsigned char> png(std::begin(kPngSignature), std::end(kPngSignature));
    std::vector<unsigned char> header;
    put32(header, static_cast<uint32_t>(w));
    put32(header, static_cast<uint32_t>(h));
    header.insert(header.end(), {static_cast<unsigned char>(bits), 0 /* grey */, 0, 0, 0 /* not interlaced */});
    chunk(png, "IHDR", header.data(), header.size());
    for (const auto& [keyword, value] : text) {
        std::vector<unsigned char> body(keyword.begin(), keyword.end());
        body.push_back(0);
        body.insert(body.end(), value.begin(), value.end());
        chunk(png, "tEXt", body.data(), body.size());
    }
    for (size_t at = 0; at < compressed.size(); at += kIdatBytes)
        chunk(png, "IDAT", compressed.data() + at, std::min(kIdatBytes, compressed.size() - at));
    chunk(png, "IEND", nullptr, 0);
    return png;
}

}  // namespace heightpack::detail
