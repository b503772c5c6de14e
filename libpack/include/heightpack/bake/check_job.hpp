// The whole `check` operation: does a map, or a texture heightpack wrote, tile at every mip level?
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "heightpack/core/mip.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/core/tile/look.hpp"
#include "heightpack/core/tile/tileable.hpp"
#include "heightpack/io/read.hpp"

namespace heightpack {

struct CheckOptions {
    LoadOptions load;
    MipOptions mip;  // the chain `pack` would make from a flat image (a texture's own levels are used as they are)
    double threshold = kDefaultSeamThreshold;
    // What the eye sees at the tile grid (frame, blobs, echo of level 0): always measured; a map that
    // exceeds these fails the check only with lookFails (otherwise it is a warning the shell words).
    LookThresholds look;
    bool lookFails = false;
    std::string previewPath;  // write the 2x2 seam preview PNG here, if not empty
    // Reports progress: the stage ("load", "mip", "check") and the fraction of it done; may be empty.
    std::function<void(std::string_view stage, double fraction)> progress;
};

struct CheckReport {
    std::string input;
    std::string kind;   // "image" (levels made as pack would), "neighbour4", "plain", "normal" or "texture"
    std::string note;   // e.g. why only level 0 was scored
    Fix noteFix = Fix::None;  // the remedy the note points at, for the shell to word (ResizeToPowerOfTwo)
    SourceInfo source;  // for an image: what it held and which channel was used (empty for a texture's levels)
    double threshold = kDefaultSeamThreshold;
    std::vector<LevelSeams> levels;
    LevelSeams worst;  // per edge pair, the highest scores over the measured levels
    std::optional<SeamFailure> failure;  // the first failing edge, finest level first
    std::optional<PackingCheck> packing;  // for neighbour4 textures
    bool tiles = true;  // every measured level passes (and the packing is consistent)
    TileLook look;      // level 0's frame, blobs and echo
    LookThresholds lookThresholds;
    bool lookFails = false;  // CheckOptions::lookFails: a look over its thresholds fails the check
    bool looksRight() const { return look.passes(lookThresholds); }
    // The verdict: seams pass at every level, and the look too when it counts.
    bool passed() const { return tiles && (!lookFails || looksRight()); }
};

// The quantum of a source's samples: 1/255 for 8 bits, 1/65535 for 16, 0 for float.
double sampleQuantum(const SourceInfo& source);

// The seams of the mip chain `pack` would make from a flat map: the whole chain when the sides are powers
// of two, else level 0 alone (pack would resize first; *note then says so). Level 0 is the heights
// themselves, not a copy.
ChainSeams measureSeamChain(const Image& heights, const MipOptions& mip, double threshold, const SeamOptions& seams,
                            std::string* note = nullptr);

// The verdict on heights already loaded (a flat map): the chain measureSeamChain measures, scored level by
// level, the sample quantum taken from source. Kind "image"; input is source.path. Writes nothing:
// options.previewPath is not used (seamPreview(heights, report.worst, report.threshold) draws the preview).
CheckReport checkHeights(const Image& heights, const SourceInfo& source, const CheckOptions& options);

// Scores the seams of the file at path at every level. A flat image gets the mip chain pack would make;
// an EXR with mip levels is scored level by level as stored, on its first channel (the height R of a
// packed texel). Fails only when the file cannot be read or the preview cannot be written.
Result<CheckReport> checkFile(const std::string& path, const CheckOptions& options);

}  // namespace heightpack
