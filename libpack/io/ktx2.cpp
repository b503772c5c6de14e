// KTX 2.0 files (Khronos KTX File Format Specification 2.0), written and read by heightpack itself:
// Debian 12 has no libktx. The layout, in file order:
//   identifier, header (vkFormat, typeSize, size, layerCount, levelCount, supercompressionScheme), index (DFD, key/
//   value data, no supercompression global data), level index (level 0 first), the Data Format Descriptor
//   (one basic descriptor block, a sample per channel), key/value data (sorted by key, each entry padded
//   to 4 bytes), then the levels' data, smallest level first, each aligned to lcm(texel size, 4) (1 when
//   supercompressed). An array's level holds every layer's image of that level, layer 0 first, and its
//   layers' names are the key heightpack:layers. With Zstandard each level is one zstd frame (all its
//   layers); uncompressedByteLength is its size once inflated.
#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <numeric>

#include "heightpack/io/attributes.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/texture_write.hpp"
#include "ktx2_layout.hpp"
#include "level_write.hpp"
#include "texel_encode.hpp"

namespace heightpack {

using detail::FileCloser;
using detail::kBandRows;
using detail::readLe32;
namespace ktx2 = detail::ktx2;

namespace {

// The Data Format Descriptor: dfdTotalSize, then one Khronos basic descriptor block (model RGBSDA, BT.709
// primaries, linear transfer, straight alpha, 1x1 texel blocks) with one sample per channel.
std::vector<std::uint8_t> dataFormatDescriptor(const TexelFormatInfo& f) {
    const std::uint32_t blockSize = 24 + 16 * f.channels;
    std::vector<std::uint8_t> out;
    ktx2::put32(out, 4 + blockSize);
    ktx2::put32(out, 0);                                // vendorId 0 (Khronos), descriptorType 0 (basic)
    ktx2::put32(out, 2 | blockSize << 16);              // versionNumber 2 (KDF 1.3), descriptorBlockSize
    ktx2::put32(out, 1 | 1 << 8 | 1 << 16 | 0 << 24);   // colorModel RGBSDA, primaries BT709, transfer LINEAR, flags
    ktx2::put32(out, 0);                                // texelBlockDimension0..3: 1x1x1x1, stored minus one
    ktx2::put32(out, static_cast<std::uint32_t>(f.bytesPerTexel()));  // bytesPlane0
    ktx2::put32(out, 0);                                // bytesPlane4..7
    const int bits = 8 * f.bytesPerComponent();
    for (int c = 0; c < f.channels; ++c) {
        const std::uint32_t channelId = c == 3 ? 15 : static_cast<std::uint32_t>(c);  // R G B ... A
        std::uint32_t qualifiers = 0, lower = 0, upper = 0;
        switch (f.kind) {
            case ComponentKind::Float32:
            case ComponentKind::Float16:
                qualifiers = 0x80 | 0x40;  // FLOAT | SIGNED
                lower = 0xBF800000u;       // -1.0f
                upper = 0x3F800000u;       // 1.0f
                break;
            case ComponentKind::Unorm16: upper = 65535; break;
            case ComponentKind::Block: break;  // described in ktx2_blocks.cpp
            case ComponentKind::Snorm16:
                qualifiers = 0x40;
                lower = static_cast<std::uint32_t>(-32767);
                upper = 32767;
                break;
        }
        ktx2::put32(out, static_cast<std::uint32_t>(c * bits) | static_cast<std::uint32_t>(bits - 1) << 16 |
                       (channelId | qualifiers) << 24);
        ktx2::put32(out, 0);  // samplePosition0..3
        ktx2::put32(out, lower);
        ktx2::put32(out, upper);
    }
    return out;
}

struct ZstdFree {
    void operator()(ZSTD_CCtx* c) const { ZSTD_freeCCtx(c); }
};

}  // namespace

Status writeKtx2(const std::string& path, const ChainToWrite& content, const TextureWriteOptions& options) {
    auto storage = planTexelStorage({path, Container::Ktx2}, content, options);
    if (!storage) return storage.error();
    return writeKtx2(path, content, options, storage->plan);
}

Status writeKtx2(const std::string& path, const ChainToWrite& content, const TextureWriteOptions& options,
                 const WritePlan& decided) {
    if (Status s = checkWritable(path); !s) return s;
    const detail::EncodePlan plan = detail::encodePlanOf(content, options, decided);
    const TexelFormatInfo& f = plan.format;
    const bool zstd = options.storage.supercompression == Supercompression::Zstd;

    Attributes keyValues = detail::attributesAsText(content.attributes);
    if (plan.normalisation) {
        keyValues.emplace_back(ktx2::kOffsetKey, detail::floatText(plan.normalisation->offset));
        keyValues.emplace_back(ktx2::kScaleKey, detail::floatText(plan.normalisation->scale));
    }
    if (!content.layerNames.empty()) keyValues.emplace_back(attr::layers.name, detail::layerList(content.layerNames));
    keyValues.emplace_back("KTXwriter", options.writer.empty() ? std::string("heightpack") : options.writer);
    // By convention the option of Khronos' `ktx` tool that gives the same supercompression: data in the
    // file, not a hint naming a flag of heightpack's (the marker tells floor_rules.sh so).
    if (zstd) keyValues.emplace_back("KTXwriterScParams", "--zstd " + std::to_string(options.storage.zstdLevel));  // floor_rules: data
    if (f.isBlock()) return detail::writeKtx2Blocks(path, content, options, plan, keyValues);

    const int levels = plan.levels, layers = content.layerCount();
    const std::vector<std::uint8_t> dfd = dataFormatDescriptor(f);
    const std::vector<std::uint8_t> kvd = ktx2::keyValueData(keyValues);
    const size_t dfdOffset = ktx2::kHeaderBytes + 24 * size_t(levels);
    const size_t kvdOffset = dfdOffset + dfd.size();
    const size_t dataStart = kvdOffset + kvd.size();
    const size_t alignment = zstd ? 1 : std::lcm(size_t(f.bytesPerTexel()), size_t(4));

    // Level offsets and lengths: known in advance without supercompression, found while writing with it.
    std::vector<std::uint64_t> offset(levels), length(levels), rawLength(levels);
    size_t at = dataStart;
    for (int level = levels - 1; level >= 0; --level) {
        rawLength[level] = std::uint64_t(mipLevelSide(content.width, level)) *
                           mipLevelSide(content.height, level) * f.bytesPerTexel() * layers;
        at = ktx2::alignUp(at, alignment);
        offset[level] = at;
        length[level] = rawLength[level];
        at += rawLength[level];
    }

    auto header = [&] {
        std::vector<std::uint8_t> h(ktx2::kIdentifier, ktx2::kIdentifier + 12);
        ktx2::put32(h, f.vkFormat);
        ktx2::put32(h, static_cast<std::uint32_t>(f.bytesPerComponent()));  // typeSize
        ktx2::put32(h, static_cast<std::uint32_t>(content.width));
        ktx2::put32(h, static_cast<std::uint32_t>(content.height));
        ktx2::put32(h, 0);  // pixelDepth: a 2D texture
        ktx2::put32(h, content.layerNames.empty() ? 0 : static_cast<std::uint32_t>(layers));  // 0: not an array
        ktx2::put32(h, 1);  // faceCount
        ktx2::put32(h, static_cast<std::uint32_t>(levels));
        ktx2::put32(h, zstd ? ktx2::kSupercompressionZstd : 0);
        ktx2::put32(h, static_cast<std::uint32_t>(dfdOffset));
        ktx2::put32(h, static_cast<std::uint32_t>(dfd.size()));
        ktx2::put32(h, kvd.empty() ? 0 : static_cast<std::uint32_t>(kvdOffset));
        ktx2::put32(h, static_cast<std::uint32_t>(kvd.size()));
        ktx2::put64(h, 0);  // no supercompression global data
        ktx2::put64(h, 0);
        for (int level = 0; level < levels; ++level) {
            ktx2::put64(h, offset[level]);
            ktx2::put64(h, length[level]);
            ktx2::put64(h, rawLength[level]);
        }
        h.insert(h.end(), dfd.begin(), dfd.end());
        h.insert(h.end(), kvd.begin(), kvd.end());
        return h;
    };

    TemporaryFile temp(path);
    if (!zstd) {  // every level's place known: written on all threads, each band where it belongs
        std::vector<detail::PlacedImage> images;
        for (int level = levels - 1; level >= 0; --level) {
            const std::uint64_t layerBytes = rawLength[level] / std::uint64_t(layers);
            for (int layer = 0; layer < layers; ++layer)
                images.push_back({layer, level, offset[level] + std::uint64_t(layer) * layerBytes});
        }
        if (Status s = detail::writePlacedImages(path, temp.path(), header(), images, content, plan, options.threads,
                                                 options.progress);
            !s)
            return s;
        return temp.commit();
    }
    // Zstandard: each level one frame, its compressed length known once written, so written in order.
    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(temp.path().c_str(), "wb"));
    auto failed = [&](const char* step) {
        return cannotWrite(path, std::string(step) + " failed", "check free disk space and permissions");
    };
    if (!file) return failed("creating the file");
    auto write = [&](const void* data, size_t n) { return n == 0 || std::fwrite(data, 1, n, file.get()) == n; };
    std::vector<std::uint8_t> head = header();
    if (!write(head.data(), head.size())) return failed("writing the header");

