// The whole `pack` operation in one call: load, scale, mip, pack, write. The CLI and build steps call this.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "heightpack/io/read.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/result.hpp"

namespace heightpack {

struct PackOptions {
    LoadOptions load;
    MipOptions mip;                    // filter, wrap, threads
    float scale = 1.0f;                // stored height = offset + scale * painted value
    float offset = 0.0f;
    bool resizeToPowerOfTwo = false;   // else a size that is not a power of two is refused
    Compression compression = Compression::Zip;
    std::string plainOutput;           // also write the unpacked one-channel chain here, if not empty
    bool packed = true;                // false: write only the unpacked chain, at output (foam, masks)
    std::string version;               // recorded as heightpack:version
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
    double loadSeconds = 0.0;
    double mipSeconds = 0.0;
    double writeSeconds = 0.0;
};

// Packs the height map at input into a 4-neighbour packed, mip-mapped RGBA32F EXR at output.
Result<PackReport> packHeightMap(const std::string& input, const std::string& output, const PackOptions& options);

// The header attributes heightpack records for a chain written with these options and layout
// ("neighbour4" or "plain").
std::vector<ExrAttribute> heightAttributes(std::string_view layout, const PackOptions& options,
                                           const SourceInfo& source, const std::string& sourceHash);

}  // namespace heightpack
