// Does a map tile? Seam scores per edge pair and mip level, and three ways to make a map tile.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "heightpack/image.hpp"

namespace heightpack {

// How the tile boundary compares with the interior along one direction. Each score is the mean absolute
// difference across the boundary (texel W-1 to texel 0, seen as neighbours when tiled) divided by the
// median, over the 16 interior columns (rows) nearest the boundary, of the same statistic: about 1 where
// the boundary is like the places beside it, large at a seam. `value` compares first differences (a jump
// in height); `slope` compares second differences (a kink: heights meet but slopes do not).
struct SeamScore {
    double value = 1.0;
    double slope = 1.0;
    bool measured = false;  // false below 16 texels along the direction (or 4 across): too few to judge
};

struct LevelSeams {
    int width = 0;
    int height = 0;
    SeamScore leftRight;  // the left and right edges meeting (differences along x)
    SeamScore topBottom;  // the top and bottom edges meeting (differences along y)
};

// The default verdict threshold: a boundary whose differences are more than twice the interior's median
// column fails. Tileable maps score about 1 (their boundary is just another column); a seam a person
// notices scores several times more.
inline constexpr double kDefaultSeamThreshold = 2.0;

// Scores of one level (channel 0). A direction needs at least 16 texels along it and 4 across.
LevelSeams measureSeams(const Image& level);

// Whether a measured score passes the threshold (both value and slope must).
bool seamPasses(const SeamScore& score, double threshold = kDefaultSeamThreshold);
bool levelTiles(const LevelSeams& seams, double threshold = kDefaultSeamThreshold);

// ---- Making a map tile ----

// Which discontinuities the periodic component removes.
enum class PeriodicContinuity {
    Heights,           // Moisan 2011 exactly: heights meet at the edges; slopes may still kink there
    HeightsAndSlopes,  // the boundary image built from second differences: heights and slopes meet
};

// Moisan's periodic + smooth decomposition ("Periodic plus smooth image decomposition", J. Math.
// Imaging Vis. 2011): returns the periodic component u - s, where s is the smooth (harmonic inside the
// tile) field whose periodic Laplacian equals the boundary image of u. Changes the map only by that
// smooth field and keeps its mean. With HeightsAndSlopes (the default) the boundary image holds the
// second differences across each edge rather than the jumps, so slopes continue across the edge too:
// lighting from a normal map sees no line where Moisan's original leaves a kink. Any size.
Image periodicComponent(const Image& map, PeriodicContinuity continuity = PeriodicContinuity::HeightsAndSlopes);

enum class CrossfadeBlend {
    HistogramPreserving,  // Heitz & Neyret 2018: blend Gaussianised values with variance-preserving weights
    Linear,               // the classic blend; washes out contrast in the band (for comparison)
};

// Offset-and-blend: the map blended with itself shifted by half a tile, the shifted copy near the tile
// edges (where it is continuous) and the original in the middle, over a band of `width` of the tile
// (0 < width <= 0.5) with a smoothstep ramp.
Image crossfadeTile(const Image& map, double width, CrossfadeBlend blend = CrossfadeBlend::HistogramPreserving);

// The weight of the original map at texel (x, y) in crossfadeTile: 0 at the tile edges, 1 beyond the band.
double crossfadeWeight(int x, int y, int width, int height, double band);

// Mirror tiling: the map, its mirror image in x, in y and in both, as a 2W x 2H map. Heights meet at every
// edge; slopes flip sign at the mirror lines (check reports those kinks).
Image mirrorTile(const Image& map);

// ---- Packed textures ----

struct PackingCheck {
    bool consistent = true;
    double maxError = 0.0;  // largest |G - R shifted| etc. over all levels
    int firstBadLevel = -1;
};

// Verifies that every level of a 4-neighbour packed chain has G, B, A equal to R shifted by one texel in
// x, y and both, with the wrap mode.
PackingCheck checkPacking(const std::vector<Image>& packedLevels, Wrap wrap);

// ---- Showing it ----

// The map tiled 2x2 (its tile edges meet in the cross through the middle), grey from its min to max,
// scaled by a power of two so the longer side is 512 to 1024 pixels, with each failing seam drawn
// half-transparent over the cross: red where heights jump, orange where only slopes break. RGB in [0,1].
Image seamPreview(const Image& level0, const LevelSeams& seams, double threshold = kDefaultSeamThreshold);

}  // namespace heightpack
