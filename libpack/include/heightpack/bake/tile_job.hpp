// The whole `tile` operation: make a map tile, changing the painting as little as the method allows.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "heightpack/core/mip.hpp"
#include "heightpack/core/names.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/core/tile/look.hpp"
#include "heightpack/core/tile/tileable.hpp"
#include "heightpack/io/read.hpp"
#include "heightpack/version.hpp"

namespace heightpack {

enum class TileMethod {
    Periodic,   // re-synthesis of a band around each wrap line (core/tile_resynthesis.hpp), the large scales
                // made periodic by Moisan's smooth field; judged by the seam measure and the look, with
                // another seed and then a wider band when a result does not pass
    Quilt,      // a strip across each wrap line copied from where it matches best, cut in and healed
                // (core/tile_quilt.hpp): for structured maps (pebbles, cells, strokes) that a Gaussian field
                // does not describe
    Moisan,     // Moisan's original periodic component: heights meet, slopes may kink at the edges
    Crossfade,  // offset and blend: four copies, the high-pass blended keeping variance (leaves an echo)
    Mirror,     // mirror tiling: twice the size, symmetric
};
template <>
struct NameTable<TileMethod> {
    static constexpr EnumName<TileMethod> entries[] = {
        {TileMethod::Periodic, "periodic", "re-synthesise a band around each wrap line"},
        {TileMethod::Quilt, "quilt", "copy a strip from elsewhere in the map across each wrap line"},
        {TileMethod::Moisan, "moisan", "Moisan's periodic component"},
        {TileMethod::Crossfade, "crossfade", "offset and blend"},
        {TileMethod::Mirror, "mirror", "mirror tiling, twice the size"},
    };
};

struct TileOptions {
    LoadOptions load;
    MipOptions mip;  // the chain the verdict is judged on, as pack would make it (wrap stays periodic)
    TileMethod method = TileMethod::Periodic;
    double width = 0.1;  // crossfade band, fraction of the tile, (0, 0.5]
    bool force = false;  // apply the method even to a map that already tiles
    double threshold = kDefaultSeamThreshold;
    LookThresholds look;  // what Periodic's result must pass beyond its seams (frame, blobs, echo)
    uint64_t seed = 1;    // Periodic's re-synthesis noise (the next seeds when a result does not pass)
    int bits = 0;  // 8, 16 or 32 (float); 0 keeps the input's depth (float inputs stay float)
    std::string version = kVersion;  // this library's (heightpack/version.hpp); recorded in outputs, part of cache keys
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
    TileLook look;              // the output's frame, blobs and echo (the input's own echo subtracted)
    LookThresholds lookThresholds;
    int bandX = 0, bandY = 0;   // Periodic, quilt: texels re-synthesised (or quilted) across the left/right and top/bottom wrap lines
    uint64_t seed = 0;          // Periodic: the seed of the result written
    int match = 0;              // quilt: which source match was copied (1 the best, 2 the next), else 0
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
// slopes by design) and, for Periodic, when its look passes too (the other methods' looks are reported). Integer outputs are never clipped or rescaled: heights
// outside [0,1] are written as float where the format holds floats (.exr, .tif), else it fails with
// CannotWrite and writes nothing.
Result<TileReport> tileFile(const std::string& input, const std::string& output, const TileOptions& options);

}  // namespace heightpack
