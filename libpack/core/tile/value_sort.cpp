#include "value_sort.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <utility>

#include "heightpack/core/image.hpp"
#include "heightpack/core/parallel.hpp"

namespace heightpack::detail {

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

}  // namespace heightpack::detail
