// Writing tiled, mip-mapped float EXRs (flat scanline ones: exr_scanline.cpp, on the helpers here), on two
// paths that produce the same standard file layout:
// - none / zip / zips: our own tile loop on OpenEXRCore. Rows of tiles are packed and deflated on all
//   threads, a row per worker (libdeflate, in EXR's ZIP tile format: bytes split, delta predictor, zlib
//   stream), and written in file order as they are done, so the bytes never depend on the thread count.
//   This is where heightpack beats a general texture maker: OpenEXR 3.1 deflates with zlib, several
//   times slower.
// - rle / piz: OpenEXR's C++ TiledOutputFile, which implements those codecs (exr_write_imf.cpp).
#include <Imath/half.h>
#include <OpenEXR/openexr.h>
#include <libdeflate.h>

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <numeric>
#include <vector>

#include "heightpack/core/mip.hpp"
#include "heightpack/core/parallel.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/files.hpp"

#include "exr_write_parts.hpp"
#include "ordered_writes.hpp"
#include "text.hpp"

namespace heightpack {

namespace detail {

namespace {

// The errors of the write under way on this thread. OpenEXRCore 3.1 calls the handler while it holds the
// context's lock, so asking the context for its user data there waits on that lock forever.
thread_local CoreErrors* currentErrors = nullptr;

extern "C" void rememberCoreError(exr_const_context_t, exr_result_t code, const char* msg) {
    if (currentErrors) currentErrors->last = msg ? msg : exr_get_default_error_message(code);
}

}  // namespace

void reportCoreErrorsTo(CoreErrors& errors) { currentErrors = &errors; }

Status coreFailure(const std::string& finalPath, const CoreErrors& errors, const char* step, exr_result_t rv) {
    const std::string why = errors.last.empty() ? exr_get_default_error_message(rv) : errors.last;
    return cannotWrite(finalPath, std::string(step) + " failed: " + firstLine(why), "check free disk space and permissions");
}

exr_result_t startWrite(exr_context_t* ctxt, const std::string& path, CoreErrors& errors) {
    currentErrors = &errors;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = rememberCoreError;
    exr_result_t rv = exr_start_write(ctxt, path.c_str(), EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS) rv = exr_set_longname_support(*ctxt, 1);
    return rv;
}

void packStorageTile(const float* band, int levelWidth, int channels, const std::vector<int>& nameOrder, int x0,
              int tileWidth, int rows, bool half, std::vector<unsigned char>& out) {
    const size_t start = out.size(), count = size_t(rows) * channels * tileWidth;
    if (half) {
        out.resize(start + count * sizeof(std::uint16_t));
        std::uint16_t* to = reinterpret_cast<std::uint16_t*>(out.data() + start);
        for (int r = 0; r < rows; ++r) {
            const float* line = band + (size_t(r) * levelWidth + x0) * channels;
            for (int c : nameOrder)
                for (int x = 0; x < tileWidth; ++x) *to++ = Imath::half(line[size_t(x) * channels + c]).bits();
        }
        return;
    }
    out.resize(start + count * sizeof(float));
    float* to = reinterpret_cast<float*>(out.data() + start);
    for (int r = 0; r < rows; ++r) {
        const float* line = band + (size_t(r) * levelWidth + x0) * channels;
        for (int c : nameOrder)
            for (int x = 0; x < tileWidth; ++x) *to++ = line[size_t(x) * channels + c];
    }
}

void zipTile(const std::vector<unsigned char>& raw, std::vector<unsigned char>& scratch, std::vector<unsigned char>& out,
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
    // Deflated straight onto the end of out (no copy of the tile's bytes afterwards).
    const size_t start = out.size();
    out.resize(start + libdeflate_zlib_compress_bound(compressor, n));
    const size_t packed = libdeflate_zlib_compress(compressor, scratch.data(), n, out.data() + start, out.size() - start);
    if (packed == 0 || packed >= n) {
        out.resize(start);
        out.insert(out.end(), raw.begin(), raw.end());
    } else {
        out.resize(start + packed);
    }
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

std::vector<int> fileOrder(const std::vector<std::string>& names) {
    std::vector<int> order(names.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return names[a] < names[b]; });
    return order;
}

}  // namespace detail

namespace {

// libdeflate's level 4: on the 4096^2 benchmark map, 68.5 MB against 72.0 MB from OpenEXR's own zip
// (zlib level 4), in about half the CPU time. Fixed, so outputs are reproducible.
constexpr int kDeflateLevel = 4;


// One row of tiles of one level of a tiled file: the rows [y0, y0 + rows) of a level `width` wide.
struct TileRow {
    int level = 0, y0 = 0, rows = 0, width = 0, tilesX = 0;
};

// The same layout as packStorageTile's, appended to out, each line's channel runs taken straight from
// content.fillRun; fails, naming the level, on a value that is not finite. half: halves (via values).
Status runTile(const ChainToWrite& content, const TileRow& job, int x0, int tileWidth, const std::vector<int>& nameOrder,
               bool half, const std::string& finalPath, std::vector<float>& values, std::vector<unsigned char>& out) {
    const size_t count = size_t(job.rows) * nameOrder.size() * tileWidth, start = out.size();
    if (half)
        values.resize(count);
    else
        out.resize(start + count * sizeof(float));
    float* const first = half ? values.data() : reinterpret_cast<float*>(out.data() + start);
    float* to = first;
    for (int r = 0; r < job.rows; ++r)
        for (int c : nameOrder) {
            content.fillRun(job.level, job.y0 + r, x0, tileWidth, c, to);
            to += tileWidth;
        }
    if (Status finite = detail::requireFinite(finalPath, first, count, job.level); !finite) return finite;
    if (half) {
        out.resize(start + count * sizeof(std::uint16_t));
        std::uint16_t* bits = reinterpret_cast<std::uint16_t*>(out.data() + start);
        for (size_t i = 0; i < count; ++i) bits[i] = Imath::half(values[i]).bits();
    }
    return Done{};
}

Status writeWithCore(const std::string& finalPath, const std::string& path, const ChainToWrite& content,
                     const ExrWriteOptions& options) {
    detail::CoreErrors errors;
    exr_context_t ctxt = nullptr;
    auto fail = [&](const char* step, exr_result_t rv) { return detail::coreFailure(finalPath, errors, step, rv); };
    exr_result_t rv = detail::startWrite(&ctxt, path, errors);
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
    if ((rv = detail::addAttributes(ctxt, part, content.attributes))) return fail("adding an attribute", rv);
    if ((rv = exr_write_header(ctxt))) return fail("writing the header", rv);

    const int channels = static_cast<int>(content.channelNames.size());
    const std::vector<int> nameOrder = detail::fileOrder(content.channelNames);

    int levels = 0;
    if ((rv = exr_get_tile_levels(ctxt, part, &levels, nullptr))) return fail("counting levels", rv);
    // Every row of tiles of every level, in file order: the jobs.
    const int ts = options.tileSize;
    std::vector<TileRow> jobs;
    for (int level = 0; level < levels; ++level) {
        const int w = mipLevelSide(content.width, level), h = mipLevelSide(content.height, level);
        for (int y0 = 0; y0 < h; y0 += ts) jobs.push_back({level, y0, std::min(ts, h - y0), w, (w + ts - 1) / ts});
    }
    const size_t bandFloats = size_t(content.width) * std::min(ts, content.height) * channels;

    // A row of tiles is a piece: a worker fills, checks, packs and deflates it alone, and the rows reach the
    // file in order as they are done (ordered_writes.hpp). At most 2 rows a worker wait in memory, each as
    // its tiles' bytes end to end (not a deflate bound a tile), in a ring of buffers reused row after row.
    const int workers = std::min<int>(resolveThreadCount(options.threads), int(jobs.size()));
    const size_t window = 2 * size_t(workers);
    struct Row {
        std::vector<unsigned char> bytes;
        std::vector<size_t> ends;  // where each tile's bytes end
    };
    struct Worker {
        std::vector<float> band, values;
        std::vector<unsigned char> raw, scratch;
        std::unique_ptr<libdeflate_compressor, void (*)(libdeflate_compressor*)> compressor{nullptr, libdeflate_free_compressor};
    };
    std::vector<Row> ring(window);
    std::vector<Worker> own(static_cast<size_t>(workers));
    const bool runs = bool(content.fillRun);
    for (Worker& w : own) {
        if (!runs) w.band.resize(bandFloats);
        if (zip) w.compressor.reset(libdeflate_alloc_compressor(kDeflateLevel));
    }
    const long long rowsTotal = std::accumulate(jobs.begin(), jobs.end(), 0LL, [](long long n, const TileRow& j) { return n + j.rows; });
    long long rowsDone = 0;
    EarlyWriteback writeback(path);
    auto make = [&](size_t j, size_t slot, int worker) -> Status {
        const TileRow& job = jobs[j];
        Row& row = ring[slot];
        Worker& w = own[size_t(worker)];
        if (!runs) {
            content.fillRows(job.level, job.y0, job.rows, w.band.data());
            if (Status s = detail::requireFinite(finalPath, w.band.data(), size_t(job.width) * job.rows * channels, job.level); !s)
                return s;
        }
        row.bytes.clear();
        row.ends.clear();
        for (int tx = 0; tx < job.tilesX; ++tx) {
            const int x0 = tx * ts, tileWidth = std::min(ts, job.width - x0);
            // Laid out onto the row's bytes, or into raw to be deflated onto them.
            std::vector<unsigned char>& laidOut = zip ? w.raw : row.bytes;
            if (zip) w.raw.clear();
            if (runs) {
                if (Status s = runTile(content, job, x0, tileWidth, nameOrder, options.half, finalPath, w.values, laidOut); !s)
                    return s;
            } else {
                detail::packStorageTile(w.band.data(), job.width, channels, nameOrder, x0, tileWidth, job.rows, options.half, laidOut);
            }
            if (zip) detail::zipTile(w.raw, w.scratch, row.bytes, w.compressor.get());
            row.ends.push_back(row.bytes.size());
        }
        return Done{};
    };
    auto write = [&](size_t j, size_t slot) -> Result<size_t> {
        detail::reportCoreErrorsTo(errors);  // OpenEXRCore reports on the thread that writes
        const TileRow& job = jobs[j];
        const Row& row = ring[slot];
        for (int tx = 0; tx < job.tilesX; ++tx) {
            const size_t begin = tx > 0 ? row.ends[tx - 1] : 0;
            if (exr_result_t r = exr_write_tile_chunk(ctxt, part, tx, job.y0 / ts, job.level, job.level, row.bytes.data() + begin,
                                                      row.ends[tx] - begin))
                return fail("writing a tile", r).error();
        }
        rowsDone += job.rows;
        if (options.progress) options.progress(double(rowsDone) / rowsTotal);
        return row.bytes.size();
    };
    const Status made = detail::makeAndWriteInOrder(jobs.size(), workers, window, writeback, make, write);
    detail::reportCoreErrorsTo(errors);
    if (!made) return made;
    guard.release();
    if ((rv = exr_finish(&ctxt))) return fail("finishing the file", rv);
    return Done{};
}

}  // namespace

Status writeTiledExr(const std::string& path, const ChainToWrite& content, const ExrWriteOptions& options) {
    assert(content.width > 0 && content.height > 0 && !content.channelNames.empty() && content.fillRows);
    if (Status writable = checkWritable(path); !writable) return writable;
    const std::string ext = lowerExtension(path);
    if (ext != ".exr")  // never EXR bytes under another format's name
        return cannotWrite(path, "is not an .exr name, but the file would be an EXR", "name the output .exr");
    TemporaryFile temp(path);
    const bool core = options.compression == Compression::None || options.compression == Compression::Zip ||
                      options.compression == Compression::Zips;
    Status written = core ? writeWithCore(path, temp.path(), content, options)
                          : detail::writeTiledWithImf(path, temp.path(), content, options);
    if (!written) return written;
    return temp.commit();
}

}  // namespace heightpack
