// OpenEXR files written on our own OpenEXRCore path, atomically: tiled, mip-mapped float maps a band at a
// time, and flat scanline maps (what writeFlatImage writes as .exr).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "heightpack/core/names.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/attributes.hpp"

namespace heightpack {

// EXR compressions offered: the lossless ones, since heights must come back exactly as computed.
enum class Compression { None, Rle, Zips, Zip, Piz };
template <>
struct NameTable<Compression> {
    static constexpr EnumName<Compression> entries[] = {
        {Compression::None, "none", "no compression"},
        {Compression::Rle, "rle", "run-length"},
        {Compression::Zips, "zips", "zlib, one scanline at a time"},
        {Compression::Zip, "zip", "zlib, 16 scanlines at a time"},
        {Compression::Piz, "piz", "wavelet"},
    };
};

// A mip chain as every mip-mapped writer (tiled EXR, KTX2, DDS) takes it: its level-0 size, channel names,
// and a function that fills any band of rows of any level on demand, so a writer never holds more than a
// band of output; and the attributes to record.
struct ChainToWrite {
    int width = 0;
    int height = 0;
    std::vector<std::string> channelNames;  // interleaved in this order in the rows fillRows writes
    // Writes `rows` rows of level `level` starting at y0 into dst (levelWidth * channels floats a row).
    std::function<void(int level, int y0, int rows, float* dst)> fillRows;
    // Optional: `count` values of channel `channel` of row y of level `level` from texel x0, as fillRows
    // would put them at dst[x * channels + channel]. A writer that lays the channels of a row apart (an EXR
    // tile: a line is each channel's run in turn) takes the runs straight from it, with no band of
    // interleaved rows to fill and gather from. Empty: such writers go through fillRows.
    std::function<void(int level, int y, int x0, int count, int channel, float* dst)> fillRun;
    std::vector<ExrAttribute> attributes;
    // An array texture (KTX2 layerCount, DDS arraySize; an EXR has none and holds layers as channels
    // NAME.R ... instead): each layer's name in order, every layer of the same size and of channelNames,
    // its rows filled by fillLayerRows(layer, level, y0, rows, dst) as fillRows fills a single texture's.
    // Empty: a single texture, filled by fillRows.
    std::vector<std::string> layerNames;
    std::function<void(int layer, int level, int y0, int rows, float* dst)> fillLayerRows;
    int layerCount() const { return layerNames.empty() ? 1 : static_cast<int>(layerNames.size()); }
};

struct ExrWriteOptions {
    Compression compression = Compression::Zip;
    int tileSize = 64;
    int threads = 0;  // for packing and compressing tiles; 0 = all cores; the bytes do not depend on it
    bool half = false;  // 16-bit half channels, each value rounded to nearest; the caller checks the range
    // Called after each row of tiles with the fraction written so far; may be empty.
    std::function<void(double fraction)> progress;
};

// Writes content as a tiled (tileSize^2), MIPMAP_LEVELS, ROUND_DOWN EXR of 32-bit float (or half) channels. The
// file appears at path only once complete: it is written to a temporary file in the same folder and
// renamed, so a failure or interruption leaves no partial file and any existing file untouched.
Status writeTiledExr(const std::string& path, const ChainToWrite& content, const ExrWriteOptions& options);

// A flat (one-level) scanline EXR: interleaved float pixels, each channel stored as float or half.
struct ScanlineExrContent {
    int width = 0;
    int height = 0;
    std::vector<std::string> channelNames;  // interleaved in this order in pixels
    const float* pixels = nullptr;          // width * height * channelNames.size() values, row by row
    std::vector<ExrAttribute> attributes;
};

// Writes content as a scanline EXR, atomically as writeTiledExr does: in ZIP (16 rows a block; lossless),
// ZIPS (one row a block) or uncompressed (None; any other compression is taken as Zip). The blocks are
// packed (and deflated) on `threads` threads (0 = all cores) and written in file order, so the bytes never
// depend on the thread count. A non-finite value is an internal error: nothing is written.
Status writeScanlineExr(const std::string& path, const ScanlineExrContent& content, bool half, int threads,
                        Compression compression = Compression::Zip);

}  // namespace heightpack
