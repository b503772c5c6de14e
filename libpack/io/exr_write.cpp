// Writing tiled, mip-mapped float EXRs, and flat scanline ones (ZIP, on the OpenEXRCore path below).
// For the tiled files, two paths that produce the same standard file layout:
// - none / zip / zips: our own tile loop on OpenEXRCore. Tiles are packed and deflated on all threads
//   (libdeflate, in EXR's ZIP tile format: bytes split, delta predictor, zlib stream), then written in
//   file order by one thread, so the bytes never depend on the thread count. This is where heightpack
//   beats a general texture maker: OpenEXR 3.1 deflates with zlib, several times slower.
// - rle / piz: OpenEXR's C++ TiledOutputFile, which implements those codecs.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <Imath/half.h>
#include <OpenEXR/openexr.h>
#include <libdeflate.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <numeric>

#include "heightpack/core/parallel.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/files.hpp"

#include "text.hpp"

namespace heightpack {

namespace {

// libdeflate's level 4: on the 4096^2 benchmark map, 68.5 MB against 72.0 MB from OpenEXR's own zip
// (zlib level 4), in about half the CPU time. Fixed, so outputs are reproducible.
constexpr int kDeflateLevel = 4;
// A flat scanline file (synth's maps) at level 1: on synth's 4096^2 map with displacement and foam,
// 194.6 MB against 194.2 MB at level 4, in about 17% less time (float noise barely compresses).
constexpr int kScanlineDeflateLevel = 1;


int levelSize(int size, int level) { return std::max(1, size >> level); }

// The last guard before bytes reach a file: an output never holds NaN or infinity. Whatever let one
// through (an option or input check missing) is a bug, reported as one.
Status requireFinite(const std::string& path, const float* values, size_t count, int level) {
    for (size_t i = 0; i < count; ++i)
        if (!std::isfinite(values[i]))
            return Error{ErrorKind::Internal, path,
                         "internal error: level " + std::to_string(level) + " holds a non-finite value; nothing was written",
                         "please report this with the command line"};
    return Done{};
}

// ---- The OpenEXRCore path ----

struct CoreErrors {
    std::string last;
};

// The errors of the write under way on this thread. OpenEXRCore 3.1 calls the handler while it holds the
// context's lock, so asking the context for its user data there waits on that lock forever.
thread_local CoreErrors* currentErrors = nullptr;

extern "C" void rememberCoreError(exr_const_context_t, exr_result_t code, const char* msg) {
    if (currentErrors) currentErrors->last = msg ? msg : exr_get_default_error_message(code);
}

// Starts writing path, with errors remembered in errors and attribute names over 31 characters allowed
// (heightpack:significantWaveHeight has 32; OpenEXR's C++ library sets the same flag by itself).
exr_result_t startWrite(exr_context_t* ctxt, const std::string& path, CoreErrors& errors) {
    currentErrors = &errors;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = rememberCoreError;
    exr_result_t rv = exr_start_write(ctxt, path.c_str(), EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS) rv = exr_set_longname_support(*ctxt, 1);
    return rv;
}

// Packs one tile's texels in EXR's uncompressed tile layout: line by line, and within a line each
// channel's run of floats (or halves), channels in name order.
void packTile(const float* band, int levelWidth, int channels, const std::vector<int>& nameOrder, int x0,
              int tileWidth, int rows, bool half, std::vector<unsigned char>& raw) {
    if (half) {
        raw.resize(size_t(rows) * channels * tileWidth * sizeof(std::uint16_t));
        std::uint16_t* out = reinterpret_cast<std::uint16_t*>(raw.data());
        for (int r = 0; r < rows; ++r) {
            const float* line = band + (size_t(r) * levelWidth + x0) * channels;
            for (int c : nameOrder)
                for (int x = 0; x < tileWidth; ++x) *out++ = Imath::half(line[size_t(x) * channels + c]).bits();
        }
        return;
    }
    raw.resize(size_t(rows) * channels * tileWidth * sizeof(float));
    float* out = reinterpret_cast<float*>(raw.data());
    for (int r = 0; r < rows; ++r) {
        const float* line = band + (size_t(r) * levelWidth + x0) * channels;
        for (int c : nameOrder)
            for (int x = 0; x < tileWidth; ++x) *out++ = line[size_t(x) * channels + c];
    }
}

// EXR's ZIP tile compression (as ImfZip.cpp): split even and odd bytes, delta-code them, deflate as a
// zlib stream. Leaves the raw bytes when compression would not make them smaller, as EXR requires.
void zipTile(std::vector<unsigned char>& raw, std::vector<unsigned char>& scratch, std::vector<unsigned char>& out,
             libdeflate_compressor* compressor) {
    const size_t n = raw.size();
    scratch.resize(n);
    // Split and delta in one pass, each byte against its predecessor in the split order, read from raw:
    // the loops carry no value from one byte to the next, so they vectorise (a tenth of the time of
    // splitting, then delta-coding in place).
    const size_t evens = (n + 1) / 2, odds = n / 2;
    const unsigned char* in = raw.data();
    unsigned char* even = scratch.data();
    unsigned char* odd = scratch.data() + evens;
    if (n > 0) even[0] = in[0];
    for (size_t i = 1; i < evens; ++i) even[i] = static_cast<unsigned char>(in[2 * i] - in[2 * i - 2] + 128);
    if (odds > 0) odd[0] = static_cast<unsigned char>(in[1] - in[2 * (evens - 1)] + 128);  // after the last even
    for (size_t i = 1; i < odds; ++i) odd[i] = static_cast<unsigned char>(in[2 * i + 1] - in[2 * i - 1] + 128);
    out.resize(libdeflate_zlib_compress_bound(compressor, n));
    const size_t packed = libdeflate_zlib_compress(compressor, scratch.data(), n, out.data(), out.size());
    if (packed == 0 || packed >= n)
        out.swap(raw);
    else
        out.resize(packed);
}

exr_result_t addAttributes(exr_context_t ctxt, int part, const std::vector<ExrAttribute>& attributes) {
    for (const ExrAttribute& a : attributes) {
        const exr_result_t rv = std::holds_alternative<std::string>(a.value)
                                    ? exr_attr_set_string(ctxt, part, a.name.c_str(), std::get<std::string>(a.value).c_str())
                                    : exr_attr_set_float(ctxt, part, a.name.c_str(), std::get<float>(a.value));
        if (rv) return rv;
    }
    return EXR_ERR_SUCCESS;
}

// The channels' order in the file (EXR sorts them by name), as indices into names.
std::vector<int> fileOrder(const std::vector<std::string>& names) {
    std::vector<int> order(names.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return names[a] < names[b]; });
    return order;
}

Status writeWithCore(const std::string& finalPath, const std::string& path, const MipChainSource& content,
                     const ExrWriteOptions& options) {
    CoreErrors errors;
    exr_context_t ctxt = nullptr;
    auto fail = [&](const char* step, exr_result_t rv) -> Status {
        const std::string why = errors.last.empty() ? exr_get_default_error_message(rv) : errors.last;
        return cannotWrite(finalPath, std::string(step) + " failed: " + detail::firstLine(why),
                           "check free disk space and permissions");
    };
    exr_result_t rv = startWrite(&ctxt, path, errors);
    std::unique_ptr<exr_context_t, void (*)(exr_context_t*)> guard(&ctxt, [](exr_context_t* c) { exr_finish(c); });
    if (rv != EXR_ERR_SUCCESS) return fail("opening the file", rv);

    int part = 0;
    const bool zip = options.compression != Compression::None;
    if ((rv = exr_add_part(ctxt, nullptr, EXR_STORAGE_TILED, &part)) ||
        (rv = exr_initialize_required_attr_simple(ctxt, part, content.width, content.height,
                                                  zip ? (options.compression == Compression::Zips ? EXR_COMPRESSION_ZIPS
                                                                                                  : EXR_COMPRESSION_ZIP)
                                                      : EXR_COMPRESSION_NONE)) ||
        (rv = exr_set_tile_descriptor(ctxt, part, options.tileSize, options.tileSize, EXR_TILE_MIPMAP_LEVELS,
                                      EXR_TILE_ROUND_DOWN)))
        return fail("describing the file", rv);
    for (const std::string& name : content.channelNames)
        if ((rv = exr_add_channel(ctxt, part, name.c_str(), options.half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1)))
            return fail("adding a channel", rv);
    if ((rv = addAttributes(ctxt, part, content.attributes))) return fail("adding an attribute", rv);
    if ((rv = exr_write_header(ctxt))) return fail("writing the header", rv);

    const int channels = static_cast<int>(content.channelNames.size());
    const std::vector<int> nameOrder = fileOrder(content.channelNames);

    int levels = 0;
    if ((rv = exr_get_tile_levels(ctxt, part, &levels, nullptr))) return fail("counting levels", rv);
    const int ts = options.tileSize;
    long long rowsTotal = 0, rowsDone = 0;
    for (int level = 0; level < levels; ++level) rowsTotal += levelSize(content.height, level);

    std::vector<float> band;
    std::vector<std::vector<unsigned char>> tiles;
    for (int level = 0; level < levels; ++level) {
        const int w = levelSize(content.width, level), h = levelSize(content.height, level);
        const int tilesX = (w + ts - 1) / ts, tilesY = (h + ts - 1) / ts;
        band.resize(size_t(w) * ts * channels);
        tiles.resize(tilesX);
        for (int ty = 0; ty < tilesY; ++ty) {
            const int y0 = ty * ts, rows = std::min(ts, h - y0);
            parallelFor(rows, options.threads, [&](int a, int b) {
                content.fillRows(level, y0 + a, b - a, band.data() + size_t(a) * w * channels);
            });
            if (Status s = requireFinite(finalPath, band.data(), size_t(w) * rows * channels, level); !s) return s;
            parallelFor(tilesX, options.threads, [&](int a, int b) {
                std::vector<unsigned char> raw, scratch;
                libdeflate_compressor* compressor = zip ? libdeflate_alloc_compressor(kDeflateLevel) : nullptr;
                for (int tx = a; tx < b; ++tx) {
                    const int x0 = tx * ts;
                    packTile(band.data(), w, channels, nameOrder, x0, std::min(ts, w - x0), rows, options.half,
                             zip ? raw : tiles[tx]);
                    if (zip) zipTile(raw, scratch, tiles[tx], compressor);
                }
                libdeflate_free_compressor(compressor);
            });
            for (int tx = 0; tx < tilesX; ++tx)
                if ((rv = exr_write_tile_chunk(ctxt, part, tx, ty, level, level, tiles[tx].data(), tiles[tx].size())))
                    return fail("writing a tile", rv);
            rowsDone += rows;
            if (options.progress) options.progress(double(rowsDone) / rowsTotal);
        }
    }
    guard.release();
    if ((rv = exr_finish(&ctxt))) return fail("finishing the file", rv);
    return Done{};
}

// The flat scanline file: blocks of rows (16 for ZIP and None, 1 for ZIPS), a batch of blocks packed (and
// deflated) on all threads, then written in order by one thread. It replaced OpenImageIO's writer (zlib
// through OpenEXR 3.1), which took about 40% of `synth`'s time; the file holds the same channels, types
// and attributes.
Status writeScanlineWithCore(const std::string& finalPath, const std::string& path, const ScanlineExrContent& content,
                             bool half, int threads, Compression compression) {
    CoreErrors errors;
    exr_context_t ctxt = nullptr;
    auto fail = [&](const char* step, exr_result_t rv) -> Status {
        const std::string why = errors.last.empty() ? exr_get_default_error_message(rv) : errors.last;
        return cannotWrite(finalPath, std::string(step) + " failed: " + detail::firstLine(why),
                           "check free disk space and permissions");
    };
    exr_result_t rv = startWrite(&ctxt, path, errors);
    std::unique_ptr<exr_context_t, void (*)(exr_context_t*)> guard(&ctxt, [](exr_context_t* c) { exr_finish(c); });
    if (rv != EXR_ERR_SUCCESS) return fail("opening the file", rv);

    const bool zip = compression != Compression::None;
    int part = 0;
    if ((rv = exr_add_part(ctxt, nullptr, EXR_STORAGE_SCANLINE, &part)) ||
        (rv = exr_initialize_required_attr_simple(ctxt, part, content.width, content.height,
                                                  !zip ? EXR_COMPRESSION_NONE
                                                  : compression == Compression::Zips ? EXR_COMPRESSION_ZIPS
                                                                                     : EXR_COMPRESSION_ZIP)))
        return fail("describing the file", rv);
    // pLinear 0 (OpenEXRCore calls it "logarithmic"): what OpenImageIO wrote, Imf::Channel's default.
    for (const std::string& name : content.channelNames)
        if ((rv = exr_add_channel(ctxt, part, name.c_str(), half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT,
                                  EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1)))
            return fail("adding a channel", rv);
    if ((rv = addAttributes(ctxt, part, content.attributes))) return fail("adding an attribute", rv);
    if ((rv = exr_write_header(ctxt))) return fail("writing the header", rv);

    const int channels = static_cast<int>(content.channelNames.size());
    const std::vector<int> nameOrder = fileOrder(content.channelNames);
    int linesPerBlock = 0;
    if ((rv = exr_get_scanlines_per_chunk(ctxt, part, &linesPerBlock))) return fail("describing the file", rv);
    const int blocks = (content.height + linesPerBlock - 1) / linesPerBlock;
    // Enough blocks a batch to keep the threads busy, few enough that the compressed batch stays small.
    const int batch = 64;
    // The batch's blocks are reserved here, on this thread: a worker's own allocations would come from its
    // own arena, new memory beside the caller's freed heap (16 MB more at 4096^2, 4 float channels).
    std::vector<std::vector<unsigned char>> packed(batch);
    libdeflate_compressor* sizing = libdeflate_alloc_compressor(kScanlineDeflateLevel);
    const size_t rawBlock = size_t(linesPerBlock) * content.width * channels * (half ? 2 : 4);
    for (std::vector<unsigned char>& block : packed) block.reserve(zip ? libdeflate_zlib_compress_bound(sizing, rawBlock) : rawBlock);
    libdeflate_free_compressor(sizing);
    for (int first = 0; first < blocks; first += batch) {
        const int count = std::min(batch, blocks - first);
        std::vector<Status> failed(count, Done{});
        parallelFor(count, threads, [&](int a, int b) {
            std::vector<unsigned char> raw, scratch;
            libdeflate_compressor* compressor = zip ? libdeflate_alloc_compressor(kScanlineDeflateLevel) : nullptr;
            for (int i = a; i < b; ++i) {
                const int y0 = (first + i) * linesPerBlock, rows = std::min(linesPerBlock, content.height - y0);
                const float* band = content.pixels + size_t(y0) * content.width * channels;
                failed[i] = requireFinite(finalPath, band, size_t(content.width) * rows * channels, 0);
                if (!failed[i]) continue;
                packTile(band, content.width, channels, nameOrder, 0, content.width, rows, half, zip ? raw : packed[i]);
                if (zip) zipTile(raw, scratch, packed[i], compressor);
            }
            libdeflate_free_compressor(compressor);
        });
        for (int i = 0; i < count; ++i) {
            if (!failed[i]) return failed[i];
            if ((rv = exr_write_scanline_chunk(ctxt, part, (first + i) * linesPerBlock, packed[i].data(), packed[i].size())))
                return fail("writing rows", rv);
        }
    }
    guard.release();
    if ((rv = exr_finish(&ctxt))) return fail("finishing the file", rv);
    return Done{};
}

// ---- The OpenEXR C++ path (rle, piz) ----

Imf::Compression toImf(Compression compression) {
    switch (compression) {
        case Compression::None: return Imf::NO_COMPRESSION;
        case Compression::Rle: return Imf::RLE_COMPRESSION;
        case Compression::Zips: return Imf::ZIPS_COMPRESSION;
        case Compression::Zip: return Imf::ZIP_COMPRESSION;
        case Compression::Piz: return Imf::PIZ_COMPRESSION;
    }
    return Imf::ZIP_COMPRESSION;
}

Status writeWithImf(const std::string& finalPath, const std::string& path, const MipChainSource& content,
                    const ExrWriteOptions& options) {
    Imf::Header header(content.width, content.height);
    header.compression() = toImf(options.compression);
    header.setTileDescription(
        Imf::TileDescription(options.tileSize, options.tileSize, Imf::MIPMAP_LEVELS, Imf::ROUND_DOWN));
    const Imf::PixelType type = options.half ? Imf::HALF : Imf::FLOAT;
    for (const std::string& name : content.channelNames) header.channels().insert(name, Imf::Channel(type));
    for (const ExrAttribute& a : content.attributes) {
        if (const auto* s = std::get_if<std::string>(&a.value))
            header.insert(a.name, Imf::StringAttribute(*s));
        else
            header.insert(a.name, Imf::FloatAttribute(std::get<float>(a.value)));
    }
    try {
        Imf::TiledOutputFile file(path.c_str(), header);
        const int channels = static_cast<int>(content.channelNames.size());
        const size_t texelBytes = sizeof(float) * channels;
        long long rowsTotal = 0, rowsDone = 0;
        for (int level = 0; level < file.numLevels(); ++level) rowsTotal += file.levelHeight(level);
        std::vector<float> band;
        std::vector<Imath::half> halves;
        for (int level = 0; level < file.numLevels(); ++level) {
            const int w = file.levelWidth(level), h = file.levelHeight(level);
            band.resize(static_cast<size_t>(w) * options.tileSize * channels);
            if (options.half) halves.resize(band.size());
            for (int ty = 0; ty < file.numYTiles(level); ++ty) {
                const int y0 = ty * options.tileSize;
                const int rows = std::min(options.tileSize, h - y0);
                content.fillRows(level, y0, rows, band.data());
                if (Status s = requireFinite(finalPath, band.data(), size_t(w) * rows * channels, level); !s) return s;
                Imf::FrameBuffer frame;
                if (options.half) {
                    for (size_t i = 0; i < size_t(w) * rows * channels; ++i) halves[i] = Imath::half(band[i]);
                    const size_t halfTexel = sizeof(Imath::half) * channels;
                    for (int c = 0; c < channels; ++c)
                        frame.insert(content.channelNames[c],
                                     Imf::Slice::Make(Imf::HALF, halves.data() + c, IMATH_NAMESPACE::V2i(0, y0), w,
                                                      rows, halfTexel, halfTexel * w));
                }
                for (int c = 0; c < channels && !options.half; ++c) {
                    frame.insert(content.channelNames[c],
                                 Imf::Slice::Make(Imf::FLOAT, band.data() + c, IMATH_NAMESPACE::V2i(0, y0), w, rows,
                                                  texelBytes, texelBytes * w));
                }
                file.setFrameBuffer(frame);
                // A whole row of tiles per call lets OpenEXR compress them on its thread pool.
                file.writeTiles(0, file.numXTiles(level) - 1, ty, ty, level);
                rowsDone += rows;
                if (options.progress) options.progress(double(rowsDone) / rowsTotal);
            }
        }
    } catch (const std::exception& e) {
        return cannotWrite(finalPath, "writing failed: " + detail::firstLine(e.what()), "check free disk space and permissions");
    }
    return Done{};
}

}  // namespace

