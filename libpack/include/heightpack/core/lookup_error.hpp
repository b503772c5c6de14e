// What storing a chain in a smaller pixel type (half floats, 16-bit codes) costs in precision, measured
// where it matters: at the bilinear lookups a shader makes, against the same lookups of the float chain.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "heightpack/core/image.hpp"

namespace heightpack {

// What reading back a stored texel gives for the float value v: v itself for 32-bit float, the nearest
// half, or the value of the nearest 16-bit code. Must be a pure function of v.
using TexelRounding = std::function<float(float v)>;
// The same for n values at once, values[i] to readBack[i]: one call a row instead of one a value.
using TexelRowRounding = std::function<void(const float* values, size_t n, float* readBack)>;

// For each level of chain (level 0 first), the worst absolute difference between a bilinear lookup from
// the texels as stored (every value through `stored`) and the same lookup from the float texels, over
// every channel, anywhere in the level, in either wrap mode. The lookup is samplePackedBilinear's (the
// packed vertex-shader fetch, equal to hardware filtering of the plain level): a packed texel holds four
// copies of plain values, so its stored channels are stored(H) of the same neighbours and one function
// serves packed and plain chains alike. A lookup is a weighted mean of four texels (weights >= 0 that sum
// to 1), so the difference of the two lookups is the same mean of the texels' differences: never more
// than the largest of them, which the lookup at that texel's centre gives. The worst is therefore the
// worst texel's |stored(v) - v|, taken in double precision (it equals, bit for bit, the worst over a grid
// of every texel centre and every midpoint between neighbours evaluated in double: weights 1/2 and 1/4
// are exact and rounding is monotone). Values are in the chain's units; a non-finite difference counts as
// infinity. threads: 0 = all cores; the result does not depend on it.
std::vector<double> worstLookupError(const std::vector<Image>& chain, const TexelRowRounding& stored, int threads = 0);
std::vector<double> worstLookupError(const std::vector<Image>& chain, const TexelRounding& stored, int threads = 0);

// For each level of a normal map's chain, the worst angle in degrees between a texel's normal as stored
// (every value through `stored`) and as given: two channels are x and y with z rebuilt as the shader does
// (normalFromXy), three or more x, y, z (normalised; a fourth channel, height or variance, is not a
// direction). Per texel, not per lookup: a shader renormalises what it filters, so no bilinear mix is
// bounded by its corners' angles as a value is. A non-finite value counts as 180 degrees. threads: 0 = all
// cores; the result does not depend on it.
std::vector<double> worstAngleErrorDegrees(const std::vector<Image>& chain, const TexelRowRounding& stored, int threads = 0);

}  // namespace heightpack
