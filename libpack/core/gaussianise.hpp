// Internal: the rank Gaussianisation of Heitz & Neyret (2018), shared by the crossfade and the band
// re-synthesis of tile_fix.cpp and tile_resynthesis.cpp.
#pragma once

#include <cstdint>
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
    std::vector<uint32_t> order;   // order[k]: the index of the k-th smallest value
    std::vector<double> gaussian;  // per value of the input, its Gaussian

    Gaussianiser(const std::vector<float>& values, int threads);
    // Ties of values (quantised input: an 8-bit painting has plateaus) broken by `order`, e.g. a smoothed
    // copy of the map, so a smooth field stays smooth in the Gaussian domain instead of becoming steps.
    Gaussianiser(const std::vector<float>& values, const std::vector<float>& order, int threads);
    // The value whose rank's quantile is g, interpolated between neighbouring sorted values.
    float back(double g) const { return backThrough(sorted, g); }
    // The same through another increasing list of as many values.
    static float backThrough(const std::vector<float>& increasing, double g);
};

}  // namespace heightpack::detail
