#include "heightpack/core/sea_report.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "heightpack/core/parallel.hpp"

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

namespace {

// row(y) for every row on `threads` threads, the results in row order: combined in that order afterwards,
// a sum is the same whatever the thread count.
template <typename Row>
auto perRow(const Image& image, int threads, const Row& row) {
    std::vector<decltype(row(0))> out(image.height);
    parallelFor(image.height, threads, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) out[y] = row(y);
    });
    return out;
}

// The `channel` values of row y of image, `step` floats apart.
const float* rowOf(const Image& image, int y, int channel) {
    return image.pixels.data() + size_t(y) * image.width * image.channels + channel;
}

}  // namespace

double significantWaveHeight(const Image& heights, int channel, int threads) {
    // Two passes (mean, then squares about it): one pass loses digits for maps far from zero mean.
    const double n = double(heights.texelCount());
    if (n == 0) return 0.0;
    const size_t step = size_t(heights.channels);
    double sum = 0.0;
    for (double row : perRow(heights, threads, [&](int y) {
             const float* v = rowOf(heights, y, channel);
             double s = 0.0;
             for (int x = 0; x < heights.width; ++x) s += v[x * step];
             return s;
         }))
        sum += row;
    const double mean = sum / n;
    double sq = 0.0;
    for (double row : perRow(heights, threads, [&](int y) {
             const float* v = rowOf(heights, y, channel);
             double s = 0.0;
             for (int x = 0; x < heights.width; ++x) s += (v[x * step] - mean) * (v[x * step] - mean);
             return s;
         }))
        sq += row;
    return 4.0 * std::sqrt(sq / n);
}

std::pair<float, float> channelRange(const Image& image, int channel, int threads) {
    const size_t step = size_t(image.channels);
    std::pair<float, float> range{image.pixels[channel], image.pixels[channel]};
    for (const auto& [lo, hi] : perRow(image, threads, [&](int y) {
             const float* v = rowOf(image, y, channel);
             std::pair<float, float> r{v[0], v[0]};
             for (int x = 1; x < image.width; ++x) r = {std::min(r.first, v[x * step]), std::max(r.second, v[x * step])};
             return r;
         }))
        range = {std::min(range.first, lo), std::max(range.second, hi)};
    return range;
}

double foldFraction(const Image& jacobian, int channel, int threads) {
    const size_t texels = jacobian.texelCount(), step = size_t(jacobian.channels);
    if (texels == 0) return 0.0;
    size_t folds = 0;
    for (size_t row : perRow(jacobian, threads, [&](int y) {
             const float* j = rowOf(jacobian, y, channel);
             size_t count = 0;
             for (int x = 0; x < jacobian.width; ++x) count += j[x * step] < 0.0f;
             return count;
         }))
        folds += row;
    return double(folds) / double(texels);
}

double largestDisplacement(const Image& displacement, double choppiness, int channel, int threads) {
    // The largest squared length, one root at the end: a float's square is exact in double, so this is
    // hypot's answer to rounding without a hypot per texel (16 million at 4096^2).
    const size_t step = size_t(displacement.channels);
    double worst = 0.0;
    for (double row : perRow(displacement, threads, [&](int y) {
             const float* d = rowOf(displacement, y, channel);
             double w = 0.0;
             for (int x = 0; x < displacement.width; ++x) {
                 const double dx = d[x * step], dy = d[x * step + 1];
                 w = std::max(w, dx * dx + dy * dy);
             }
             return w;
         }))
        worst = std::max(worst, row);
    return std::abs(choppiness) * std::sqrt(worst);
}

}  // namespace heightpack
