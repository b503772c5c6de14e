// Internal: what the EXR writers share. exr_write.cpp writes tiled files (none, zip, zips) on OpenEXRCore
// and holds the helpers below; exr_scanline.cpp writes flat scanline files on them; exr_write_imf.cpp
// writes rle and piz tiles through OpenEXR's C++ library, which implements those codecs.
#pragma once

#include <OpenEXR/openexr.h>
#include <libdeflate.h>

#include <cstddef>
#include <string>
#include <vector>

#include "heightpack/io/exr_write.hpp"

namespace heightpack::detail {

// The last guard before bytes reach a file: an output never holds NaN or infinity. Whatever let one
// through (an option or input check missing) is a bug, reported as one, naming the level.
Status requireFinite(const std::string& path, const float* values, size_t count, int level);

// Writes content as writeTiledExr describes, through Imf::TiledOutputFile, to path (the temporary file
// whose errors are reported under finalPath).
Status writeTiledWithImf(const std::string& finalPath, const std::string& path, const ChainToWrite& content,
                         const ExrWriteOptions& options);

// ---- On OpenEXRCore ----

// The last error OpenEXRCore reported for one write.
struct CoreErrors {
    std::string last;
};

// Starts writing path, with errors remembered in errors (for this thread's calls) and attribute names over
// 31 characters allowed (heightpack:significantWaveHeight has 32; OpenEXR's C++ library sets the same flag).
exr_result_t startWrite(exr_context_t* ctxt, const std::string& path, CoreErrors& errors);
// From now on this thread's OpenEXRCore errors go to errors too (a worker that writes chunks).
void reportCoreErrorsTo(CoreErrors& errors);
// The CannotWrite error for a failed step: OpenEXRCore's own message when it gave one.
Status coreFailure(const std::string& finalPath, const CoreErrors& errors, const char* step, exr_result_t rv);

exr_result_t addAttributes(exr_context_t ctxt, int part, const std::vector<ExrAttribute>& attributes);

// The channels' order in the file (EXR sorts them by name), as indices into names.
std::vector<int> fileOrder(const std::vector<std::string>& names);

// Appends one tile's texels to out in EXR's uncompressed tile layout: line by line, and within a line each
// channel's run of floats (or halves), channels in name order. band holds the tile's rows, levelWidth
// texels of `channels` interleaved floats each; the tile starts at texel x0.
void packStorageTile(const float* band, int levelWidth, int channels, const std::vector<int>& nameOrder, int x0,
              int tileWidth, int rows, bool half, std::vector<unsigned char>& out);

// EXR's ZIP tile compression (as ImfZip.cpp) of raw, appended to out: even and odd bytes split and
// delta-coded (in scratch), deflated as a zlib stream; the raw bytes themselves when compression would not
// make them smaller, as EXR requires.
void zipTile(const std::vector<unsigned char>& raw, std::vector<unsigned char>& scratch, std::vector<unsigned char>& out,
             libdeflate_compressor* compressor);

}  // namespace heightpack::detail
