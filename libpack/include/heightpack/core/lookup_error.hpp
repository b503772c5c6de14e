// What storing a chain in a smaller pixel type (half floats, 16-bit codes) costs in precision, measured
// where it matters: at the bilinear lookups a shader makes, against the same lookups of the float chain.
#pragma once

#include <functional>
#include <vector>

#include "heightpack/core/image.hpp"

namespace heightpack {

// What reading back a stored texel gives for the float value v: v itself for 32-bit float, the nearest
// half, or the value of the nearest 16-bit code. Must be a pure function of v.
using TexelRounding = std::function<float(float v)>;

// For each level of chain (level 0 first), the worst absolute difference between a bilinear lookup from
// the texels as stored (every value through `stored`) and the same lookup from the float texels, over
// every channel and a 2x oversampled grid: every texel centre and every midpoint between neighbouring
// texels (along x, along y and diagonally), neighbours found with wrap, clamp keeping the lookup inside
// the level as samplePackedBilinear does. The lookup is samplePackedBilinear's (the packed vertex-shader
// fetch, equal to hardware filtering of the plain level): a packed texel holds four copies of plain
// values, so its stored channels are stored(H) of the same neighbours and one function serves packed and
// plain chains alike. Both lookups are taken in double precision, so the difference is the storing's
// alone. (A lookup is linear in its four texels, so no point of a cell strays further than its worst
// corner: the grid's centres already find the worst; the midpoints guard the claim.)
// Values are in the chain's units. threads: 0 = all cores; the result does not depend on it.
std::vector<double> worstLookupError(const std::vector<Image>& chain, Wrap wrap, const TexelRounding& stored,
                                     int threads = 0);

}  // namespace heightpack
