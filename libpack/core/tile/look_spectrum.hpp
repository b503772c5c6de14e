// Internal: the spectra the tile look's statistics (tile/look.cpp) are taken from: a map's half spectrum,
// band passes of it as differences of Gaussians, and the row and column means of a band pass's energy.
#pragma once

#include <complex>
#include <vector>

#include "heightpack/core/image.hpp"

#include "field.hpp"

namespace heightpack::detail {

// The half spectrum of a map (kx = 0 .. w/2) in floats: the statistics need no more, and a real field's
// transforms in floats cost a quarter of complex ones in double.
struct HalfSpectrum {
    int w, h, columns;
    std::vector<std::complex<float>> values;
    std::complex<float> at(int q, int r) const { return values[size_t(r) * columns + q]; }
};

// The half spectrum of map's first channel (unscaled, as forwardRealDftToHalf gives it).
HalfSpectrum spectrumOf(const Image& map, int threads);
// The real field of a half spectrum (overwritten), scaled by 1/(w h) as the inverse of spectrumOf.
Field fieldOf(HalfSpectrum& half, int threads);

// The spectrum of the map filtered periodically with a difference of Gaussians of sigmas fine < coarse
// (texels): a band pass. With folds (foldX, foldY) other than 1, the spectrum of that band pass sampled
// every foldX-th column and foldY-th row (w / foldX x h / foldY, which the folds must divide).
HalfSpectrum bandPassSpectrum(const HalfSpectrum& spectrum, double fine, double coarse, int threads, int foldX = 1, int foldY = 1);
// That band pass (no folds) as a field.
Field bandPassed(const HalfSpectrum& spectrum, double fine, double coarse, int threads);

// The means of a field's columns and of its rows.
struct Profiles {
    std::vector<double> columns, rows;
};
// The profiles of the square of bandPassed(spectrum, fine, coarse), without storing it. On `threads`
// threads (0 = all cores), with the same result on any number.
Profiles energyProfiles(const HalfSpectrum& spectrum, double fine, double coarse, int threads);

}  // namespace heightpack::detail
