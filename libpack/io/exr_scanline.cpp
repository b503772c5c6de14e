// Flat scanline EXRs (synth's maps, tile's, fresnel's, the manifest's intermediates) on OpenEXRCore and
// libdeflate, with the tiled writer's helpers (exr_write_parts.hpp).
#include <OpenEXR/openexr.h>
#include <libdeflate.h>

#include <algorithm>
#include <cassert>
#include <memory>
#include <string>
#include <vector>

#include "heightpack/core/parallel.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/files.hpp"

#include "exr_write_parts.hpp"
#include "ordered_writes.hpp"

namespace heightpack {

namespace detail {

namespace {

// Level 1: on synth's 4096^2 map with shift and foam, 194.6 MB against 194.2 MB at level 4, in
// about 17% less time (float noise barely compresses).
constexpr int kScanlineDeflateLevel = 1;

// The flat scanline file: blocks of rows (16 for ZIP and None, 1 for ZIPS), packed (and deflated) on all
// threads and written in order. It replaced OpenImageIO's writer (zlib through OpenEXR 3.1), which took
// about 40% of `synth`'s time; the file holds the same channels, types and attributes.
Status writeScanlineWithCore(const std::string& finalPath, const std::string& path, const ScanlineExrContent& content,
                             bool half, int threads, Compression compression) {
    CoreErrors errors;
    exr_context_t ctxt = nullptr;
    auto fail = [&](const char* step, exr_result_t rv) { return coreFailure(finalPath, errors, step, rv); };
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
    // A block is a piece: a worker checks, packs (and deflates) it, and the blocks reach the file in order
    // as they are done (ordered_writes.hpp), the writes overlapping the packing of the blocks after. The
    // ring of blocks waiting is reserved here, on this thread: a worker's own allocations would come from
    // its own arena, new memory beside the caller's freed heap.
    const int workers = std::min(resolveThreadCount(threads), blocks);
    const size_t window = 2 * size_t(workers);
    std::vector<std::vector<unsigned char>> packed(window);
    libdeflate_compressor* sizing = libdeflate_alloc_compressor(kScanlineDeflateLevel);
    const size_t rawBlock = size_t(linesPerBlock) * content.width * channels * (half ? 2 : 4);
    for (std::vector<unsigned char>& block : packed) block.reserve(zip ? libdeflate_zlib_compress_bound(sizing, rawBlock) : rawBlock);
    libdeflate_free_compressor(sizing);
    struct Worker {
        std::vector<unsigned char> raw, scratch;
        std::unique_ptr<libdeflate_compressor, void (*)(libdeflate_compressor*)> compressor{nullptr, libdeflate_free_compressor};
    };
    std::vector<Worker> own(static_cast<size_t>(workers));
    for (Worker& w : own) {
        if (!zip) continue;
        w.compressor.reset(libdeflate_alloc_compressor(kScanlineDeflateLevel));
        w.raw.reserve(rawBlock);
        w.scratch.reserve(rawBlock);
    }
    auto make = [&](size_t block, size_t slot, int worker) -> Status {
        const int y0 = int(block) * linesPerBlock, rows = std::min(linesPerBlock, content.height - y0);
        const float* band = content.pixels + size_t(y0) * content.width * channels;
        if (Status s = requireFinite(finalPath, band, size_t(content.width) * rows * channels, 0); !s) return s;
        Worker& w = own[size_t(worker)];
        packed[slot].clear();
        w.raw.clear();
        packStorageTile(band, content.width, channels, nameOrder, 0, content.width, rows, half, zip ? w.raw : packed[slot]);
        if (zip) zipTile(w.raw, w.scratch, packed[slot], w.compressor.get());
        return Done{};
    };
    auto write = [&](size_t block, size_t slot) -> Result<size_t> {
        reportCoreErrorsTo(errors);  // OpenEXRCore reports on the thread that writes
        if (exr_result_t r = exr_write_scanline_chunk(ctxt, part, int(block) * linesPerBlock, packed[slot].data(), packed[slot].size()))
            return fail("writing rows", r).error();
        return packed[slot].size();
    };
    EarlyWriteback writeback(path);
    const Status made = makeAndWriteInOrder(size_t(blocks), workers, window, writeback, make, write);
    reportCoreErrorsTo(errors);
    if (!made) return made;
    guard.release();
    if ((rv = exr_finish(&ctxt))) return fail("finishing the file", rv);
    return Done{};
}

}  // namespace

}  // namespace detail

Status writeScanlineExr(const std::string& path, const ScanlineExrContent& content, bool half, int threads,
                        Compression compression) {
    assert(content.width > 0 && content.height > 0 && !content.channelNames.empty() && content.pixels);
    if (Status writable = checkWritable(path); !writable) return writable;
    if (lowerExtension(path) != ".exr")
        return cannotWrite(path, "is not an .exr name, but the file would be an EXR", "name the output .exr");
    TemporaryFile temp(path);
    if (Status written = detail::writeScanlineWithCore(path, temp.path(), content, half, threads, compression); !written)
        return written;
    return temp.commit();
}

}  // namespace heightpack
