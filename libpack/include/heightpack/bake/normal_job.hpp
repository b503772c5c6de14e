// The whole `normal` operation: load heights, filter a mip chain, derive normals per level, write.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "heightpack/core/layout.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/normal.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/read.hpp"
#include "heightpack/io/texture_storage.hpp"
#include "heightpack/version.hpp"

namespace heightpack {

enum class NormalFormat {
    Exr,   // mip-mapped RGB(A), xyz in [-1,1], like the packed heights: EXR, KTX2 or DDS by the extension
    Png8,  // level 0 only, 8-bit, rgb = 0.5 + 0.5 n
};
template <>
struct NameTable<NormalFormat> {
    static constexpr EnumName<NormalFormat> entries[] = {
        {NormalFormat::Exr, "exr", "mip-mapped, in an .exr, .ktx2 or .dds"},
        {NormalFormat::Png8, "png8", "level 0 alone, 8-bit PNG"},
    };
};

struct NormalJobOptions {
    LoadOptions load;
    NormalOptions normal;             // tile size, height range, kernel, wrap, convention, alpha, threads
    Filter filter = Filter::Kaiser;   // for the height mip chain the normals are derived from
    bool resizeToPowerOfTwo = false;  // EXR only: a mip chain needs power-of-two sides
    NormalFormat format = NormalFormat::Exr;
    // Mip-mapped outputs: pixel type or "auto" within a tolerance (normal units), EXR compression, KTX2
    // supercompression.
    TextureStorage storage;
    // With storage.tolerance 0 and this > 0, the tolerance as a height error in metres instead: the tilt
    // that error makes across one texel of level 0 (the longer side of a texel, so the stricter), this /
    // texel size, in normal units; the job converts it once it knows the map's size.
    double toleranceMetres = 0.0;
    // Rgb: x, y, z (and alpha). Xy: x and y alone, for a shader that rebuilds z; mip-mapped outputs
    // without alpha only.
    Layout layout = Layout::Rgb;
    std::string version = kVersion;  // this library's (heightpack/version.hpp); recorded in outputs, part of cache keys
    std::function<void(std::string_view stage, double fraction)> progress;
};

struct NormalReport {
    std::string input;
    std::string output;
    SourceInfo source;
    std::string sourceHash;
    bool resized = false;
    std::vector<std::pair<int, int>> levelSizes;
    double maxSlopeDegrees = 0.0;  // steepest normal at level 0, for a sanity check of the units
    double seconds = 0.0;
    Layout layout = Layout::Rgb;
    PixelType pixelType = PixelType::Float;  // as written (the choice, with a tolerance); float for a PNG
    std::vector<double> lookupError;         // per level, normal units; empty for a PNG
    double tolerance = 0.0;                  // the pixel type was chosen within this (normal units); 0: given
    bool toleranceInDegrees = false;         // tolerance is an angle in degrees instead
    // Per level, the worst angle in degrees between a stored normal and its own: block formats, and any
    // type chosen within a tolerance in degrees; empty otherwise.
    std::vector<double> angleError;
};

// The EXR compression for normals when the caller names none. Float normals are stored uncompressed:
// their mantissas are noise to deflate, which saved 0.9-5.5% of the bytes of the example maps' and a
// 4096^2 map's normals (2.3% there) at 3-4x the CPU time of the whole command. Half normals, and "auto"
// (tolerance > 0; a normal map's choice is half unless the tolerance is below half's error), keep zip,
// which halves their bytes.
Compression defaultNormalCompression(PixelType requested, double tolerance);

// The normals `normal` writes, made in memory.
struct NormalMaps {
    std::vector<Image> chain;      // RGB(A) per level, xyz in [-1, 1]; level 0 alone for NormalFormat::Png8
    bool resized = false;          // the heights were resampled to power-of-two sides first
    double maxSlopeDegrees = 0.0;  // steepest normal at level 0
};

// What makeNormalMap would write (before a PNG's 0.5 + 0.5 n encoding) for heights already loaded: for
// NormalFormat::Exr a mip chain of the heights (power-of-two sides, resized when
// options.resizeToPowerOfTwo, else BadInput naming source.path) with a normal level per height level; for
// Png8 the normals of level 0 alone, at any size. Reports the "mip" and "normal" stages to options.progress.
Result<NormalMaps> makeNormalChain(Image heights, const SourceInfo& source, const NormalJobOptions& options);

// Loads input, makes its normals with makeNormalChain and writes them to output in options.format.
Result<NormalReport> makeNormalMap(const std::string& input, const std::string& output,
                                   const NormalJobOptions& options);

}  // namespace heightpack
