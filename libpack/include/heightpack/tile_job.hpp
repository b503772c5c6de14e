// The whole `tile` operation: make a map tile, changing the painting as little as the method allows.
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "heightpack/io.hpp"
#include "heightpack/result.hpp"
#include "heightpack/tileable.hpp"

namespace heightpack {

enum class TileMethod {
    Periodic,   // periodic + smooth with slopes continued across the edges: only a smooth field is subtracted
    Moisan,     // Moisan's original periodic component: heights meet, slopes may kink at the edges
    Crossfade,  // offset and blend with a histogram-preserving blend over a band
    Mirror,     // mirror tiling: twice the size, symmetric
};
const char* tileMethodName(TileMethod method);

struct TileOptions {
    LoadOptions load;
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
    bool alreadyTiled = false;  // the input passed the check and was copied unchanged
    LevelSeams before;          // level 0 of the input
    LevelSeams after;           // level 0 of the output
    int bits = 0;
    // An integer output holds [0,1]: a result reaching outside is mapped back by
    // stored = (value - remapOffset) * remapScale (affine, so it still tiles), instead of being clipped.
    bool remapped = false;
    double remapScale = 1.0;
    double remapOffset = 0.0;
    int width = 0;
    int height = 0;
};

// Checks input (level 0); if it tiles and !force, copies it to output unchanged. Otherwise applies the
// method and writes the result at the input's bit depth (or options.bits), recording what was done in
// the metadata.
Result<TileReport> tileFile(const std::string& input, const std::string& output, const TileOptions& options);

}  // namespace heightpack
