// Does a map tile? Seam scores per edge pair and mip level, and three ways to make a map tile.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "heightpack/core/image.hpp"

namespace heightpack {

// How the tile edge compares with every other place the tile could have been cut, along one direction.
// For each gap between neighbouring texels (the tile edge is the gap between the last texel and the
// first) three difference operators are averaged over the lines across: the height step, a third
// difference (a jump that stands out of a smooth slope) and the change of slope. Each gap is compared
// with what the gaps just beside it predict (so a steep or busy place predicts large differences), and
// the tile edge's excess is divided by the spread of the same excess over every other gap (median
// absolute deviation). A score is that ratio: about 0 where the tile edge is like any other cut, a few
// units by chance, and large at a seam. When the map has an 8x8 block grid (JPEG), each phase of the
// grid is first divided by its own typical level, so the tile edge, itself a grid line, meets its peers.
struct SeamScore {
    double value = 0.0;  // heights jump: the larger of the step and the third-difference scores
    double slope = 0.0;  // slopes break: the change-of-slope score
    bool measured = false;  // false below 32 texels along the direction or 8 lines across: too few to judge
};

struct LevelSeams {
    int width = 0;
    int height = 0;
    SeamScore leftRight;  // the left and right edges meeting (differences along x)
    SeamScore topBottom;  // the top and bottom edges meeting (differences along y)
};

// The default verdict threshold. Measured with tests/bench/heightpack_seam_rates --count 1000 (formats
// cycling over 8/16-bit PNG, float EXR, JPEG 75/90; spectra k^-1.5 to k^-4; 64 to 1024 texels): exactly
// periodic maps score at most 5.7 (p99 3.9); parabola kinks of 6 mean bends at least 11.9, ramps of 3
// mean steps 4.6 and more (p1 7.5), crops of larger fields 2.4 and more (p1 4.7, the weak ones from very
// rough fields). The real tiling textures of tests/corpus score at most 6.4.
inline constexpr double kDefaultSeamThreshold = 6.5;

// What the measure needs to know beyond the level's texels.
struct SeamOptions {
    int level = 0;          // the level's index in its mip chain: an 8x8 block grid of level 0 is 8 >> level
    double quantum = 0.0;   // the source's height step (1/255 for 8 bits, 0 for float): differences of
                            // rounding alone are no evidence of a seam
    int threads = 0;        // 0 = all cores; scores do not depend on it
};

// Scores of one level (channel 0).
LevelSeams measureSeams(const Image& level, const SeamOptions& options = {});

// Whether a measured score passes the threshold (both value and slope must).
bool seamPasses(const SeamScore& score, double threshold = kDefaultSeamThreshold);
bool levelTiles(const LevelSeams& seams, double threshold = kDefaultSeamThreshold);

enum class SeamEdge { LeftRight, TopBottom };
enum class SeamKind { Jump, Kink };
const char* seamEdgeName(SeamEdge edge);  // "left/right", "top/bottom"

// The first failing edge of a chain, finest level first.
struct SeamFailure {
    int level = 0;
    int width = 0;
    int height = 0;
    SeamEdge edge = SeamEdge::LeftRight;
    SeamKind kind = SeamKind::Jump;
    double score = 0.0;
};

// The first failing edge over levels, finest first (left/right before top/bottom within a level); only
// the given edge when one is named.
std::optional<SeamFailure> firstSeamFailure(const std::vector<LevelSeams>& levels, double threshold,
                                            std::optional<SeamEdge> edge = std::nullopt);

// Every level of a mip chain measured with one threshold: the verdict `check` gives and `tile` acts on.
struct ChainSeams {
    double threshold = kDefaultSeamThreshold;
    std::vector<LevelSeams> levels;
    std::optional<SeamFailure> failure;  // none when every measured level passes
    bool tiles() const { return !failure.has_value(); }
};
// options.level is set per level.
ChainSeams measureChainSeams(const std::vector<Image>& chain, double threshold = kDefaultSeamThreshold,
                             SeamOptions options = {});
// The same for the chain of level0 and the levels below it (generateMipLevelsBelow's).
ChainSeams measureChainSeams(const Image& level0, const std::vector<Image>& below, double threshold, SeamOptions options);

// "left/right edges at level 2 (32x32): heights jump, score 12.3 (threshold 7.5)".
std::string describeSeamFailure(const SeamFailure& failure, double threshold);
// A score with as many decimals as it takes to compare with threshold as the number does ("7.51", not
// "7.5", against 7.5); "inf" for an infinite score (an edge that differs where the interior has no
// variation at all).
std::string seamScoreText(double score, double threshold = kDefaultSeamThreshold);

// ---- Making a map tile ----

// Which discontinuities the periodic component removes.
enum class PeriodicContinuity {
    Heights,           // Moisan 2011 exactly: heights meet at the edges; slopes may still kink there
    HeightsAndSlopes,  // Moisan, then the slope change left at each edge bent away near the edge
};

// Moisan's periodic + smooth decomposition ("Periodic plus smooth image decomposition", J. Math.
// Imaging Vis. 2011): returns the periodic component u - s, where s is the smooth (harmonic inside the
// tile) field whose periodic Laplacian equals the jumps of u across the tile edges. It changes the map
// by a field bounded by those jumps and keeps its mean. With HeightsAndSlopes (the default) the change
// of slope that remains at each edge, smoothed along the edge, is then bent away within an eighth of the
// tile beside it, so lighting sees no line there either; the middle of the tile keeps its detail, and
// nothing grows with the tile's size (a global field matching slopes would bend the tile into a dome
// whenever the edge slopes differ on average). Any size.
Image periodicComponent(const Image& map, PeriodicContinuity continuity = PeriodicContinuity::HeightsAndSlopes);

enum class CrossfadeBlend {
    HistogramPreserving,  // Heitz & Neyret 2018 in the Gaussianised domain, four copies, the low-pass blended
                          // linearly and the high-pass with variance-preserving weights
    Linear,               // the classic blend of two copies; washes out contrast in the band (for comparison)
};

// Offset-and-blend: the map blended with itself shifted by half a tile, the shifted copies near the tile
// edges (where they are continuous) and the original in the middle, over a band of `width` of the tile
// (0 < width <= 0.5) with a smoothstep ramp. Every offset-and-blend shows the map's middle twice in a tile
// (an echo that check reports).
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