Status writeTiledExr(const std::string& path, const MipChainSource& content, const ExrWriteOptions& options) {
    assert(content.width > 0 && content.height > 0 && !content.channelNames.empty() && content.fillRows);
    if (Status writable = checkWritable(path); !writable) return writable;
    const std::string ext = lowerExtension(path);
    if (ext != ".exr")  // never EXR bytes under another format's name
        return cannotWrite(path, "is not an .exr name, but the file would be an EXR", "name the output .exr");
    TemporaryFile temp(path);
    const bool core = options.compression == Compression::None || options.compression == Compression::Zip ||
                      options.compression == Compression::Zips;
    Status written = core ? writeWithCore(path, temp.path(), content, options)
                          : writeWithImf(path, temp.path(), content, options);
    if (!written) return written;
    return temp.commit();
}

Status writeScanlineExr(const std::string& path, const ScanlineExrContent& content, bool half, int threads,
                        Compression compression) {
    assert(content.width > 0 && content.height > 0 && !content.channelNames.empty() && content.pixels);
    if (Status writable = checkWritable(path); !writable) return writable;
    if (lowerExtension(path) != ".exr")
        return cannotWrite(path, "is not an .exr name, but the file would be an EXR", "name the output .exr");
    TemporaryFile temp(path);
    if (Status written = writeScanlineWithCore(path, temp.path(), content, half, threads, compression); !written)
        return written;
    return temp.commit();
}

}  // namespace heightpack
