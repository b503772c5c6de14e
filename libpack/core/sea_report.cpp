#include "heightpack/core/sea_report.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace heightpack {

SeaStateSummary summariseSeaState(const SpectrumOptions& options, double resolvedVariance) {
    SeaStateSummary s;
    s.significantWaveHeight = 4.0 * std::sqrt(std::max(0.0, resolvedVariance));
    const double peak = spectrumPeakOmega(options);
    if (peak > 0.0) {
        s.peakPeriod = 2 * std::numbers::pi / peak;
        s.peakWavelength = 2 * std::numbers::pi / dispersionWavenumber(peak, options.depth);
        s.steepness = s.significantWaveHeight / s.peakWavelength;
    }
    return s;
}

double significantWaveHeight(const Image& heights, int channel) {
    // Two passes (mean, then squares about it): one pass loses digits for maps far from zero mean.
    const size_t texels = heights.texelCount(), step = size_t(heights.channels);
    const double n = double(texels);
    if (n == 0) return 0.0;
    const float* v = heights.pixels.data() + channel;
    double sum = 0.0;
    for (size_t i = 0; i < texels; ++i) sum += v[i * step];
    const double mean = sum / n;
    double sq = 0.0;
    for (size_t i = 0; i < texels; ++i) sq += (v[i * step] - mean) * (v[i * step] - mean);
    return 4.0 * std::sqrt(sq / n);
}

double foldFraction(const Image& jacobian, int channel) {
    const size_t texels = jacobian.texelCount(), step = size_t(jacobian.channels);
    if (texels == 0) return 0.0;
    size_t folds = 0;
    for (size_t i = 0; i < texels; ++i) folds += jacobian.pixels[i * step + channel] < 0.0f;
    return double(folds) / double(texels);
}

double largestDisplacement(const Image& displacement, double choppiness, int channel) {
    const size_t texels = displacement.texelCount(), step = size_t(displacement.channels);
    const float* d = displacement.pixels.data() + channel;
    // The largest squared length, one root at the end: a float's square is exact in double, so this is
    // hypot's answer to rounding without a hypot per texel (16 million at 4096^2).
    double worst = 0.0;
    for (size_t i = 0; i < texels; ++i) {
        const double x = d[i * step], y = d[i * step + 1];
        worst = std::max(worst, x * x + y * y);
    }
    return std::abs(choppiness) * std::sqrt(worst);
}

}  // namespace heightpack
