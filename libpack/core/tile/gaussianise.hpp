// Internal: the rank Gaussianisation of Heitz & Neyret (2018), shared by the crossfade and the band
// re-synthesis of tile/fix.cpp and tile/resynthesis.cpp.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "buffer.hpp"
#include "value_sort.hpp"

namespace heightpack::detail {

// The standard normal CDF and its inverse (Acklam's approximation refined by a Halley step, ~1e-15).
double normalCdf(double x);
double inverseNormalCdf(double p);

// Each value to the standard normal quantile of its (mid-)rank, so equal values map to equal Gaussians;
// and back, the rank's value interpolated between neighbouring ranks. The quantiles are computed on
// `threads` threads (0 = all cores), with the same result on any number.
// Ranks are exact (a sort) for fewer than 2^20 values, or values crowded into a few parts of their range.
// Otherwise they come from a histogram of kRankBins equal parts of the range, each part's ranks
// interpolated linearly in the value between its lowest and highest (a part whose values are all equal
// takes their mid-rank, as the sort): at least 64 values a part on average and none with more than 64x
// that (a smooth density's peak part holds a few times the mean; more is a cluster finer than a part), so
// a rank is off by a fraction of its part's count at most, and by its sampling noise (about sqrt(count))
// on a smooth distribution: the Gaussians' RMS error is under 1e-4 (Gaussianiser tests). A sort, with its
// scattered writes and 300 MB at 4096^2, would cost a tenth of tile's time.
struct Gaussianiser {
    Buffer<double> gaussian;  // per value of the input, its Gaussian

    Gaussianiser(std::span<const float> values, int threads);
    // The value whose rank's quantile is g.
    float back(double g) const;
    // back of count Gaussians at once (the same values), faster where they are many.
    void back(const double* g, float* out, size_t count) const;
    // Whether the ranks are exact (sorted) rather than interpolated in parts of the range.
    bool exact() const { return binned_.empty(); }

    static constexpr int kRankBins = 1 << 14;

private:
    struct Bin {
        float low = 0, high = 0;  // the part's lowest and highest value
        size_t first = 0;         // the rank of its lowest
        size_t count = 0;
        double gaussian = 0, slope = 0;  // the Gaussian of low, and its change per unit of value
        bool curved = false;             // in the tails: its values sorted, ranks exact
        size_t tailOffset = 0;           // curved: its first value's place in tailValues_
    };
    size_t n_ = 0;
    Buffer<float> sorted_;     // exact: the values in increasing order (-0 as +0)
    std::vector<Bin> binned_;  // binned: the parts, in order of value
    std::vector<int> binOfRank_;  // binned: the part holding rank k n / binOfRank_.size()
    std::vector<float> tailValues_;  // binned: the curved parts' values, sorted
    bool binnedRanks(std::span<const float> values, int threads);
    void sortedRanks(std::span<const float> values, int threads);
    float binnedValue(double rank) const;
};

}  // namespace heightpack::detail