    std::unique_ptr<ZSTD_CCtx, ZstdFree> cctx(ZSTD_createCCtx());
    if (!cctx || ZSTD_isError(ZSTD_CCtx_setParameter(cctx.get(), ZSTD_c_compressionLevel, options.storage.zstdLevel)))
        return Error{ErrorKind::Internal, path, "internal error: Zstandard could not be set up", "please report this"};
    std::vector<std::uint8_t> packed(ZSTD_CStreamOutSize());
    long long rowsTotal = 0, rowsDone = 0;
    for (int level = 0; level < levels; ++level) rowsTotal += mipLevelSide(content.height, level) * layers;
    size_t position = head.size();
    detail::BandEncoder encoder(path, content, plan, options.threads);
    const std::vector<std::uint8_t>& bytes = encoder.bytes();
    for (int level = levels - 1; level >= 0; --level) {
        const size_t start = position;  // supercompressed levels are not aligned (alignment 1)
        const int h = mipLevelSide(content.height, level);
        // Each level one frame that records its size, as readers expect to allocate from it.
        if (ZSTD_isError(ZSTD_CCtx_setPledgedSrcSize(cctx.get(), rawLength[level])))
            return Error{ErrorKind::Internal, path, "internal error: Zstandard refused a level's size", "please report this"};
        const int bandsPerLayer = (h + kBandRows - 1) / kBandRows;
        for (int band = 0; band < layers * bandsPerLayer; ++band) {  // each layer's bands in turn
            const int layer = band / bandsPerLayer, y0 = band % bandsPerLayer * kBandRows;
            const int rows = std::min(kBandRows, h - y0);
            if (Status s = encoder.encode(level, y0, rows, layer); !s) return s;
            ZSTD_inBuffer in{bytes.data(), bytes.size(), 0};
            const bool last = layer + 1 == layers && y0 + rows == h;
            for (bool done = false; !done;) {
                ZSTD_outBuffer out{packed.data(), packed.size(), 0};
                const size_t left = ZSTD_compressStream2(cctx.get(), &out, &in, last ? ZSTD_e_end : ZSTD_e_continue);
                if (ZSTD_isError(left))
                    return Error{ErrorKind::Internal, path, std::string("internal error: Zstandard: ") +
                                 ZSTD_getErrorName(left), "please report this"};
                if (!write(packed.data(), out.pos)) return failed("writing a level");
                position += out.pos;
                done = last ? left == 0 : in.pos == in.size;
            }
            rowsDone += rows;
            if (options.progress) options.progress(double(rowsDone) / double(rowsTotal));
        }
        offset[level] = start;
        length[level] = position - start;
    }
    // The level index, now that the compressed sizes are known.
    head = header();
    if (std::fseek(file.get(), 0, SEEK_SET) != 0 || !write(head.data(), dfdOffset)) return failed("writing the level index");
    if (std::fflush(file.get()) != 0 || std::ferror(file.get())) return failed("writing the file");
    if (std::fclose(file.release()) != 0) return failed("closing the file");
    return temp.commit();
}

