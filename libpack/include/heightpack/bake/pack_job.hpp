// The whole `pack` operation in one call: load, scale, mip, pack, write. The CLI and build steps call this;
// packHeights is the same operation on heights already in memory (the viewer, an engine).
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "heightpack/core/layout.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/read.hpp"
#include "heightpack/io/texture_storage.hpp"
#include "heightpack/version.hpp"

namespace heightpack {

struct PackOptions {
    LoadOptions load;
    MipOptions mip;                    // filter, wrap, threads
    float scale = 1.0f;                // stored height = offset + scale * painted value
    float offset = 0.0f;
    bool resizeToPowerOfTwo = false;   // else a size that is not a power of two is refused
    // How the texels are stored in whichever container the output's extension names (.exr, .ktx2, .dds):
    // pixel type or "auto" within a tolerance (stored units), EXR compression, KTX2 supercompression.
    TextureStorage storage;
    std::string plainOutput;           // also write the unpacked one-channel chain here, if not empty
    // Neighbour4: the packed chain at output. Plain: only the unpacked one-channel chain, at output
    // (textureGather or hardware filtering; foam, masks); plainOutput must then be empty.
    Layout layout = Layout::Neighbour4;
    double heightRange = 0.0;          // metres between a stored 0.0 and 1.0, when known: recorded, errors in metres
    // Also keep the input's shift (its Dx, Dy; see pack_shift.hpp), packed beside
    // the heights in the same EXR. An input without it is refused (BadInput, Fix::AddShift).
    bool shift = false;
    // Also keep the input's foam coverage (its Foam channel, as synth --foam writes it; see pack_foam.hpp),
    // packed beside the heights (and Dx, Dy) in the same EXR as layer Foam. An input without it is refused
    // (BadInput).
    bool foam = false;
    std::string version = kVersion;  // this library's (heightpack/version.hpp); recorded in outputs, part of cache keys
    // Reports progress: the stage ("load", "mip", "write") and the fraction of it done.
    std::function<void(std::string_view stage, double fraction)> progress;
};

struct PackReport {
    std::string input;
    std::string output;
    std::string plainOutput;
    SourceInfo source;
    std::string sourceHash;
    bool resized = false;
    std::vector<std::pair<int, int>> levelSizes;  // level 0 first
    Layout layout = Layout::Neighbour4;           // of output
    Container container = Container::Exr;         // of output, as its name decided it
    PixelType pixelType = PixelType::Float;       // as written (the choice, with a tolerance)
    std::vector<double> lookupError;              // per level, stored units (see worstLookupError)
    double loadSeconds = 0.0;
    double mipSeconds = 0.0;
    double writeSeconds = 0.0;
};

// The chains `pack` writes, made in memory.
struct PackedMaps {
    std::vector<Image> plain;   // one channel per level, level 0 first: the stored heights (offset + scale * value)
    std::vector<Image> packed;  // the same levels 4-neighbour packed (RGBA); empty for Layout::Plain
    bool resized = false;       // level 0 was resampled to power-of-two sides
};

// What packHeightMap would write for heights already loaded: sides made powers of two (when
// options.resizeToPowerOfTwo, else such heights fail with BadInput naming source.path), scaled, mip-mapped
// with options.mip and packed with its wrap mode. Reports the "mip" stage to options.progress. Output
// paths, compression and version in options are not used.
Result<PackedMaps> packHeights(Image heights, const SourceInfo& source, const PackOptions& options);

// Packs the height map at input into a 4-neighbour packed, mip-mapped texture at output: EXR, KTX2 or DDS
// by its extension, in options.storage.
Result<PackReport> packHeightMap(const std::string& input, const std::string& output, const PackOptions& options);

// The header attributes heightpack records for a chain written with these options and layout
// (Neighbour4 or Plain).
std::vector<ExrAttribute> heightAttributes(Layout layout, const PackOptions& options,
                                           const SourceInfo& source, const std::string& sourceHash);

}  // namespace heightpack
