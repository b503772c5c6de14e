// Internal: the smoothing the band re-synthesis (tile/resynthesis.cpp) needs before it models a map: a
// mirrored Gaussian blur of a field, and a map's quantisation undone.
#pragma once

#include <vector>

#include "heightpack/core/image.hpp"

#include "field.hpp"

namespace heightpack::detail {

// A Gaussian blur of sigma texels by three box passes each way (O(1) per texel whatever sigma), the field
// mirrored at its edges. f is blurred in place; scratch (f's size) holds every other pass. Rows and column
// blocks run on `threads` threads; each running sum adds in one fixed order, so the thread count changes
// no bit.
void blur(Field& f, Field& scratch, double sigma, int threads);

// Whether a quantised map shows its levels as terraces: one in 20 pairs of neighbours or more are equal.
// Otherwise its texel-to-texel steps span several levels (about 8 or more for a Gaussian field), and undoing
// the rounding would move each texel by less than half a level, a change its own detail drowns.
bool hasTerraces(const Image& map, int threads);

// A smooth map that rounds back to map (whose levels are `quantum` apart): the plateaus of a quantised
// gradient become the ramp they were rounded from; no texel leaves its rounding interval.
std::vector<float> dequantised(const Image& map, double quantum, int threads);

// Moisan's smooth field of the heights (w x h, row-major) blurred at sigma texels, each side of a wrap line
// blurred apart (mirrored): the large-scale part of the map's edge jumps. The field is harmonic inside the
// tile and its boundary values vary on the scale of sigma, so it is made on a grid `step` times coarser
// (the largest power of two that divides the tile, is at most sigma / 8 and leaves 64 cells a side), from
// the means of step x step cells, and interpolated back linearly, clamped at the tile's edges.
std::vector<float> largeScaleField(const std::vector<float>& values, int w, int h, double sigma, int threads);

}  // namespace heightpack::detail
