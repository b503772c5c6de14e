// The numbers an engineer checks a synthesised sea by: wave height from the heights and from the
// spectrum, peak period and wavelength, steepness, folds, and how far the shift can move a vertex.
#pragma once

#include "heightpack/core/image.hpp"
#include "heightpack/core/sea/spectrum.hpp"

namespace heightpack {

// What the spectrum says, whatever the seed.
struct SeaStateSummary {
    double significantWaveHeight = 0.0;  // m: 4 sqrt(m0), m0 the variance the grid resolves
    double peakPeriod = 0.0;             // s: 2 pi / the peak of the whole sea's frequency spectrum
    double peakWavelength = 0.0;         // m: 2 pi / k at that peak, through the dispersion at the depth
    // Hs / peak wavelength: DNV-RP-C205's significant steepness S_p = 2 pi Hs / (g Tp^2) in deep water,
    // with the finite-depth wavelength when there is a depth. A breaking sea is near 1/7.
    double steepness = 0.0;
};

// The summary for a sea whose grid resolves `resolvedVariance` (Ocean::resolvedVariance) of the spectrum.
SeaStateSummary summariseSeaState(const SpectrumOptions& options, double resolvedVariance);

// Where a frame's channels are: the heights, Dx (Dy in the next channel), the Jacobian; -1 = absent.
struct FrameChannels {
    int heights = 0, shift = -1, jacobian = -1;
};
// The numbers a report takes from one frame; 0 for what its channels do not hold.
struct FrameNumbers {
    double significantWaveHeight = 0.0;  // 4 x the standard deviation of the heights
    float minHeight = 0.0f, maxHeight = 0.0f;
    double foldFraction = 0.0;         // of texels whose Jacobian is negative: the surface folds there
    double largestShift = 0.0;  // the largest |choppiness * (Dx, Dy)| of any texel
};
// All of them in two passes over the frame, over rows on `threads` threads (0 = all cores), combined in
// row order: the same numbers whatever the count.
FrameNumbers frameNumbers(const Image& frame, const FrameChannels& channels, double choppiness = 1.0, int threads = 1);

// One number of one channel (0 in a one-channel map), as frameNumbers gives it.
// 4 x the standard deviation of the map's texels: the realised significant wave height.
double significantWaveHeight(const Image& heights, int channel = 0, int threads = 1);
// The fraction of texels whose Jacobian is negative: where the choppy surface folds over itself.
double foldFraction(const Image& jacobian, int channel = 0, int threads = 1);
// The longest horizontal move any texel makes: the largest |choppiness * (Dx, Dy)|, Dx in `channel` and
// Dy in the next.
double largestShift(const Image& shift, double choppiness, int channel = 0, int threads = 1);

}  // namespace heightpack
