#include "gaussianise.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <span>

#include "heightpack/core/image.hpp"
#include "heightpack/core/parallel.hpp"

namespace heightpack::detail {

double normalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

namespace {

// Acklam's rational approximation of the normal quantile: relative error below 1.15e-9.
double acklamQuantile(double p) {
    static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                               1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00};
    static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                               6.680131188771972e+01, -1.328068155288572e+01};
    static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                               -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00};
    static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                               3.754408661907416e+00};
    const double low = 0.02425;
    if (p < low) {
        const double q = std::sqrt(-2 * std::log(p));
        return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
               ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
    }
    if (p > 1 - low) {
        const double q = std::sqrt(-2 * std::log(1 - p));
        return -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
               ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
    }
    const double q = p - 0.5, r = q * q;
    return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
           (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
}

}  // namespace

double inverseNormalCdf(double p) {
    const double x = acklamQuantile(p);
    const double e = normalCdf(x) - p;
    const double u = e * std::sqrt(2 * std::numbers::pi) * std::exp(x * x / 2);
    return x - u / (1 + x * u / 2);
}

Gaussianiser::Gaussianiser(std::span<const float> values, int threads) : gaussian(values.size()), n_(values.size()) {
    if (n_ == 0) return;
    if (!binnedRanks(values, threads)) sortedRanks(values, threads);
}

