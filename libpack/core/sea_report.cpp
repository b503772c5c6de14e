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

double significantWaveHeight(const Image& heights) {
    // Two passes (mean, then squares about it): one pass loses digits for maps far from zero mean.
    const double n = double(heights.pixels.size());
    if (n == 0) return 0.0;
    double sum = 0.0;
    for (float v : heights.pixels) sum += v;
    const double mean = sum / n;
    double sq = 0.0;
    for (float v : heights.pixels) sq += (v - mean) * (v - mean);
    return 4.0 * std::sqrt(sq / n);
}

double foldFraction(const Image& jacobian) {
    if (jacobian.pixels.empty()) return 0.0;
    const auto folds = std::count_if(jacobian.pixels.begin(), jacobian.pixels.end(), [](float j) { return j < 0.0f; });
    return double(folds) / double(jacobian.pixels.size());
}

double largestDisplacement(const Image& displacement, double choppiness) {
    double worst = 0.0;
    for (size_t i = 0; i + 1 < displacement.pixels.size(); i += 2)
        worst = std::max(worst, std::hypot(double(displacement.pixels[i]), double(displacement.pixels[i + 1])));
    return std::abs(choppiness) * worst;
}

}  // namespace heightpack
