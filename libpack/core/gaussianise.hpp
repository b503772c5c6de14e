// Internal: the rank Gaussianisation of Heitz & Neyret (2018), shared by the crossfade and the band
// re-synthesis of tile_fix.cpp and tile_resynthesis.cpp.
#pragma once

#include <vector>

namespace heightpack::detail {

// The standard normal CDF and its inverse (Acklam's approximation refined by a Halley step, ~1e-15).
double normalCdf(double x);
double inverseNormalCdf(double p);

// Each value to the standard normal quantile of its (mid-)rank, so equal values map to equal Gaussians;
// and back through the sorted values. The sort runs on `threads` threads (0 = all cores) and gives the
// same result on any number.
struct Gaussianiser {
    std::vector<float> sorted;     // the values in increasing order
    std::vector<double> gaussian;  // per value of the input, its Gaussian

    Gaussianiser(const std::vector<float>& values, int threads);
    // The value whose rank's quantile is g, interpolated between neighbouring sorted values.
    float back(double g) const;
};

}  // namespace heightpack::detail
