#include "gaussianise.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <span>
#include <utility>

#include "heightpack/core/image.hpp"
#include "heightpack/core/parallel.hpp"

namespace heightpack::detail {

namespace {

// A float's bits as an unsigned key that sorts as the float does (negatives flipped, positives with the
// sign bit set); -0 counts as +0, as comparison has it.
uint32_t keyOf(float v) {
    uint32_t u;
    const float canonical = v == 0.0f ? 0.0f : v;
    std::memcpy(&u, &canonical, sizeof u);
    return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

float valueOfKey(uint32_t key) {
    const uint32_t u = (key & 0x80000000u) ? (key & 0x7fffffffu) : ~key;
    float v;
    std::memcpy(&v, &u, sizeof v);
    return v;
}

}  // namespace

namespace {

// The whole sort in passes of 11 bits over all items (least significant digit first).
Buffer<uint64_t> digitSortedItems(std::span<const float> values, int threads) {
    const size_t n = values.size();
    // The items in a fixed number of chunks: each pass counts digits per chunk on any thread, then each
    // chunk scatters its items, in order, from its own start in each bucket. A stable sort has one result,
    // so the thread count cannot change it. Both arrays are first written by the chunks (no serial zeroing).
    constexpr int kChunks = 64, kBits = 11, kBuckets = 1 << kBits;
    const size_t chunkSize = (n + kChunks - 1) / kChunks;
    auto chunkRange = [&](int c) { return std::pair<size_t, size_t>(std::min(n, c * chunkSize), std::min(n, (c + 1) * chunkSize)); };
    Buffer<uint64_t> items(n), scratch(n);  // key << 32 | index
    parallelFor(kChunks, threads, [&](int begin, int end) {
        for (size_t i = chunkRange(begin).first; i < chunkRange(end - 1).second; ++i) items[i] = uint64_t(keyOf(values[i])) << 32 | i;
    });
    std::vector<size_t> counts(size_t(kChunks) * kBuckets);
    for (int shift = 32; shift < 64; shift += kBits) {
        parallelFor(kChunks, threads, [&](int begin, int end) {
            for (int c = begin; c < end; ++c) {
                size_t* count = &counts[size_t(c) * kBuckets];
                std::fill(count, count + kBuckets, size_t(0));
                const auto [from, to] = chunkRange(c);
                for (size_t i = from; i < to; ++i) ++count[(items[i] >> shift) & (kBuckets - 1)];
            }
        });
        // Each (chunk, bucket)'s first place: buckets in order, chunks in order within a bucket.
        size_t next = 0;
        bool oneBucket = false;
        for (int b = 0; b < kBuckets; ++b) {
            const size_t bucketStart = next;
            for (int c = 0; c < kChunks; ++c) {
                const size_t count = counts[size_t(c) * kBuckets + b];
                counts[size_t(c) * kBuckets + b] = next;
                next += count;
            }
            oneBucket = oneBucket || next - bucketStart == n;
        }
        if (oneBucket) continue;  // every digit the same: no change
        parallelFor(kChunks, threads, [&](int begin, int end) {
            for (int c = begin; c < end; ++c) {
                size_t* start = &counts[size_t(c) * kBuckets];
                const auto [from, to] = chunkRange(c);
                for (size_t i = from; i < to; ++i) scratch[start[(items[i] >> shift) & (kBuckets - 1)]++] = items[i];
            }
        });
        items.swap(scratch);
    }
    return items;
}

// Sorts items[0, n) (key << 32 | index, in index order among equal keys) by key, stably, through scratch
// (at least n): passes of 11 bits over only the bits in which the keys differ. For a bucket that fits in
// the cache.
void sortBucket(uint64_t* items, uint64_t* scratch, size_t n) {
    if (n < 2) return;
    uint64_t any = 0, all = ~uint64_t(0);
    for (size_t i = 0; i < n; ++i) {
        any |= items[i];
        all &= items[i];
    }
    const uint32_t differing = static_cast<uint32_t>((any ^ all) >> 32);
    if (differing == 0) return;
    constexpr int kBits = 11, kBuckets = 1 << kBits;
    const int low = std::countr_zero(differing), high = 32 - std::countl_zero(differing);
    size_t count[kBuckets];
    uint64_t* from = items;
    uint64_t* to = scratch;
    for (int shift = 32 + low; shift < 32 + high; shift += kBits) {
        std::fill(count, count + kBuckets, size_t(0));
        for (size_t i = 0; i < n; ++i) ++count[(from[i] >> shift) & (kBuckets - 1)];
        size_t next = 0;
        for (size_t& c : count) next += std::exchange(c, next);
        for (size_t i = 0; i < n; ++i) to[count[(from[i] >> shift) & (kBuckets - 1)]++] = from[i];
        std::swap(from, to);
    }
    if (from != items) std::copy(from, from + n, items);
}

}  // namespace

Buffer<uint64_t> sortedItems(std::span<const float> values, int threads) {
    const size_t n = values.size();
    // First by bucket: the range of values cut into equal parts, about 4096 values a part on average
    // (a bucket is monotone in the value, so buckets in order hold the values in order); the items
    // scattered into their buckets once, in index order, then each bucket sorted alone while it is in the
    // cache. The whole-array digit passes read and wrote every item three times over. A map whose values
    // crowd into few parts (a flat region, a handful of levels) is sorted by those passes instead. Either
    // way the sort is stable, with one result on any thread count.
    constexpr size_t kPerBucket = 4096;
    constexpr int kChunks = 64;
    const size_t buckets = std::min<size_t>(n / kPerBucket, size_t(1) << 16);
    if (buckets < 16) return digitSortedItems(values, threads);
    const SampleRange range = sampleRange(values, threads);
    const double low = range.low, scale = double(buckets) / (double(range.high) - low);
    if (!(scale < std::numeric_limits<double>::infinity())) return digitSortedItems(values, threads);  // one value
    auto bucketOf = [&](float v) { return std::min(buckets - 1, static_cast<size_t>((double(v) - low) * scale)); };
    const size_t chunkSize = (n + kChunks - 1) / kChunks;
    std::vector<size_t> starts(size_t(kChunks) * buckets);  // per chunk, per bucket: counts, then first places
    parallelFor(kChunks, threads, [&](int begin, int end) {
        for (int c = begin; c < end; ++c) {
            size_t* count = &starts[size_t(c) * buckets];
            for (size_t i = std::min(n, c * chunkSize); i < std::min(n, (c + 1) * chunkSize); ++i) ++count[bucketOf(values[i])];
        }
    });
    std::vector<size_t> bucketStart(buckets + 1);
    size_t next = 0, largest = 0;
    for (size_t b = 0; b < buckets; ++b) {
        bucketStart[b] = next;
        for (int c = 0; c < kChunks; ++c) next += std::exchange(starts[size_t(c) * buckets + b], next);
        largest = std::max(largest, next - bucketStart[b]);
    }
    bucketStart[buckets] = n;
    if (largest > n / 16) return digitSortedItems(values, threads);  // crowded: one thread would sort most
    Buffer<uint64_t> items(n);
    parallelFor(kChunks, threads, [&](int begin, int end) {
        for (int c = begin; c < end; ++c) {
            size_t* start = &starts[size_t(c) * buckets];
            for (size_t i = std::min(n, c * chunkSize); i < std::min(n, (c + 1) * chunkSize); ++i)
                items[start[bucketOf(values[i])]++] = uint64_t(keyOf(values[i])) << 32 | i;
        }
    });
    // The buckets in groups of about equal numbers of items, so the threads' shares are even.
    std::vector<size_t> groupStart;  // bucket indices
    for (size_t b = 0; b < buckets; ++b)
        if (groupStart.empty() || bucketStart[b] * kChunks >= groupStart.size() * n) groupStart.push_back(b);
    groupStart.push_back(buckets);
    parallelFor(int(groupStart.size()) - 1, threads, [&](int begin, int end) {
        Buffer<uint64_t> scratch(largest);
        for (size_t b = groupStart[size_t(begin)]; b < groupStart[size_t(end)]; ++b)
            sortBucket(&items[bucketStart[b]], scratch.data(), bucketStart[b + 1] - bucketStart[b]);
    });
    return items;
}

std::vector<uint32_t> stableOrder(std::span<const float> values, int threads) {
    const Buffer<uint64_t> items = sortedItems(values, threads);
    std::vector<uint32_t> order(items.size());
    parallelFor(static_cast<int>((items.size() + 65535) / 65536), threads, [&](int begin, int end) {
        for (size_t i = size_t(begin) * 65536; i < std::min(items.size(), size_t(end) * 65536); ++i) order[i] = static_cast<uint32_t>(items[i]);
    });
    return order;
}

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

Gaussianiser::Gaussianiser(std::span<const float> values, int threads) : sorted(values.size()), gaussian(values.size()) {
    const size_t n = values.size();
    if (n == 0) return;
    // The (value, index) pairs by value then index: a stable radix sort of the values' bits, which keeps
    // the index order of equal values (and is ~10x std::sort's time on millions of texels). The sorted
    // values come back from the keys, in order, rather than gathered from all over the input.
    const Buffer<uint64_t> items = sortedItems(values, threads);
    auto indexAt = [&](size_t k) { return static_cast<uint32_t>(items[k]); };
    parallelFor(static_cast<int>((n + 65535) / 65536), threads, [&](int begin, int end) {
        for (size_t i = size_t(begin) * 65536; i < std::min(n, size_t(end) * 65536); ++i) sorted[i] = valueOfKey(uint32_t(items[i] >> 32));
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
            if (start > 0 && sorted[start] == sorted[start - 1]) {  // inside a run an earlier block takes
                ++start;
                continue;
            }
            size_t stop = start + 1;
            while (stop < n && sorted[stop] == sorted[start]) ++stop;
            const double g = acklamQuantile((0.5 * double(start + stop - 1) + 0.5) / double(n));
            for (size_t k = start; k < stop; ++k) gaussian[indexAt(k)] = g;
            start = stop;
        }
    });
}

void Gaussianiser::back(const double* g, float* out, size_t count) const {
    // In groups: every place of a group found (and its sorted values asked of memory) before any is read,
    // so the misses of a group overlap instead of each waiting on the last.
    constexpr size_t kGroup = 16;
    const double top = double(sorted.size() - 1);
    for (size_t start = 0; start < count; start += kGroup) {
        const size_t n = std::min(kGroup, count - start);
        double pos[kGroup];
        for (size_t k = 0; k < n; ++k) {
            pos[k] = std::clamp(normalCdf(g[start + k]) * sorted.size() - 0.5, 0.0, top);
            __builtin_prefetch(&sorted[static_cast<size_t>(pos[k])]);
        }
        for (size_t k = 0; k < n; ++k) {
            const size_t i = static_cast<size_t>(pos[k]);
            const size_t j = std::min(i + 1, sorted.size() - 1);
            out[start + k] = static_cast<float>(sorted[i] + (double(sorted[j]) - sorted[i]) * (pos[k] - i));
        }
    }
}

float Gaussianiser::back(double g) const {
    float value;
    back(&g, &value, 1);
    return value;
}

}  // namespace heightpack::detail