namespace detail {

// Reads a KTX2 file holding one of heightpack's formats. Every offset and length is checked against the
// file's size before it is used.
Result<GpuTexture> readKtx2(const std::string& path) {
    auto read = readWholeFile(path);
    if (!read) return read.error();
    const std::vector<std::uint8_t>& b = *read;
    auto corrupt = [&](const std::string& what) {
        return badInput(path, "is not a KTX2 file heightpack can read: " + what,
                        "write it again with heightpack, or check that it was copied whole");
    };
    if (b.size() < ktx2::kHeaderBytes || std::memcmp(b.data(), ktx2::kIdentifier, 12) != 0)
        return corrupt("no KTX 2.0 identifier");
    const std::uint8_t* p = b.data() + 12;
    const std::uint32_t vkFormat = readLe32(p), width = readLe32(p + 8), height = readLe32(p + 12), depth = readLe32(p + 16),
                        layers = readLe32(p + 20), faces = readLe32(p + 24), levelCount = readLe32(p + 28),
                        scheme = readLe32(p + 32), dfdOffset = readLe32(p + 36), dfdLength = readLe32(p + 40),
                        kvdOffset = readLe32(p + 44), kvdLength = readLe32(p + 48);
    GpuTexture t;
    t.container = Container::Ktx2;
    const auto format = texelFormatFromVk(vkFormat);
    if (!format) return corrupt("vkFormat " + std::to_string(vkFormat) + " is not one heightpack writes");
    t.format = *format;
    TexelFormatInfo f = texelFormatInfo(t.format);
    if (width == 0 || height == 0 || width > 65536 || height > 65536) return corrupt("its size is out of range");
    if (depth != 0 || faces != 1) return corrupt("it is not a 2D texture or array");
    if (layers > 64) return corrupt("it lists " + std::to_string(layers) + " layers, more than heightpack writes");
    const int layerCount = layers > 1 ? int(layers) : 1;
    if (scheme != 0 && scheme != ktx2::kSupercompressionZstd)
        return corrupt("supercompression scheme " + std::to_string(scheme) + " is not supported");
    t.supercompression = scheme == ktx2::kSupercompressionZstd ? Supercompression::Zstd : Supercompression::None;
    t.width = int(width);
    t.height = int(height);
    const int full = mipLevelCount(t.width, t.height);
    const int levels = levelCount == 0 ? 1 : int(std::min<std::uint32_t>(levelCount, 64));
    if (levels > full) return corrupt("it lists more levels than its size allows");
    if (ktx2::kHeaderBytes + 24 * size_t(levels) > b.size()) return corrupt("its level index is truncated");
    if (size_t(dfdOffset) + dfdLength > b.size() || size_t(kvdOffset) + kvdLength > b.size())
        return corrupt("its descriptor or key/value data lies past its end");

    // Key/value data.
    for (size_t at = kvdOffset, end = size_t(kvdOffset) + kvdLength; at + 4 <= end;) {
        const std::uint32_t n = readLe32(b.data() + at);
        if (n > end - at - 4) return corrupt("a key/value entry runs past the key/value data");
        const char* entry = reinterpret_cast<const char*>(b.data() + at + 4);
        const std::string_view kv(entry, n);
        const size_t nul = kv.find('\0');
        if (nul == std::string_view::npos) return corrupt("a key has no terminating NUL");
        std::string value(kv.substr(nul + 1));
        if (!value.empty() && value.back() == '\0') value.pop_back();
        t.keyValues.emplace_back(std::string(kv.substr(0, nul)), std::move(value));
        at = ktx2::alignUp(at + 4 + n, 4);
    }
    // An ASTC format holds one channel or two: its swizzle says which (the one-channel format otherwise).
    if (f.isBlock() && findAttribute(t.keyValues, ktx2::kSwizzleKey) == ktx2::astcSwizzle(2)) {
        t.format = astcTwoChannels(t.format);
        f = texelFormatInfo(t.format);
    }
    if (layerCount > 1) t.layerNames = layerNamesOf(findAttribute(t.keyValues, attr::layers), layerCount);
    const std::string off = findAttribute(t.keyValues, ktx2::kOffsetKey), scale = findAttribute(t.keyValues, ktx2::kScaleKey);
    if ((f.kind == ComponentKind::Unorm16 || f.isBlock()) && !off.empty() && !scale.empty()) {
        // Read before the levels are decoded through them, so checked here rather than by describeTexture.
        float value[2];
        for (int k = 0; k < 2; ++k) {
            const std::string& text = k == 0 ? off : scale;
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || std::abs(v) > 1e30)
                return badInput(path, std::string("its ") + (k == 0 ? ktx2::kOffsetKey : ktx2::kScaleKey) + " metadata '" +
                                          text.substr(0, 64) + "' is not a finite number",
                                "remove or correct that metadata in the file");
            value[k] = float(v);
        }
        t.normalisation = Normalisation{value[0], value[1]};
    }

