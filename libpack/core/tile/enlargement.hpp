// Internal: recognising a map that is an enlargement of a smaller one (a painting made at 512 and resized
// to 2048 before packing), so the band re-synthesis (tile/resynthesis.cpp) can work at the map's own
// resolution and enlarge its result the same way: the new bands then have the smoothness of the map
// around them, where a Gaussian model of the enlarged map shows grain or a frame of other texture.
#pragma once

#include "heightpack/core/image.hpp"

namespace heightpack::detail {

// The interpolation kernels of common resizers (OpenImageIO, ImageMagick, GIMP, Photoshop), in source
// texels: a texel's centre at (x + 0.5) / factor - 0.5 in the source, the taps' weights normalised.
// BlackmanHarris is OpenImageIO's default for enlarging (3 source texels wide).
enum class Kernel { Nearest, Linear, CatmullRom, BlackmanHarris, Lanczos3 };

struct Enlargement {
    int factor = 1;  // 1: the map is not (recognisably) an enlargement
    Kernel kernel = Kernel::Nearest;
};

// Maps smaller than this a side are not taken for enlargements.
inline constexpr int kLeastEnlargedSide = 1024;
// Nor is any map taken for an enlargement of a source smaller than this a side.
inline constexpr int kLeastSourceSide = 64;

// How far, in source texels, enlargedTile's new content reaches beyond the source tile's (the widest
// kernel's radius, and one to spare).
inline constexpr int kEnlargedTileReach = 4;

// The largest factor (16, 8, 4 or 2, dividing both sides, leaving at least kLeastSourceSide texels a side)
// and the kernel with which map is an enlargement of some smaller map to within its quantisation (quantum:
// the map's height step, 0 for float): the least-squares fit of a source, enlarged again, leaves no more
// than the rounding's noise and a small part of the map's finest detail. Judged on a central window of at
// most 512 x 512 texels. isSource: map is the source found for an enlargement, examined whatever its size
// (a painting made at 64, enlarged 8x and then the whole 4x, is tiled at 64: a model of the 512 map puts
// grain along the wrap lines).
Enlargement findEnlargement(const Image& map, double quantum, int threads, bool isSource = false);

// The least-squares source of map under e (edges clamped, as resizers do): w / factor x h / factor.
Image fitSource(const Image& map, Enlargement e, int threads);

// source enlarged by e; periodic: the source wraps (a tile), else its edges are clamped.
Image enlarge(const Image& source, Enlargement e, bool periodic, int threads);

// The tile of map (an enlargement of source under e) made from sourceTiled, a tile of source whose new
// content reaches reachX source texels from its left/right wrap line and reachY from its top/bottom one:
// within them, widened by the kernel's reach, sourceTiled enlarged as a tile; beyond them, the map plus
// the source's change (a smooth field there) enlarged. The two differ by what source misses of the map
// (its rounding), so the seam between them shows nothing. Eased into range (the map's).
Image enlargedTile(const Image& map, const Image& source, const Image& sourceTiled, Enlargement e, int reachX, int reachY,
                   SampleRange range, int threads);

// image's values on levels of quantum (0: as they are) and within range. A source's tile goes to the source's
// levels before it is enlarged: the map was made from a source so stored, whose rounding it shows smoothed
// (a band made of values between the levels would lack that fine detail: a frame).
void putOnLevels(Image& image, double quantum, SampleRange range);

// map's source under e (fitSource) within range, on its own levels: 8-bit ones where nearly every value
// of the fit lies on them (a painting made in 8 bits, enlarged and stored in 16 bits or float), else map's
// (quantum; 0 for float). quantum becomes the source's.
Image roundedSource(const Image& map, Enlargement e, double& quantum, SampleRange range, int threads);

}  // namespace heightpack::detail
