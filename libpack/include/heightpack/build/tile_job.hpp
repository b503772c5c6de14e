// The whole `tile` operation: make a map tile, changing the painting as little as the method allows.
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "heightpack/core/mip.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/core/tileable.hpp"
#include "heightpack/io/read.hpp"

namespace heightpack {

enum class TileMethod {
    Periodic,   // Moisan's periodic component with the edge slopes bent together; where slopes still break at
                // some level or the span grows past 1.5x, a crossfade near the edges (the measure chooses)
    Moisan,     // Moisan's original periodic component: heights meet, slopes may kink at the edges
    Crossfade,  // offset and blend with a histogram-preserving blend over a band
    Mirror,     // mirror tiling: twice the size, symmetric
};
const char* tileMethodName(TileMethod method);

struct TileOptions {
    LoadOptions load;
    MipOptions mip;  // the chain the verdict is judged on, as pack would make it (wrap stays periodic)
    TileMethod method = TileMethod::Periodic;
    double width = 0.1;  // crossfade band, fraction of the tile, (0, 0.5]
    bool force = false;  // apply the method even to a map that already tiles
    double threshold = kDefaultSeamThreshold;
    int bits = 0;  // 8, 16 or 32 (float); 0 keeps the input's depth (float inputs stay float)
    std::string version;
    // Reports progress: the stage ("load", "check", "tile", "write") and the fraction of it done; may be empty.
    std::function<void(std::string_view stage, double fraction)> progress;
};

struct TileReport {
    std::string input;
    std::string output;
    SourceInfo source;          // what the input held and which channel was used
    bool alreadyTiled = false;  // the input passed the check at every level and was written unchanged
    bool written = false;       // false when the method could not make the map tile: nothing was written
    std::string methodUsed;     // "none", the method's name, or what Periodic chose ("moisan+crossfade over 0.1 of the tile")
    ChainSeams before;          // the input, judged at every level as `check` judges it
    ChainSeams after;           // the output as written (rounded to its type), likewise
    double crossfadeWidth = 0.0;  // the band of a crossfade used, fraction of the tile
    int bits = 0;
    // Written as float although the input (or --depth) is an integer type: the heights left [0,1], which
    // an integer type cannot hold without clipping, or (unchanged maps) are not exact in that type.
    bool widened = false;
    double low = 0.0, high = 0.0;  // the range of the heights written
    double inputLow = 0.0, inputHigh = 0.0;
    int width = 0;
    int height = 0;
};

// Judges input at every level pack would make (the seam measure of `check`). If it tiles and !force,
// writes it unchanged: the file's bytes when it is a one-channel file of output's format, else its
// heights in a type that holds them exactly. Otherwise applies the method and judges the result as it
// will be stored; writes it only when it tiles (mirror: when its heights meet, its mirror lines kinking
// slopes by design). Integer outputs are never clipped or rescaled: heights
// outside [0,1] are written as float where the format holds floats (.exr, .tif), else it fails with
// CannotWrite and writes nothing.
Result<TileReport> tileFile(const std::string& input, const std::string& output, const TileOptions& options);

}  // namespace heightpack
