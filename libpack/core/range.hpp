// Internal: keeping a changed map within the range of the map it was made from.
#pragma once

#include "heightpack/core/image.hpp"

namespace heightpack::detail {

// A map less a smooth field (or healed by one) can pass the source's own extremes, and a crop that spans
// [0,1] then no longer fits an integer file. Where it does, the values within 2% of the source's range
// of an extreme and beyond are eased into that 2% (tanh: monotone, continuous); the rest, the whole middle
// of the range, is untouched. Nothing changes when out stays within source's range. On `threads` threads
// (0 = all cores), with the same result on any number.
void easeIntoRange(Image& out, SampleRange source, int threads);

}  // namespace heightpack::detail