bool Gaussianiser::binnedRanks(std::span<const float> values, int threads) {
    const size_t n = n_;
    constexpr size_t kLeast = size_t(1) << 20;
    if (n < kLeast) return false;
    const SampleRange range = sampleRange(values, threads);
    const double low = range.low, scale = kRankBins / (double(range.high) - low);
    if (!(scale < std::numeric_limits<double>::infinity())) return false;  // one value
    auto binOf = [&](float v) { return std::min(kRankBins - 1, static_cast<int>((double(v) - low) * scale)); };
    // Counts, lowest and highest per part, per worker (sums and extremes: the same in any split), merged.
    const int workers = std::min(resolveThreadCount(threads), 16);
    struct Part {
        size_t count = 0;
        float low = std::numeric_limits<float>::infinity(), high = -std::numeric_limits<float>::infinity();
    };
    std::vector<std::vector<Part>> parts(static_cast<size_t>(workers));
    parallelFor(workers, workers, [&](int first, int last) {
        for (int worker = first; worker < last; ++worker) {
            std::vector<Part>& mine = parts[size_t(worker)];
            mine.assign(kRankBins, Part{});
            const size_t from = n * size_t(worker) / size_t(workers), to = n * size_t(worker + 1) / size_t(workers);
            for (size_t i = from; i < to; ++i) {
                const float v = values[i] == 0.0f ? 0.0f : values[i];  // -0 as +0, as comparison has it
                Part& p = mine[size_t(binOf(v))];
                ++p.count;
                p.low = std::min(p.low, v);
                p.high = std::max(p.high, v);
            }
        }
    });
    binned_.assign(kRankBins, Bin{});
    size_t next = 0;
    const size_t crowded = 64 * (n / kRankBins);  // a smooth density's peak part holds a few times the mean
    for (int b = 0; b < kRankBins; ++b) {
        Bin& bin = binned_[size_t(b)];
        bin.low = std::numeric_limits<float>::infinity();
        bin.high = -std::numeric_limits<float>::infinity();
        for (const std::vector<Part>& mine : parts) {
            bin.count += mine[size_t(b)].count;
            bin.low = std::min(bin.low, mine[size_t(b)].low);
            bin.high = std::max(bin.high, mine[size_t(b)].high);
        }
        bin.first = next;
        next += bin.count;
        if (bin.count > crowded && bin.low != bin.high) {  // crowded, and not one value: sort instead
            binned_.clear();
            return false;
        }
    }
    // Each part's ranks: its lowest value's, interpolated to its highest's; a part of one value, its
    // mid-rank; the Gaussians interpolated alike. A rank's place within its part is only as good as the
    // part's values are even (a few ranks off, as order statistics go), so where one rank moves the
    // Gaussian by more than 1e-5 (the tails: beyond 2.9 standard deviations at 2^24 values, where it
    // curves like a logarithm and a rank moves it by tenths at the far end) the part is "curved": its
    // values are sorted, for their exact ranks.
    auto quantile = [&](double rank) { return acklamQuantile((rank + 0.5) / double(n)); };
    for (Bin& bin : binned_) {
        if (bin.count == 0) continue;
        if (bin.low == bin.high) {
            bin.gaussian = quantile(double(bin.first) + 0.5 * double(bin.count - 1));
            continue;
        }
        const double last = double(bin.first + bin.count - 1), span = double(bin.high) - bin.low;
        bin.gaussian = quantile(double(bin.first));
        bin.slope = (quantile(last) - bin.gaussian) / span;
        bin.curved = bin.slope * span / (last - double(bin.first)) > 1e-5;
    }
    // Every value's Gaussian, those of curved parts gathered (key << 32 | index, per worker in index
    // order, so the whole list is in index order on any split).
    std::vector<std::vector<uint64_t>> tails(static_cast<size_t>(workers));
    parallelFor(workers, workers, [&](int first, int last) {
        for (int worker = first; worker < last; ++worker) {
            const size_t from = n * size_t(worker) / size_t(workers), to = n * size_t(worker + 1) / size_t(workers);
            for (size_t i = from; i < to; ++i) {
                const float v = values[i] == 0.0f ? 0.0f : values[i];
                const Bin& bin = binned_[size_t(binOf(v))];
                if (bin.curved) tails[size_t(worker)].push_back(uint64_t(keyOf(v)) << 32 | i);
                else gaussian[i] = bin.gaussian + (double(v) - bin.low) * bin.slope;
            }
        }
    });
    std::vector<uint64_t> tail;
    for (const std::vector<uint64_t>& t : tails) tail.insert(tail.end(), t.begin(), t.end());
    std::sort(tail.begin(), tail.end());  // by value, then index: the tails' values in rank order
    tailValues_.resize(tail.size());
    for (size_t k = 0; k < tail.size(); ++k) tailValues_[k] = valueOfKey(uint32_t(tail[k] >> 32));
    size_t partStart = 0;  // the first place in the tail list of the part of the run at start
    for (size_t start = 0; start < tail.size();) {
        // A run of equal values, within one part: its ranks from the part's first.
        if (start > 0 && binOf(tailValues_[start]) != binOf(tailValues_[start - 1])) partStart = start;
        const Bin& bin = binned_[size_t(binOf(tailValues_[start]))];
        size_t stop = start + 1;
        while (stop < tail.size() && tailValues_[stop] == tailValues_[start]) ++stop;
        const double rank = double(bin.first + (start - partStart)) + 0.5 * double(stop - start - 1);
        for (size_t k = start; k < stop; ++k) gaussian[uint32_t(tail[k])] = quantile(rank);
        start = stop;
    }
    size_t offset = 0;
    for (Bin& bin : binned_)
        if (bin.curved) {
            bin.tailOffset = offset;
            offset += bin.count;
        }
    // For back: the part holding each of kRankBins evenly spaced ranks, so a rank's part is a short walk.
    binOfRank_.resize(kRankBins);
    int b = 0;
    for (size_t k = 0; k < binOfRank_.size(); ++k) {
        const size_t rank = n * k / binOfRank_.size();
        while (binned_[size_t(b)].first + binned_[size_t(b)].count <= rank) ++b;
        binOfRank_[k] = b;
    }
    return true;
}

