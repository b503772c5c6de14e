// Ocean height maps synthesised from a wave spectrum (Tessendorf, "Simulating Ocean Water", 2001):
// periodic over the tile by construction, and looping in time when the frequencies are quantised.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "heightpack/core/image.hpp"

namespace heightpack {

enum class SpectrumModel {
    Phillips,  // (alpha/2) k^-3, cut below the largest wind wave exp(-1/(k Lw)^2) and above exp(-k^2 l^2)
    Jonswap,   // fetch-limited: Hasselmann et al. 1973, peak enhancement gamma
};
template <>
struct NameTable<SpectrumModel> {
    static constexpr EnumName<SpectrumModel> entries[] = {
        {SpectrumModel::Phillips, "phillips", "Phillips spectrum"},
        {SpectrumModel::Jonswap, "jonswap", "fetch-limited JONSWAP spectrum"},
    };
};
inline const char* spectrumModelName(SpectrumModel model) { return nameOf(model); }
inline std::optional<SpectrumModel> parseSpectrumModel(std::string_view name) { return parseName<SpectrumModel>(name); }

inline constexpr double kGravity = 9.81;

struct SpectrumOptions {
    SpectrumModel model = SpectrumModel::Jonswap;
    double windSpeed = 10.0;         // m/s, at 10 m
    double windDirection = 0.0;      // degrees, from +x (columns) toward +y (rows)
    double fetch = 100000.0;         // m (JONSWAP)
    double gamma = 3.3;              // JONSWAP peak enhancement
    double phillipsAlpha = 0.0081;   // Phillips' constant
    double smallWaveLength = 0.0;    // Phillips suppression length l (m); 0 = Lw / 1000
    double tileSize = 256.0;         // m across the (square) tile
    int size = 256;                  // texels across; a power of two
    uint64_t seed = 1;
    double loopPeriod = 0.0;         // s; when positive, frequencies are multiples of 2 pi / loopPeriod
};

// The omnidirectional wavenumber spectrum S(k) in m^3: the height variance is its integral over k.
double omnidirectionalSpectrum(const SpectrumOptions& options, double k);

// The directional spectrum over the wave-vector plane, in m^4: S(k) / k times the spreading
// (2 / pi) cos^2(theta - wind) for waves travelling with the wind, zero against it.
double directionalSpectrum(const SpectrumOptions& options, double kx, double ky);

// The integral of S(k) over all k > 0 (numerically): the variance of an unbounded sea.
double spectrumVariance(const SpectrumOptions& options);

// Deep-water dispersion w = sqrt(g k), quantised down to a multiple of 2 pi / loopPeriod when looping.
double angularFrequency(const SpectrumOptions& options, double k);

// A synthesised sea: Gaussian random amplitudes drawn once from the seed (a fixed generator and order,
// so a seed reproduces the map), evolved to any time.
class Ocean {
public:
    explicit Ocean(const SpectrumOptions& options);
    // Heights in metres at time t (seconds), size x size; real by construction (Hermitian spectrum).
    Image heights(double t) const;
    // Tessendorf's horizontal displacement (choppiness) at time t: two channels, x and y, in metres per
    // unit of choppiness, D(k) = -i k / |k| h(k). An engine moves each vertex by lambda * D.
    Image displacement(double t) const;
    // The variance the grid carries on average: the spectrum summed over the resolved wave vectors.
    double resolvedVariance() const { return resolvedVariance_; }
    const SpectrumOptions& options() const { return options_; }

private:
    // The spectrum at time t, times `factor(kx, ky)` (a complex multiplier that keeps it Hermitian).
    Image transform(double t, int component) const;
    SpectrumOptions options_;
    std::vector<double> amplitudeRe_, amplitudeIm_;  // h0(k), row-major over the DFT grid
    std::vector<double> omega_;
    double resolvedVariance_ = 0.0;
};

}  // namespace heightpack
