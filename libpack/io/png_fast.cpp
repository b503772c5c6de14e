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
#include "png_unfilter.hpp"

namespace heightpack::detail {

namespace {

uint32_t be32(const unsigned char* p) {
    return (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | uint32_t(p[3]);
}

// Converts sample `channel` of each of a row's pixels to floats, as OpenImageIO converts them.
void rowToFloats(const unsigned char* row, const GreyPngPlan& plan, float* out) {
    const int bytesPerSample = plan.bitDepth / 8, bpp = plan.samples * bytesPerSample;
    row += plan.channel * bytesPerSample;
    if (plan.bitDepth == 16) {
        const float scale = 1.0f / 65535.0f;
        for (int x = 0; x < plan.width; ++x) out[x] = float((row[size_t(x) * bpp] << 8) | row[size_t(x) * bpp + 1]) * scale;
    } else {
        const float scale = 1.0f / 255.0f;
        for (int x = 0; x < plan.width; ++x) out[x] = float(row[size_t(x) * bpp]) * scale;
    }
}

}  // namespace

std::optional<GreyPngPlan> planGreyPng(const std::vector<unsigned char>& file, int width, int height, int channel) {
    if (file.size() < 8 + 25 || std::memcmp(file.data(), kPngSignature, 8) != 0) return std::nullopt;
    const unsigned char* data = file.data();
    const size_t size = file.size();

    // Chunk order as the PNG specification (section 5.6) fixes it: IHDR first and once, the IDAT chunks
    // one unbroken run, IEND last. Anything else unusual (a critical chunk this decoder does not know,
    // a palette in a grey image) goes to the library decoder, which knows every rule.
    GreyPngPlan plan;
    plan.width = width;
    plan.height = height;
    plan.channel = channel;
    int colourType = -1;
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
        if (isData && !inData) plan.dataBegin = p;
        if (inData && !isData) plan.dataEnd = p;
        inData = isData;
        if (isHeader) {
            sawHeader = true;
            if (length != 13 || be32(body) != uint32_t(width) || be32(body + 4) != uint32_t(height)) return std::nullopt;
            plan.bitDepth = body[8];
            colourType = body[9];
            if (body[10] != 0 || body[11] != 0 || body[12] != 0) return std::nullopt;  // interlaced or unknown
        } else if (std::memcmp(type, "IEND", 4) == 0) {
            ended = true;
        } else if (!isData && !(type[0] & 0x20)) {
            return std::nullopt;  // a critical chunk (PLTE in a grey image, or one unknown here)
        }
        p += size_t(length) + 12;
    }
    plan.samples = colourType == 0 ? 1 : colourType == 4 ? 2 : 0;
    if (!ended || plan.dataEnd == 0 || plan.samples == 0 || channel >= plan.samples ||
        (plan.bitDepth != 8 && plan.bitDepth != 16))
        return std::nullopt;
    return plan;
}

std::optional<Image> decodeGreyPng(std::vector<unsigned char> file, const GreyPngPlan& plan, int threads) {
    const int width = plan.width, height = plan.height;
    // The IDAT bodies gathered into one zlib stream at the front of the file's own bytes (each moves down
    // over the chunk headers before it, so none is overwritten before it moves): no second copy.
    size_t compressed = 0;
    for (size_t p = plan.dataBegin; p < plan.dataEnd;) {
        const size_t length = be32(file.data() + p);
        std::memmove(file.data() + compressed, file.data() + p + 8, length);
        compressed += length;
        p += length + 12;
    }

    // Inflated rows: a filter byte and rowBytes bytes each. Where they fit (all but 16-bit grey + alpha),
    // they go into the tail of the float image itself, and become its floats a row at a time below, so the
    // image and the rows are never held apart: the peak is the file's bytes plus the floats.
    const size_t rowBytes = size_t(width) * plan.samples * (plan.bitDepth / 8), stride = rowBytes + 1;
    const size_t rowsSize = stride * height;
    Image image(width, height, 1);
    const size_t imageBytes = image.pixels.size() * sizeof(float);
    const bool inPlace = rowsSize <= imageBytes;
    std::vector<unsigned char> apart(inPlace ? 0 : rowsSize);
    unsigned char* const rows = inPlace ? reinterpret_cast<unsigned char*>(image.pixels.data()) + (imageBytes - rowsSize)
                                        : apart.data();
    std::unique_ptr<libdeflate_decompressor, void (*)(libdeflate_decompressor*)> inflater(
        libdeflate_alloc_decompressor(), libdeflate_free_decompressor);
    if (!inflater) return std::nullopt;
    // LIBDEFLATE_SUCCESS with a null actual size means the stream filled the buffer exactly.
    if (libdeflate_zlib_decompress(inflater.get(), file.data(), compressed, rows, rowsSize, nullptr) != LIBDEFLATE_SUCCESS)
        return std::nullopt;
    std::vector<unsigned char>().swap(file);  // the compressed bytes are done with
    if (!unfilter(rows, height, rowBytes, plan.samples * (plan.bitDepth / 8), threads)) return std::nullopt;

    // Row y's floats take bytes [4Wy, 4W(y + 1)) of the image; its inflated row starts at byte
    // tail + y * stride, with tail = H * (4W - stride). So a row's floats never reach a later row's bytes
    // (4W(y + 1) <= tail + (y + 1) * stride), and rows whose floats all end before the first row of theirs
    // still to convert are converted together, on all threads. Each such batch takes about half of the rows
    // left (rowBytes is at most 2W here): about log2(H) batches; a row whose floats would overwrite its own
    // bytes is converted alone, from a copy. The rows apart from the image are converted in one batch.
    const size_t floatRow = size_t(width) * sizeof(float), tail = imageBytes - rowsSize;
    std::vector<unsigned char> spare;
    for (int first = 0; first < height;) {
        const int end = inPlace ? int(std::min<size_t>(height, (tail + first * stride) / floatRow)) : height;
        if (end > first) {
            parallelFor(end - first, threads, [&](int a, int b) {
                for (int y = first + a; y < first + b; ++y) rowToFloats(rows + y * stride + 1, plan, image.row(y));
            });
            first = end;
        } else {
            spare.assign(rows + first * stride + 1, rows + (first + 1) * stride);
            rowToFloats(spare.data(), plan, image.row(first));
            ++first;
        }
    }
    return image;
}

}  // namespace heightpack::detail