    if (std::int64_t(t.width) * t.height * layerCount > kMostTexelsReadALevel)
        return badInput(path, "its level 0 holds " + std::to_string(std::int64_t(t.width) * t.height * layerCount) +
                                  " texels, more than heightpack reads (" + std::to_string(kMostTexelsReadALevel) +
                                  ", 16384 x 16384)",
                        "check that the file is a texture heightpack wrote; its header may be damaged");
    for (int level = 0; level < levels; ++level) {
        const std::uint8_t* e = b.data() + ktx2::kHeaderBytes + 24 * size_t(level);
        const std::uint64_t offset = ktx2::get64(e), length = ktx2::get64(e + 8), raw = ktx2::get64(e + 16);
        const int w = mipLevelSide(t.width, level), h = mipLevelSide(t.height, level);
        const std::uint64_t expected = std::uint64_t(imageBytes(f, w, h)) * layerCount;
        if (offset > b.size() || length > b.size() - offset)
            return corrupt("level " + std::to_string(level) + " lies past the end of the file");
        if (raw != expected) return corrupt("level " + std::to_string(level) + " has the wrong size");
        std::vector<std::uint8_t> bytes;
        if (t.supercompression == Supercompression::Zstd) {
            const unsigned long long size = ZSTD_getFrameContentSize(b.data() + offset, length);
            if (size != expected && size != ZSTD_CONTENTSIZE_UNKNOWN)
                return corrupt("level " + std::to_string(level) + " is not a Zstandard frame of the level's size");
            // Nor more than its frame can hold, checked before the level is allocated (a frame that does not
            // state its size could claim terabytes): a Zstandard block inflates to at most 128 KiB, and the
            // smallest (a run) takes 4 bytes.
            if (expected / ktx2::kZstdMostBlockBytes > length / 4 + 1)
                return corrupt("level " + std::to_string(level) + " claims more than its Zstandard frame can hold");
            bytes.resize(expected);
            const size_t got = ZSTD_decompress(bytes.data(), bytes.size(), b.data() + offset, length);
            if (ZSTD_isError(got) || got != expected)
                return corrupt("level " + std::to_string(level) + " does not inflate");
        } else {
            if (length != expected) return corrupt("level " + std::to_string(level) + " has the wrong size");
            bytes.assign(b.begin() + std::ptrdiff_t(offset), b.begin() + std::ptrdiff_t(offset + length));
        }
        t.levels.push_back(decodeLayers(f, bytes.data(), w, h, layerCount, t.normalisation));
        t.levelBytes.push_back(std::move(bytes));
    }
    return t;
}

}  // namespace detail

}  // namespace heightpack
