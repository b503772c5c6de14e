// Internal: the stationary Gaussian model of a Gaussianised map that the band re-synthesis
// (tile/resynthesis.cpp) conditions: its power spectrum and covariances, from one forward DFT of the map,
// and unconditional samples, one inverse DFT each.
#pragma once

#include <opencv2/core.hpp>

#include <complex>
#include <cstdint>
#include <vector>

#include "heightpack/core/image.hpp"

#include "field.hpp"
#include "strip_field.hpp"

namespace heightpack::detail {

// Which wrap line a band crosses: X, the left/right one (the band's lines are columns); Y, the top/bottom one.
enum class Axis { X, Y };

// The model of a Gaussianised map g: the spectrum of its periodic component (Moisan's: no cross of edge
// jumps in it) less the quantisation's white floor, and the covariances along the axes.
struct GaussianModel {
    int w, h;
    // CV_64F, h x (w / 2 + 1): |P(k)|^2 less the floor, P the periodic component's DFT, for the half
    // kx <= w/2 (the power of a real field is even: the rest is powerAt's mirror of it).
    cv::Mat power;
    std::vector<double> lagX, lagY;  // the circular autocovariance C(d, 0) and C(0, d)
    GaussianModel(int width, int height) : w(width), h(height), power(height, width / 2 + 1, CV_64F), lagX(width), lagY(height) {}
    double variance() const { return lagX[0]; }
    // The power at (kx, ky) = (q, r), for any q < w.
    double powerAt(int q, int r) const { return q < power.cols ? power.at<double>(r, q) : power.at<double>((h - r) % h, w - q); }
};

// The spectrum of Moisan's periodic component of map's first channel, as forwardRealDftToHalf gives it (the
// half kx <= w/2, in floats, unscaled), the mean set to 0: the map's own less its edge jumps' smooth field's.
std::vector<std::complex<float>> periodicHalfSpectrum(const Image& map, int threads);

// noise: the variance of the input's quantisation, in the Gaussian domain: white noise that the map holds
// as terraces and a sample would show as grain. Its level is taken off the power spectrum, so the model is
// of the field the quantised map samples, and the kriging treats it as measurement noise (a nugget).
GaussianModel modelOf(const Field& g, double noise, int threads);

// A field with the model's covariance (asymptotic discrete spot noise: sqrt(power) times complex white
// noise), drawn per frequency from (seed, index) alone: the same on any number of threads. Only its strips
// within reachX columns and reachY rows of the wrap lines are kept.
StripField sampleOf(const GaussianModel& model, uint64_t seed, int reachX, int reachY, int threads);

// The covariance between lines du apart (du < strip), per frequency k along them (k up to half their
// length), as a (length / 2 + 1) x strip CV_64FC2 matrix: covHat(k, du) = the sum along the lines of
// C(du, v) e^(-2 pi i k v / length).
cv::Mat lineCovarianceSpectra(const GaussianModel& model, Axis axis, int strip, int threads);

// Moisan's smooth field of the jumps across f's top/bottom wrap line alone: periodic in both directions,
// harmonic but at that line, where it carries the jump. Taking it off makes f wrap top to bottom without
// touching the left/right wrap line, as the left/right band's Fourier treatment along y needs. Only its
// columns within reachX of the left/right wrap line are kept.
StripField topBottomSmoothField(const Field& f, int reachX, int threads);

}  // namespace heightpack::detail
