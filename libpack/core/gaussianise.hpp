// Internal: the rank Gaussianisation of Heitz & Neyret (2018), shared by the crossfade and the band
// re-synthesis of tile_fix.cpp and tile_resynthesis.cpp.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "buffer.hpp"

namespace heightpack::detail {

// The permutation that sorts values (finite, fewer than 2^32) by value, equal values in index order; on
// `threads` threads (0 = all cores), with one result whatever their number.
std::vector<uint32_t> stableOrder(std::span<const float> values, int threads);
// The same sort as (key << 32 | index) items, the key a value's bits in an order that sorts as the float
// does (-0 as +0).
Buffer<uint64_t> sortedItems(std::span<const float> values, int threads);

// The standard normal CDF and its inverse (Acklam's approximation refined by a Halley step, ~1e-15).
double normalCdf(double x);
double inverseNormalCdf(double p);

// Each value to the standard normal quantile of its (mid-)rank, so equal values map to equal Gaussians;
// and back through the sorted values. The quantiles are computed on `threads` threads (0 = all cores),
// with the same result on any number.
struct Gaussianiser {
    Buffer<float> sorted;     // the values in increasing order (-0 as +0)
    Buffer<double> gaussian;  // per value of the input, its Gaussian

    Gaussianiser(std::span<const float> values, int threads);
    // The value whose rank's quantile is g, interpolated between neighbouring sorted values.
    float back(double g) const;
    // back of count Gaussians at once (the same values), faster where they are many.
    void back(const double* g, float* out, size_t count) const;
};

}  // namespace heightpack::detail
