// Internal: the smoothing the band re-synthesis (tile_resynthesis.cpp) needs before it models a map: a
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

// A smooth map that rounds back to map (whose levels are `quantum` apart): the plateaus of a quantised
// gradient become the ramp they were rounded from; no texel leaves its rounding interval.
std::vector<float> dequantised(const Image& map, double quantum, int threads);

}  // namespace heightpack::detail
