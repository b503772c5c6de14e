#include "heightpack/core/sea/sea_report.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
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

FrameNumbers frameNumbers(const Image& frame, const FrameChannels& at, double choppiness, int threads) {
    FrameNumbers numbers;
    const double n = double(frame.texelCount());
    if (n == 0) return numbers;
    const size_t step = size_t(frame.channels);
    // Pass 1: each row's height sum and range, folds and largest squared move (a float's square is exact
    // in double: one root at the end gives hypot's answer to rounding without a hypot per texel).
    struct RowNumbers {
        double sum = 0.0, move2 = 0.0;
        float lo = 0.0f, hi = 0.0f;
        size_t folds = 0;
    };
    const std::vector<RowNumbers> rows = perRow(frame, threads, [&](int y) {
        RowNumbers r;
        if (at.heights >= 0) {
            const float* h = rowOf(frame, y, at.heights);
            r.lo = r.hi = h[0];
            for (int x = 0; x < frame.width; ++x) {
                r.sum += h[x * step];
                r.lo = std::min(r.lo, h[x * step]), r.hi = std::max(r.hi, h[x * step]);
            }
        }
        if (at.jacobian >= 0) {
            const float* j = rowOf(frame, y, at.jacobian);
            for (int x = 0; x < frame.width; ++x) r.folds += j[x * step] < 0.0f;
        }
        if (at.shift >= 0) {
            const float* d = rowOf(frame, y, at.shift);
            for (int x = 0; x < frame.width; ++x) {
                const double dx = d[x * step], dy = d[x * step + 1];
                r.move2 = std::max(r.move2, dx * dx + dy * dy);
            }
        }
        return r;
    });
    double sum = 0.0, move2 = 0.0;
    size_t folds = 0;
    numbers.minHeight = rows[0].lo, numbers.maxHeight = rows[0].hi;
    for (const RowNumbers& r : rows) {
        sum += r.sum, folds += r.folds, move2 = std::max(move2, r.move2);
        numbers.minHeight = std::min(numbers.minHeight, r.lo), numbers.maxHeight = std::max(numbers.maxHeight, r.hi);
    }
    numbers.foldFraction = double(folds) / n;
    numbers.largestShift = std::abs(choppiness) * std::sqrt(move2);
    if (at.heights < 0) return numbers;
    // Pass 2: squares about the mean (one pass loses digits for maps far from zero mean).
    const double mean = sum / n;
    double sq = 0.0;
    for (double row : perRow(frame, threads, [&](int y) {
             const float* v = rowOf(frame, y, at.heights);
             double s = 0.0;
             for (int x = 0; x < frame.width; ++x) s += (v[x * step] - mean) * (v[x * step] - mean);
             return s;
         }))
        sq += row;
    numbers.significantWaveHeight = 4.0 * std::sqrt(sq / n);
    return numbers;
}

double significantWaveHeight(const Image& heights, int channel, int threads) {
    return frameNumbers(heights, {channel, -1, -1}, 1.0, threads).significantWaveHeight;
}

double foldFraction(const Image& jacobian, int channel, int threads) {
    return frameNumbers(jacobian, {-1, -1, channel}, 1.0, threads).foldFraction;
}

double largestShift(const Image& shift, double choppiness, int channel, int threads) {
    return frameNumbers(shift, {-1, channel, -1}, choppiness, threads).largestShift;
}

}  // namespace heightpack
