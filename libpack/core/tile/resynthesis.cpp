// Band re-synthesis by Gaussian conditional simulation: see tile/resynthesis.hpp for the steps.
#include "heightpack/core/tile/resynthesis.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <optional>
#include <vector>

#include "heightpack/core/parallel.hpp"
#include "heightpack/core/tile/tileable.hpp"

#include "enlargement.hpp"
#include "field.hpp"
#include "gaussian_model.hpp"
#include "gaussianise.hpp"
#include "line_kriging.hpp"
#include "range.hpp"
#include "smoothing.hpp"
#include "strip_field.hpp"

namespace heightpack {

namespace {

using detail::Axis;
using detail::Field;
using detail::GaussianModel;
using detail::StripField;
using detail::bandLinesReach;
using detail::resynthesiseLines;

// The variance, in the Gaussian domain, of rounding the map to its levels: each run of equal values spans
// an interval of Gaussians, over which a value is spread as if uniformly. 0 for a float map. runs(add) calls
// add(count) for each run of equal values, in increasing order of the value.
template <class Runs>
double quantisationNoise(size_t n, Runs runs) {
    auto quantile = [&](double rank) { return detail::inverseNormalCdf(std::clamp(rank / n, 0.5 / n, 1 - 0.5 / n)); };
    double variance = 0;
    size_t start = 0;
    runs([&](size_t count) {
        if (count > 1) {
            const double span = quantile(double(start + count)) - quantile(double(start));
            variance += double(count) / n * span * span / 12;
        }
        start += count;
    });
    return variance;
}

// quantisationNoise of values: from a histogram where every value is a whole number of quanta (a map read
// from integer samples: no sort), else from the sorted values. range: the values' (used with a quantum).
double quantisationNoise(const std::vector<float>& values, double quantum, SampleRange range, int threads) {
    const size_t n = values.size();
    if (quantum > 0 && n > 0) {
        // Counted in fixed chunks, each its own histogram, summed in order: the same on any thread count.
        constexpr int kChunks = 16;
        constexpr double kMostLevels = 1 << 17;  // 8- and 16-bit samples, and some headroom
        const size_t chunk = (n + kChunks - 1) / kChunks;
        const double inverse = 1 / quantum, first = std::round(range.low * inverse), levels = std::round(range.high * inverse) - first + 1;
        std::vector<std::vector<size_t>> counts(levels <= kMostLevels ? kChunks : 0);
        std::vector<char> whole(kChunks, 1);
        parallelFor(int(counts.size()), threads, [&](int begin, int end) {
            for (int c = begin; c < end; ++c) {
                counts[c].assign(size_t(levels), 0);
                for (size_t i = size_t(c) * chunk; i < std::min(n, size_t(c + 1) * chunk); ++i) {
                    const double q = values[i] * inverse - first;  // at least -0.5
                    const auto level = static_cast<int64_t>(q + 0.5);
                    if (!(std::abs(q - double(level)) < 0.01)) {  // a float holds k/65535 to 0.004 steps
                        whole[c] = 0;
                        break;
                    }
                    ++counts[c][size_t(level)];
                }
            }
        });
        if (!counts.empty() && std::all_of(whole.begin(), whole.end(), [](char w) { return w != 0; }))
            return quantisationNoise(n, [&](auto add) {
                for (size_t level = 0; level < size_t(levels); ++level) {
                    size_t count = 0;
                    for (const std::vector<size_t>& c : counts) count += c[level];
                    if (count > 0) add(count);
                }
            });
    }
    const std::vector<uint32_t> order = detail::stableOrder(values, threads);
    return quantisationNoise(n, [&](auto add) {
        for (size_t start = 0; start < n;) {
            size_t end = start + 1;
            while (end < n && values[order[end]] == values[order[start]]) ++end;
            add(end - start);
            start = end;
        }
    });
}

// Where the slopes along an axis stop resembling themselves: the lag at which the autocorrelation of the
// difference field falls below 1/e, from the heights' circular autocovariance along that axis.
double slopeCorrelationLength(const std::vector<double>& lags) {
    const int w = int(lags.size());
    auto c = [&](int d) { return lags[size_t(((d % w) + w) % w)]; };
    auto d = [&](int dx) { return 2 * c(dx) - c(dx + 1) - c(dx - 1); };
    const double d0 = d(0);
    if (!(d0 > 0)) return 1.0;
    double previous = 1.0;
    for (int dx = 1; dx < w / 2; ++dx) {
        const double r = d(dx) / d0;
        if (r < std::exp(-1.0)) return dx - 1 + (previous - std::exp(-1.0)) / std::max(previous - r, 1e-12);
        previous = r;
    }
    return w / 2.0;
}

int chooseBand(double fraction, double correlation, int size) {
    const int texels = fraction > 0 ? static_cast<int>(std::lround(fraction * size))
                                    : static_cast<int>(std::lround(std::clamp(4 * correlation, size / 16.0, size / 4.0)));
    return std::clamp(texels, std::min(4, size / 4), size / 2);
}

// The sigma of the large scales for a band (texels): at least 1/16 of the tile (only scales the eye reads
// as the map's swell).
double largeScaleSigma(int bandX, int bandY, int w, int h) { return std::max(0.5 * std::max(bandX, bandY), std::min(w, h) / 16.0); }

}  // namespace

// What every attempt on one map shares: the values modelled, the model, the slopes' correlation lengths,
// and the large scales of the last sigma asked for (with the corrected map's ranks).
struct Resynthesiser::State {
    const Image& map;
    int threads;
    std::vector<float> dequantised;  // the map with its quantisation undone, where it has terraces
    SampleRange mapRange;                              // the map's lowest and highest values
    const std::vector<float>* values = &map.pixels;  // the values modelled: the map's or those
    double noise = 0;
    std::optional<GaussianModel> model;
    double correlationX = 0, correlationY = 0;
    double sigma = -1;
    std::vector<float> smooth;
    std::optional<detail::Gaussianiser> ranks;
    Field gaussian{0, 0};  // the ranks' Gaussians as a field (moved out of ranks)
    double gaussianMean = 0;
    // Where the map is an enlargement: its source, whose own re-synthesis the attempts enlarge.
    detail::Enlargement enlargement;
    Image source;
    double sourceQuantum = 0;  // the source's levels (8 bits where it was painted so, whatever the map's)
    std::unique_ptr<Resynthesiser> ofSource;
    State(const Image& m, int t) : map(m), threads(t) {}
    // The large scales at sigma and the ranks of the values less them, unless they are at sigma already.
    void useSigma(double newSigma, int w, int h) {
        if (newSigma == sigma) return;
        sigma = newSigma;
        ranks.reset();
        smooth = detail::largeScaleField(*values, w, h, sigma, threads);
        detail::Buffer<float> corrected(values->size());
        parallelFor(h, threads, [&](int begin, int end) {
            for (size_t i = size_t(begin) * w; i < size_t(end) * w; ++i) corrected[i] = (*values)[i] - smooth[i];
        });
        ranks.emplace(corrected, threads);
        gaussian = Field(w, h, std::move(ranks->gaussian));
        std::vector<double> rowSums(size_t(h), 0.0);  // per row on all threads, then summed in order
        parallelFor(h, threads, [&](int begin, int end) {
            for (int y = begin; y < end; ++y)
                rowSums[y] = std::accumulate(&gaussian.v[size_t(y) * w], &gaussian.v[size_t(y) * w] + w, 0.0);
        });
        gaussianMean = std::accumulate(rowSums.begin(), rowSums.end(), 0.0) / double(gaussian.v.size());
    }
};

Resynthesiser::Resynthesiser(const Image& map, double quantum, int threads) : Resynthesiser(map, quantum, threads, false) {}

Resynthesiser::Resynthesiser(const Image& map, double quantum, int threads, bool asSource)
    : state_(std::make_unique<State>(map, threads)) {
    const int w = map.width, h = map.height;
    if (w < 16 || h < 16) return;
    // 1. Ranks to Gaussians, of the map with its quantisation undone (otherwise a smooth 8-bit painting is a
    //    staircase whose steps the model takes for fine detail, and a sample shows them as grain) and its
    //    large scales at the least sigma taken off (step 2): the field the bands are conditioned in, so one
    //    Gaussianisation serves the model and every attempt whose bands ask no larger sigma.
    State& s = *state_;
    s.mapRange = sampleRange(map, threads);
    // 0. An enlarged map (a painting resized before packing) is re-synthesised at its source's resolution
    //    and the result enlarged the same way: a Gaussian model of the enlarged map itself carries finer
    //    grain than the smooth map around the bands shows, and costs factor^2 more.
    //    A source that is itself an enlargement (a painting made at 64, enlarged 8x, then the whole 4x) is
    //    re-synthesised at its own source's size in turn: a model of it would put the grain the map lacks.
    s.enlargement = detail::findEnlargement(map, quantum, threads, asSource);
    if (s.enlargement.factor > 1) {
        s.sourceQuantum = quantum;
        s.source = detail::roundedSource(map, s.enlargement, s.sourceQuantum, s.mapRange, threads);
        s.ofSource.reset(new Resynthesiser(s.source, s.sourceQuantum, threads, true));  // composes
        return;
    }
    const bool terraced = quantum > 0 && detail::hasTerraces(map, threads);
    if (terraced) {
        s.dequantised = detail::dequantised(map, quantum, threads);
        s.values = &s.dequantised;
    }
    s.noise = quantisationNoise(*s.values, terraced ? 0.0 : quantum, s.mapRange, threads);
    s.useSigma(largeScaleSigma(0, 0, w, h), w, h);
    s.model.emplace(detail::modelOf(s.gaussian, s.noise, threads));
    s.correlationX = slopeCorrelationLength(s.model->lagX);
    s.correlationY = slopeCorrelationLength(s.model->lagY);
}

Resynthesiser::~Resynthesiser() = default;

ResynthesisResult Resynthesiser::attempt(uint64_t seed, double band) {
    State& s = *state_;
    const Image& map = s.map;
    const int w = map.width, h = map.height, threads = s.threads;
    ResynthesisResult result;
    if (s.ofSource) return enlargedAttempt(s.ofSource->attempt(seed, band));
    if (!s.model) {
        result.map = periodicComponent(map, PeriodicContinuity::Heights);
        return result;
    }
    result.bandX = chooseBand(band, s.correlationX, w);
    result.bandY = chooseBand(band, s.correlationY, h);
    // 2. Large scales, in heights: Moisan's smooth field of a low-pass of the map at the band's scale (at
    //    least 1/16 of the tile: only scales the eye reads as the map's swell; each side of a wrap line
    //    blurred apart, mirrored). Beyond the bands this is the whole change.
    s.useSigma(largeScaleSigma(result.bandX, result.bandY, w, h), w, h);
    const detail::Gaussianiser& ranks = *s.ranks;
    // 3. and 4. The bands, left/right first, then top/bottom, in the strips they read and write (beyond
    //    them the Gaussians are the map's own).
    const int contextX = std::clamp(result.bandX / 2, 4, 32), contextY = std::clamp(result.bandY / 2, 4, 32);
    const int reachX = bandLinesReach(result.bandX, contextX), reachY = bandLinesReach(result.bandY, contextY);
    detail::StripField g(w, h, reachX, reachY);
    parallelFor(h, threads, [&](int begin, int end) {
        for (int y = begin; y < end; ++y) g.setRow(y, &s.gaussian.v[size_t(y) * w]);
    });
    const detail::StripField sample = detail::sampleOf(*s.model, seed, reachX, reachY, threads);
    double mean = s.gaussianMean;
    if (result.bandX + 2 * contextX <= w) {
        // The left/right band is solved per frequency along y, so its field must wrap top to bottom: the
        // top/bottom jump is set aside meanwhile (the top/bottom band replaces what it touches later). Its
        // mean is 0, so the field's stays.
        const detail::StripField aside = detail::topBottomSmoothField(s.gaussian, reachX, threads);
        auto add = [&](double sign) {
            parallelFor(h, threads, [&](int begin, int end) {
                for (int y = begin; y < end; ++y)
                    for (int x : aside.columns()) g.at(x, y) += sign * aside.at(x, y);
            });
        };
        add(-1.0);
        mean += resynthesiseLines(g, *s.model, sample, Axis::X, result.bandX, contextX, s.noise, mean, threads) / (double(w) * h);
        add(1.0);
    }
    if (result.bandY + 2 * contextY <= h)
        resynthesiseLines(g, *s.model, sample, Axis::Y, result.bandY, contextY, s.noise, mean, threads);
    // 5. Back to heights through the sorted values. Beyond the bands, the map itself plus the large-scale
    //    change there (so its own fine detail, terraces and all, stays exactly); in the bands, the new
    //    content, which a quantised output rounds to its levels.
    auto inBand = [&](int x, int y) {
        const int dx = std::min(x, w - 1 - x), dy = std::min(y, h - 1 - y);
        return dx < (result.bandX + 1) / 2 + 1 || dy < (result.bandY + 1) / 2 + 1;
    };
    result.map = Image(w, h, 1);
    parallelFor(h, threads, [&](int begin, int end) {
        std::vector<double> gaussians(static_cast<size_t>(w));
        std::vector<float> values(static_cast<size_t>(w));
        for (int y = begin; y < end; ++y) {
            int count = 0;  // the row's texels in the bands, their Gaussians gathered and taken back at once
            for (int x = 0; x < w; ++x)
                if (inBand(x, y)) gaussians[count++] = g.at(x, y);
            ranks.back(gaussians.data(), values.data(), size_t(count));
            count = 0;
            for (int x = 0; x < w; ++x) {
                const size_t i = size_t(y) * w + x;
                result.map.pixels[i] = inBand(x, y) ? values[count++] : map.pixels[i] - s.smooth[i];
            }
        }
    });
    detail::easeIntoRange(result.map, s.mapRange, threads);
    return result;
}

ResynthesisResult Resynthesiser::enlargedAttempt(ResynthesisResult fromSource) const {
    const State& s = *state_;
    ResynthesisResult result;
    detail::putOnLevels(fromSource.map, s.sourceQuantum, s.mapRange);
    result.map = detail::enlargedTile(s.map, s.source, fromSource.map, s.enlargement, (fromSource.bandX + 1) / 2 + 1,
                                      (fromSource.bandY + 1) / 2 + 1, s.mapRange, s.threads);
    // The texels replaced: those enlargedTile takes from the source's tile.
    const int f = s.enlargement.factor;
    result.bandX = std::min(s.map.width, 2 * ((fromSource.bandX + 1) / 2 + 1 + detail::kEnlargedTileReach) * f);
    result.bandY = std::min(s.map.height, 2 * ((fromSource.bandY + 1) / 2 + 1 + detail::kEnlargedTileReach) * f);
    return result;
}

ResynthesisResult resynthesiseTile(const Image& map, const ResynthesisOptions& options) {
    return Resynthesiser(map, options.quantum, options.threads).attempt(options.seed, options.band);
}

}  // namespace heightpack