void Gaussianiser::sortedRanks(std::span<const float> values, int threads) {
    const size_t n = n_;
    sorted_.resize(n);
    // The (value, index) pairs by value then index: a stable radix sort of the values' bits, which keeps
    // the index order of equal values (and is ~10x std::sort's time on millions of texels). The sorted
    // values come back from the keys, in order, rather than gathered from all over the input.
    const Buffer<uint64_t> items = sortedItems(values, threads);
    auto indexAt = [&](size_t k) { return static_cast<uint32_t>(items[k]); };
    parallelFor(static_cast<int>((n + 65535) / 65536), threads, [&](int begin, int end) {
        for (size_t i = size_t(begin) * 65536; i < std::min(n, size_t(end) * 65536); ++i) sorted_[i] = valueOfKey(uint32_t(items[i] >> 32));
    });
    // Runs of equal values share their mid-rank's quantile; the quantiles are computed on all threads.
    // Acklam's approximation alone: its error (1.15e-9 relative) is far below the spacing of neighbouring
    // ranks' quantiles (1/(n pdf), over 1e-7 for 2^24 values), and a map of distinct values has a quantile
    // per texel, where the Halley step's erfc and exp were most of the time.
    // Each block of sorted places takes the runs that start in it (a run may end in a later block), so
    // no list of runs is built: a map of distinct values has one per texel.
    constexpr size_t kPlaces = 65536;
    parallelFor(static_cast<int>((n + kPlaces - 1) / kPlaces), threads, [&](int begin, int end) {
        for (size_t start = size_t(begin) * kPlaces, last = std::min(n, size_t(end) * kPlaces); start < last;) {
            if (start > 0 && sorted_[start] == sorted_[start - 1]) {  // inside a run an earlier block takes
                ++start;
                continue;
            }
            size_t stop = start + 1;
            while (stop < n && sorted_[stop] == sorted_[start]) ++stop;
            const double g = acklamQuantile((0.5 * double(start + stop - 1) + 0.5) / double(n));
            for (size_t k = start; k < stop; ++k) gaussian[indexAt(k)] = g;
            start = stop;
        }
    });
}

float Gaussianiser::binnedValue(double rank) const {
    size_t b = size_t(binOfRank_[std::min(binOfRank_.size() - 1, static_cast<size_t>(rank / double(n_) * double(binOfRank_.size())))]);
    // From a part that starts at or before the rank, on past those that end at or before it (empty parts
    // among them): the part that holds it.
    while (b + 1 < binned_.size() && double(binned_[b].first + binned_[b].count) <= rank) ++b;
    const Bin& bin = binned_[b];
    // The value of rank first + place, place a whole number: the part's lowest, its highest, a sorted
    // one (curved), or one interpolated in the part.
    auto valueAt = [&](size_t place) -> double {
        if (bin.curved) return tailValues_[bin.tailOffset + place];
        return bin.count < 2 ? bin.low : bin.low + (double(bin.high) - bin.low) * double(place) / double(bin.count - 1);
    };
    const double place = std::max(0.0, rank - double(bin.first));
    const size_t i = std::min(static_cast<size_t>(place), bin.count - 1);
    if (place <= double(bin.count - 1)) {
        if (i + 1 >= bin.count) return static_cast<float>(valueAt(i));
        return static_cast<float>(valueAt(i) + (valueAt(i + 1) - valueAt(i)) * (place - double(i)));
    }
    // Between the part's last rank and the next part's first: towards the next part's lowest value.
    size_t next = b + 1;
    while (next < binned_.size() && binned_[next].count == 0) ++next;
    if (next == binned_.size()) return bin.high;
    return static_cast<float>(valueAt(bin.count - 1) + (double(binned_[next].low) - valueAt(bin.count - 1)) * (place - double(bin.count - 1)));
}

void Gaussianiser::back(const double* g, float* out, size_t count) const {
    const double top = double(n_ - 1);
    if (!binned_.empty()) {
        for (size_t k = 0; k < count; ++k) out[k] = binnedValue(std::clamp(normalCdf(g[k]) * double(n_) - 0.5, 0.0, top));
        return;
    }
    // In groups: every place of a group found (and its sorted values asked of memory) before any is read,
    // so the misses of a group overlap instead of each waiting on the last.
    constexpr size_t kGroup = 16;
    for (size_t start = 0; start < count; start += kGroup) {
        const size_t n = std::min(kGroup, count - start);
        double pos[kGroup];
        for (size_t k = 0; k < n; ++k) {
            pos[k] = std::clamp(normalCdf(g[start + k]) * double(n_) - 0.5, 0.0, top);
            __builtin_prefetch(&sorted_[static_cast<size_t>(pos[k])]);
        }
        for (size_t k = 0; k < n; ++k) {
            const size_t i = static_cast<size_t>(pos[k]);
            const size_t j = std::min(i + 1, n_ - 1);
            out[start + k] = static_cast<float>(sorted_[i] + (double(sorted_[j]) - sorted_[i]) * (pos[k] - i));
        }
    }
}

float Gaussianiser::back(double g) const {
    float value;
    back(&g, &value, 1);
    return value;
}

}  // namespace heightpack::detail
