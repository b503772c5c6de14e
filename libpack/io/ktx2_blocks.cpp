// KTX2 files of block-compressed levels (BC4, BC5, ASTC). Laid out as ktx2.cpp lays out texel formats, but
// for what the KTX 2.0 specification asks of block formats: typeSize 1, levels aligned to the block size,
// and a Data Format Descriptor of colour model BC4 or BC5 with 4x4 texel blocks and one 64-bit sample a
// channel (channel 0 red, 1 green; the full 32-bit range as upper bound, as for other unsigned blocks), or
// of model ASTC with the block's size and one 128-bit sample of channel ASTC_DATA. An ASTC file records
// which channels hold the values in KTXswizzle (ktx2_layout.hpp).
#include <zstd.h>

#include <cstdio>
#include <memory>

#include "heightpack/io/files.hpp"
#include "ktx2_layout.hpp"

namespace heightpack::detail {


namespace {

constexpr std::uint32_t kModelBc4 = 131, kModelBc5 = 132, kModelAstc = 162;  // KHR_DF_MODEL_BC4, _BC5, _ASTC

std::vector<std::uint8_t> astcDataFormatDescriptor(BlockFormat format) {
    const std::uint32_t blockSize = 24 + 16, side = std::uint32_t(blockSide(format));
    std::vector<std::uint8_t> out;
    ktx2::put32(out, 4 + blockSize);
    ktx2::put32(out, 0);                    // vendorId 0 (Khronos), descriptorType 0 (basic)
    ktx2::put32(out, 2 | blockSize << 16);  // versionNumber 2 (KDF 1.3), descriptorBlockSize
    ktx2::put32(out, kModelAstc | 1 << 8 | 1 << 16);  // BT709, LINEAR, flags 0
    ktx2::put32(out, (side - 1) | (side - 1) << 8);   // texelBlockDimension (stored minus one)
    ktx2::put32(out, 16);                             // bytesPlane0
    ktx2::put32(out, 0);
    // bitOffset 0, bitLength 128 - 1, channel 0 (KHR_DF_CHANNEL_ASTC_DATA); HDR (SFLOAT) with the FLOAT and
    // SIGNED qualifiers and -1.0f..1.0f as bounds, as KTX-Software's createDFDCompressed writes them.
    const bool hdr = isAstcHdr(format);
    ktx2::put32(out, 127u << 16 | (hdr ? 0xC0u << 24 : 0u));
    ktx2::put32(out, 0);                             // samplePosition0..3
    ktx2::put32(out, hdr ? 0xBF800000u : 0u);        // sampleLower
    ktx2::put32(out, hdr ? 0x3F800000u : 0xFFFFFFFFu);  // sampleUpper
    return out;
}

std::vector<std::uint8_t> blockDataFormatDescriptor(BlockFormat format) {
    if (isAstc(format)) return astcDataFormatDescriptor(format);
    const int samples = blockChannels(format);
    const std::uint32_t blockSize = 24 + 16 * std::uint32_t(samples);
    std::vector<std::uint8_t> out;
    ktx2::put32(out, 4 + blockSize);
    ktx2::put32(out, 0);                    // vendorId 0 (Khronos), descriptorType 0 (basic)
    ktx2::put32(out, 2 | blockSize << 16);  // versionNumber 2 (KDF 1.3), descriptorBlockSize
    ktx2::put32(out, (format == BlockFormat::Bc4 ? kModelBc4 : kModelBc5) | 1 << 8 | 1 << 16);  // BT709, LINEAR, flags 0
    ktx2::put32(out, 3 | 3 << 8);           // texelBlockDimension: 4 x 4 (stored minus one)
    ktx2::put32(out, std::uint32_t(blockBytes(format)));  // bytesPlane0
    ktx2::put32(out, 0);
    for (int c = 0; c < samples; ++c) {
        ktx2::put32(out, std::uint32_t(64 * c) | 63u << 16 | std::uint32_t(c) << 24);  // bitOffset, bitLength - 1, channel
        ktx2::put32(out, 0);            // samplePosition0..3
        ktx2::put32(out, 0);            // sampleLower
        ktx2::put32(out, 0xFFFFFFFFu);  // sampleUpper
    }
    return out;
}

}  // namespace

Status writeKtx2Blocks(const std::string& path, const ChainToWrite& content, const TextureWriteOptions& options,
                       const EncodePlan& plan, const Attributes& keyValues) {
    const int levels = plan.levels, layers = content.layerCount();
    const BlockLevels* blocks = plan.blocks.get();
    if (!blocks || blocks->levels != levels || blocks->images.size() != size_t(levels) * size_t(layers))
        return Error{ErrorKind::Internal, path, "internal error: a block format was not encoded when it was planned",
                     "please report this"};
    const BlockFormat format = blockFormatOf(plan.format);
    const bool zstd = options.storage.supercompression == Supercompression::Zstd;

    // Each level's data: every layer's blocks in turn, then (with Zstandard) one frame.
    std::vector<std::vector<std::uint8_t>> data(static_cast<size_t>(levels));
    std::vector<std::uint64_t> rawLength(static_cast<size_t>(levels));
    for (int level = 0; level < levels; ++level) {
        std::vector<std::uint8_t>& d = data[size_t(level)];
        for (int layer = 0; layer < layers; ++layer) {
            const std::vector<std::uint8_t>& image = blocks->images[size_t(layer) * size_t(levels) + size_t(level)];
            d.insert(d.end(), image.begin(), image.end());
        }
        rawLength[size_t(level)] = d.size();
        if (zstd) {
            std::vector<std::uint8_t> packed(ZSTD_compressBound(d.size()));
            const size_t n = ZSTD_compress(packed.data(), packed.size(), d.data(), d.size(), options.storage.zstdLevel);
            if (ZSTD_isError(n))
                return Error{ErrorKind::Internal, path, std::string("internal error: Zstandard: ") + ZSTD_getErrorName(n),
                             "please report this"};
            packed.resize(n);
            d = std::move(packed);
        }
    }

    const std::vector<std::uint8_t> dfd = blockDataFormatDescriptor(format);
    Attributes allKeyValues = keyValues;
    if (isAstc(format)) allKeyValues.emplace_back(ktx2::kSwizzleKey, ktx2::astcSwizzle(plan.format.channels));
    const std::vector<std::uint8_t> kvd = ktx2::keyValueData(allKeyValues);
    const size_t dfdOffset = ktx2::kHeaderBytes + 24 * size_t(levels), kvdOffset = dfdOffset + dfd.size();
    const size_t alignment = zstd ? 1 : size_t(blockBytes(format));  // lcm(block size, 4)
    std::vector<std::uint64_t> offset(static_cast<size_t>(levels));
    size_t at = kvdOffset + kvd.size();
    for (int level = levels - 1; level >= 0; --level) {  // smallest level first
        at = ktx2::alignUp(at, alignment);
        offset[size_t(level)] = at;
        at += data[size_t(level)].size();
    }
    std::vector<std::uint8_t> file(ktx2::kIdentifier, ktx2::kIdentifier + 12);
    ktx2::put32(file, plan.format.vkFormat);
    ktx2::put32(file, 1);  // typeSize: 1 for block-compressed formats
    ktx2::put32(file, std::uint32_t(content.width));
    ktx2::put32(file, std::uint32_t(content.height));
    ktx2::put32(file, 0);
    ktx2::put32(file, content.layerNames.empty() ? 0 : std::uint32_t(layers));
    ktx2::put32(file, 1);
    ktx2::put32(file, std::uint32_t(levels));
    ktx2::put32(file, zstd ? ktx2::kSupercompressionZstd : 0);
    ktx2::put32(file, std::uint32_t(dfdOffset));
    ktx2::put32(file, std::uint32_t(dfd.size()));
    ktx2::put32(file, kvd.empty() ? 0 : std::uint32_t(kvdOffset));
    ktx2::put32(file, std::uint32_t(kvd.size()));
    ktx2::put64(file, 0);
    ktx2::put64(file, 0);
    for (int level = 0; level < levels; ++level) {
        ktx2::put64(file, offset[size_t(level)]);
        ktx2::put64(file, data[size_t(level)].size());
        ktx2::put64(file, rawLength[size_t(level)]);
    }
    file.insert(file.end(), dfd.begin(), dfd.end());
    file.insert(file.end(), kvd.begin(), kvd.end());
    for (int level = levels - 1; level >= 0; --level) {
        file.resize(offset[size_t(level)], 0);
        file.insert(file.end(), data[size_t(level)].begin(), data[size_t(level)].end());
    }
    if (options.progress) options.progress(1.0);
    // Written whole and atomically (a temporary file renamed into place), as the other writers do.
    return writeTextFile(path, std::string(file.begin(), file.end()));
}

}  // namespace heightpack::detail
