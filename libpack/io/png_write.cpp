#include "png_write.hpp"

#include <libdeflate.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <utility>

#include "heightpack/core/parallel.hpp"

#include "png_format.hpp"

namespace heightpack::detail {

namespace {

// libpng's and OpenImageIO's default zlib level; libdeflate's level 6 makes a file a little smaller. On
// noisy 16-bit samples (a sea's heights) level 1 is both smaller (74% of the raw bytes against 76% on a
// 4096^2 sea) and 1.6x faster; on a smooth 16-bit sum of waves 2% larger for half the time (0.23 s against
// 0.44 s at 4096^2); on smooth 8-bit paintings 10-17% larger. So each image takes the faster level unless
// a sample of its rows says the slower one saves at least kWorthSaving of the bytes.
constexpr int kDeflateLevel = 6, kFastDeflateLevel = 1;
constexpr double kWorthSaving = 0.05;
constexpr size_t kLevelSampleBytes = size_t(1) << 20;
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

// One filter type over a row into trial; returns the sum of the filtered bytes taken as signed
// magnitudes. A template per type, so that no branch on the type sits in the loop (which then vectorises).
template <int type>
uint64_t filterAs(const unsigned char* row, const unsigned char* above, size_t stride, size_t bpp, unsigned char* trial) {
    auto predicted = [](int a, int b, int c) {
        if constexpr (type == 0) return 0;
        else if constexpr (type == 1) return a;
        else if constexpr (type == 2) return b;
        else if constexpr (type == 3) return (a + b) / 2;
        else return paeth(a, b, c);
    };
    uint64_t sum = 0;
    auto put = [&](size_t i, int a, int b, int c) {
        const unsigned char v = static_cast<unsigned char>(row[i] - predicted(a, b, c));
        trial[i] = v;
        sum += v < 128 ? v : 256 - v;
    };
    const size_t lead = std::min(bpp, stride);
    if (above) {
        for (size_t i = 0; i < lead; ++i) put(i, 0, above[i], 0);
        for (size_t i = lead; i < stride; ++i) put(i, row[i - bpp], above[i], above[i - bpp]);
    } else {
        for (size_t i = 0; i < lead; ++i) put(i, 0, 0, 0);
        for (size_t i = lead; i < stride; ++i) put(i, row[i - bpp], 0, 0);
    }
    return sum;
}

// Row y's filter type byte and filtered bytes into out (1 + stride bytes): the filter of the five with the
// least sum of the filtered bytes taken as signed magnitudes. bpp: bytes per pixel.
void filterRow(const unsigned char* row, const unsigned char* above, size_t stride, int bpp, unsigned char* out,
               std::vector<unsigned char>& trial) {
    trial.resize(stride);
    using Filter = uint64_t (*)(const unsigned char*, const unsigned char*, size_t, size_t, unsigned char*);
    static constexpr Filter filters[5] = {filterAs<0>, filterAs<1>, filterAs<2>, filterAs<3>, filterAs<4>};
    uint64_t best = UINT64_MAX;
    for (int type = 0; type < 5; ++type) {
        const uint64_t sum = filters[type](row, above, stride, size_t(bpp), trial.data());
        if (sum < best) {
            best = sum;
            out[0] = static_cast<unsigned char>(type);
            std::copy(trial.begin(), trial.end(), out + 1);
        }
    }
}

}  // namespace

GreyPngPixels compressGreyPngPixels(const Image& image, int bits, int threads) {
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
                // Rounded half up by the cast (the value is not negative): libm's round is a call per texel.
                const unsigned v = static_cast<unsigned>(std::clamp(image.at(x, y) * top, 0.0f, top) + 0.5f);
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
    using Deflater = std::unique_ptr<libdeflate_compressor, void (*)(libdeflate_compressor*)>;
    auto compressor = [](int level) {
        Deflater d(libdeflate_alloc_compressor(level), libdeflate_free_compressor);
        if (!d) throw std::bad_alloc();
        return d;
    };
    Deflater deflater = compressor(kDeflateLevel);
    if (filtered.size() > 2 * kLevelSampleBytes) {  // the middle rows: the first may be all flat
        Deflater fast = compressor(kFastDeflateLevel);
        const unsigned char* sample = filtered.data() + (filtered.size() - kLevelSampleBytes) / 2;
        std::vector<unsigned char> out(libdeflate_zlib_compress_bound(deflater.get(), kLevelSampleBytes));
        const size_t slow = libdeflate_zlib_compress(deflater.get(), sample, kLevelSampleBytes, out.data(), out.size());
        const size_t quick = libdeflate_zlib_compress(fast.get(), sample, kLevelSampleBytes, out.data(), out.size());
        if (double(slow) > (1 - kWorthSaving) * double(quick)) deflater = std::move(fast);
    }
    std::vector<unsigned char> compressed(libdeflate_zlib_compress_bound(deflater.get(), filtered.size()));
    compressed.resize(libdeflate_zlib_compress(deflater.get(), filtered.data(), filtered.size(), compressed.data(), compressed.size()));
    filtered = {};
    return {w, h, bits, std::move(compressed)};
}

std::vector<unsigned char> assembleGreyPng(const GreyPngPixels& pixels, const std::vector<std::pair<std::string, std::string>>& text) {
    const std::vector<unsigned char>& compressed = pixels.compressed;
    std::vector<unsigned char> png(std::begin(kPngSignature), std::end(kPngSignature));
    std::vector<unsigned char> header;
    put32(header, static_cast<uint32_t>(pixels.width));
    put32(header, static_cast<uint32_t>(pixels.height));
    header.insert(header.end(), {static_cast<unsigned char>(pixels.bits), 0 /* grey */, 0, 0, 0 /* not interlaced */});
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

std::vector<unsigned char> encodeGreyPng(const Image& image, int bits, const std::vector<std::pair<std::string, std::string>>& text,
                                         int threads) {
    return assembleGreyPng(compressGreyPngPixels(image, bits, threads), text);
}

}  // namespace heightpack::detail
