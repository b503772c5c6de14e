// Ocean height maps synthesised from a wave spectrum (Tessendorf, "Simulating Ocean Water", 2001):
// periodic over the tile by construction, and looping in time when the frequencies are quantised.
#pragma once

#include <complex>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "heightpack/core/sea/dispersion.hpp"
#include "heightpack/core/image.hpp"
#include "heightpack/core/sea/spreading.hpp"

namespace heightpack {

enum class SpectrumModel {
    Phillips,          // (alpha/2) k^-3, cut below the largest wind wave exp(-1/(k Lw)^2) and above exp(-k^2 l^2)
    Jonswap,           // fetch-limited: Hasselmann et al. 1973, peak enhancement gamma
    PiersonMoskowitz,  // fully developed: Pierson & Moskowitz 1964, wind at 19.5 m taken as 1.026 U10
};
template <>
struct NameTable<SpectrumModel> {
    static constexpr EnumName<SpectrumModel> entries[] = {
        {SpectrumModel::Phillips, "phillips", "Phillips spectrum"},
        {SpectrumModel::Jonswap, "jonswap", "fetch-limited JONSWAP spectrum"},
        {SpectrumModel::PiersonMoskowitz, "pierson-moskowitz", "fully developed Pierson-Moskowitz spectrum"},
    };
};
inline const char* spectrumModelName(SpectrumModel model) { return nameOf(model); }

// A swell: waves raised far away, summed with the local wind sea. A JONSWAP shape in the Hs-Tp form
// (Goda 1988; DNV-RP-C205 3.5.5), scaled so that 4 sqrt(m0) is exactly significantHeight, with a narrow
// cos-2s spreading around `direction`.
struct SwellOptions {
    double significantHeight = 0.0;  // m; 0 = no swell
    double peakPeriod = 12.0;        // s
    double direction = 0.0;          // degrees, as the wind's: the way the swell travels
    double gamma = 5.0;              // peak enhancement: a swell is narrower in frequency than a wind sea
    double spreadingExponent = 75.0; // cos-2s s: Goda's s_max for swell that has come a long way
};

struct SpectrumOptions {
    SpectrumModel model = SpectrumModel::Jonswap;
    double windSpeed = 10.0;         // m/s, at 10 m
    double windDirection = 0.0;      // degrees, from +x (columns) toward +y (rows)
    double fetch = 100000.0;         // m (JONSWAP)
    double gamma = 3.3;              // JONSWAP peak enhancement
    double phillipsAlpha = 0.0081;   // Phillips' constant
    double smallWaveLength = 0.0;    // Phillips suppression length l (m); 0 = Lw / 1000
    Spreading spreading = Spreading::Cos2;  // the wind sea's directional spreading
    double spreadingExponent = 0.0;  // cos-2s s for the wind sea; 0 = Mitsuyasu's s(w)
    double depth = 0.0;              // m; 0 = deep. Else w^2 = g k tanh(k d), and TMA for JONSWAP and PM
    SwellOptions swell;
    double tileSize = 256.0;         // m across the (square) tile
    int size = 256;                  // texels across; a power of two
    uint64_t seed = 1;
    double loopPeriod = 0.0;         // s; when positive, frequencies are multiples of 2 pi / loopPeriod
    // The wavenumber band the grid keeps (rad/m): modes with bandLow <= |k| < bandHigh; bandHigh 0 = no
    // upper limit. Cascades split a spectrum into tiles of disjoint bands this way.
    double bandLow = 0.0, bandHigh = 0.0;
};

// The sea's spectrum, its parameters worked out once (peak frequency, the swell's normalisation), for
// evaluating at many wave vectors.
class SeaSpectrum {
public:
    explicit SeaSpectrum(const SpectrumOptions& options);
    // The wind sea's frequency spectrum E(w) in m^2 s (deep-water form, then times the TMA factor at the
    // depth); 0 for Phillips, which is defined over wavenumber.
    double windFrequencySpectrum(double omega) const;
    // The swell's frequency spectrum in m^2 s; 0 without a swell.
    double swellFrequencySpectrum(double omega) const;
    // The omnidirectional wavenumber spectrum S(k) in m^3 (wind sea plus swell): the height variance is
    // its integral over k > 0. A frequency spectrum moves to k through the dispersion at the depth.
    double omnidirectional(double k) const;
    // The directional spectrum over the wave-vector plane in m^4: each component's S(k) / k times its
    // spreading around its own direction.
    double directional(double kx, double ky) const;
    // The same with k = |(kx, ky)| given: a grid that has it already (from sqrt, which cannot overflow
    // there and is several times cheaper than hypot) saves taking it again.
    double directional(double kx, double ky, double k) const;
    // The wind sea's peak angular frequency (rad/s) as its model defines it.
    double windPeakOmega() const { return windPeak_; }
    const SpectrumOptions& options() const { return options_; }

private:
    double windDeepWater(double omega) const;        // JONSWAP or PM before the depth factor, m^2 s
    double windWavenumberSpectrum(double k) const;   // m^3
    double swellWavenumberSpectrum(double k) const;  // m^3
    SpectrumOptions options_;
    double windX_ = 1.0, windY_ = 0.0;  // the wind's unit vector
    double lnGamma_ = 0.0, lnSwellGamma_ = 0.0;
    double windPeak_ = 0.0, jonswapAlpha_ = 0.0;
    double swellPeak_ = 0.0, swellScale_ = 0.0;
};

// The omnidirectional wavenumber spectrum S(k) in m^3 (SeaSpectrum::omnidirectional).
double omnidirectionalSpectrum(const SpectrumOptions& options, double k);

// The directional spectrum in m^4 (SeaSpectrum::directional); with the default cos2 spreading, S(k) / k
// times (2 / pi) cos^2(theta - wind) for waves travelling with the wind, zero against it.
double directionalSpectrum(const SpectrumOptions& options, double kx, double ky);

// The integral of S(k) over all k > 0 (numerically): the variance of an unbounded sea.
double spectrumVariance(const SpectrumOptions& options);
// The integral of S(k) over lo <= k < hi (numerically).
double spectrumVariance(const SpectrumOptions& options, double lo, double hi);

// The peak angular frequency (rad/s) of the whole sea (wind sea plus swell), found on a fine grid of the
// frequency spectrum S(k) dk/dw.
double spectrumPeakOmega(const SpectrumOptions& options);

// The integral of JONSWAP's peak enhancement over the Pierson-Moskowitz shape, relative to that shape
// alone: the factor that scales a JONSWAP of given Hs and Tp back to that Hs (about 1 / (1 - 0.287 ln gamma)).
double jonswapEnhancementIntegral(double gamma);

// The dispersion (depth-aware), quantised down to a multiple of 2 pi / loopPeriod when looping.
double angularFrequency(const SpectrumOptions& options, double k);

// The fields one instant of the sea gives; which of them Ocean::fields computes.
struct SeaFieldSet {
    bool heights = true;
    bool shift = false;  // Dx, Dy per unit of choppiness
    bool jacobian = false;      // J of the horizontal map x -> x + choppiness D
};
struct SeaFields {
    Image heights;       // m, one channel
    Image shift;  // m per unit of choppiness, two channels (x, y)
    Image jacobian;      // one channel: (1 + c Dxx)(1 + c Dyy) - c^2 Dxy^2, derivatives taken spectrally
};

// Where Ocean::fieldsInto writes one field: texel (x, y) at first[(y * size + x) * stride]; null = not wanted.
struct SeaFieldTarget {
    float* first = nullptr;
    int stride = 1;  // floats from one texel to the next: 1 in a plane, the channel count in an interleaved image
};
struct SeaFieldTargets {
    SeaFieldTarget heights, shiftX, shiftY, jacobian;
};

struct OceanOptions {
    int threads = 1;      // threads for drawing up the amplitudes (0 = all cores); the sea is the same for any count
    bool evolves = true;  // false: only t = 0 is ever asked (a single frame), and half the amplitudes' memory is kept
};

// A synthesised sea: Gaussian random amplitudes drawn from the seed (a counter-based generator: each wave
// vector's draw depends on the seed and its index alone, so a seed reproduces the map on any thread count),
// evolved to any time.
class Ocean {
public:
    explicit Ocean(const SpectrumOptions& options, int threads = 1) : Ocean(options, OceanOptions{threads}) {}
    Ocean(const SpectrumOptions& options, const OceanOptions& how);
    // Heights in metres at time t (seconds), size x size; real by construction (Hermitian spectrum).
    Image heights(double t) const;
    // Tessendorf's shift (choppiness) at time t: two channels, x and y, in metres per
    // unit of choppiness, D(k) = i k / |k| h(k): an engine moves each vertex by lambda * D, and a crest
    // draws its neighbours in (a Gerstner wave's sharpening) for positive lambda.
    Image shift(double t) const;
    // Several fields at once, sharing the evolved spectrum; `threads` splits the work (0 = all cores), the
    // result is the same for any count.
    SeaFields fields(double t, const SeaFieldSet& which, double choppiness = 1.0, int threads = 1) const;
    // The same fields written straight into the caller's storage (an interleaved image's channels, say),
    // so no plane of each is held twice. t must be 0 unless the ocean evolves. The targets must not overlap:
    // the heights' storage holds the transforms' work until the heights, computed last, are written there.
    void fieldsInto(double t, const SeaFieldTargets& targets, double choppiness = 1.0, int threads = 1) const;
    // The variance the grid carries on average: the spectrum summed over the resolved wave vectors.
    double resolvedVariance() const { return resolvedVariance_; }
    // A bound on |D| at any point and time, per unit of choppiness: the sum over modes of |h(k, t)|,
    // which is at most |h0(k)| + |h0(-k)| however the phases turn.
    double shiftBound() const { return shiftBound_; }
    const SpectrumOptions& options() const { return options_; }

private:
    SpectrumOptions options_;
    // Over the half kx = 0 .. size/2 of the DFT grid (size/2 + 1 a row; the rest follows by symmetry):
    // h(k, 0) = h0(k) + conj(h0(-k)), and its partner h0(k) - conj(h0(-k)) (only when the sea evolves), so
    // that h(k, t) = cos(w t) h(k, 0) - i sin(w t) partner.
    std::vector<std::complex<float>> initial_, partner_;
    double resolvedVariance_ = 0.0;
    double shiftBound_ = 0.0;
};

}  // namespace heightpack
