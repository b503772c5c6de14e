#include "png_unfilter.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "heightpack/core/parallel.hpp"

#include "png_format.hpp"

namespace heightpack::detail {

namespace {

// Undoes one row's filter (0 to 4) on bytes [begin, end) of the row, begin a multiple of BPP, the bytes
// before begin already undone. BPP bytes per pixel, known at compile time: byte i depends on byte i - BPP,
// so the BPP chains within a pixel are independent and the unrolled inner loop runs them side by side.
// Each chain's last byte is carried in a register (`left`), not read back from the row it was just
// stored to: Paeth's chain is then its arithmetic alone, not a store and a load a byte.
template <int BPP>
void unfilterSpan(int filter, unsigned char* cur, const unsigned char* up, size_t begin, size_t end) {
    auto byte = [](int v) { return static_cast<unsigned char>(v); };
    const size_t from = std::max<size_t>(begin, BPP);  // the first pixel has no left neighbour
    int left[BPP];
    // The first pixel's bytes (their left neighbours are 0), then the left neighbours of byte `from` on.
    auto start = [&](auto first) {
        if (begin == 0)
            for (int b = 0; b < BPP && b < int(end); ++b) cur[b] = byte(cur[b] + first(b));
        for (int b = 0; b < BPP; ++b) left[b] = cur[from - BPP + b];
    };
    switch (filter) {
        case 1:
            start([](int) { return 0; });
            for (size_t i = from; i < end; i += BPP)
                for (int b = 0; b < BPP; ++b) left[b] = cur[i + b] = byte(cur[i + b] + left[b]);
            return;
        case 2:
            for (size_t i = begin; i < end; ++i) cur[i] = byte(cur[i] + up[i]);
            return;
        case 3:
            start([&](int b) { return up[b] >> 1; });
            for (size_t i = from; i < end; i += BPP)
                for (int b = 0; b < BPP; ++b) left[b] = cur[i + b] = byte(cur[i + b] + ((left[b] + up[i + b]) >> 1));
            return;
        case 4:
            start([&](int b) { return up[b]; });  // Paeth(0, up, 0) is up
            for (size_t i = from; i < end; i += BPP)
                for (int b = 0; b < BPP; ++b) left[b] = cur[i + b] = byte(cur[i + b] + paeth(left[b], up[i + b], up[i + b - BPP]));
            return;
        default: return;  // 0: nothing to undo
    }
}

// Bytes of a row undone between two looks at the row above: the rows' threads trail each other by this.
// An eighth of a row (a multiple of 64, so of every pixel size; at most 4096): row y may start a chunk
// once row y - 1 has done it, so with n workers a row needs well over n chunks, or the workers wait on
// each other at every chunk (a 16-bit row of 4096 texels was two chunks of 4096 bytes: no slack at all).
size_t unfilterChunk(size_t rowBytes) { return std::clamp<size_t>((rowBytes / 8 + 63) / 64 * 64, 64, 4096); }

#if defined(__SSE2__)
// Paeth-filtered rows side by side, a group of 8 / BPP of them: one 16-bit lane per byte, row k's bytes in
// lanes k BPP .. k BPP + BPP - 1. Step t undoes pixel t - k of every row k (those inside it): each row one
// pixel behind the one above, so the pixel above (b) and above-left (c) of row k's are row k - 1's results
// of the step before and the one before that, already in registers. A row's own chain (a) admits no
// parallelism, but the group's rows run in one vector: on 16-bit grey maps, four rows for one row's time.
template <int BPP>
class PaethLanes {
public:
    static constexpr int kRows = 8 / BPP;

    // rows[k]: row k's bytes (after its filter byte); up: the bytes of the row above row 0.
    PaethLanes(unsigned char* const* rows, const unsigned char* up, int pixels) : up_(up), pixels_(pixels) {
        std::copy_n(rows, kRows, rows_);
    }

    // Steps [from, to), in order over the calls: from 0 up to pixels + kRows - 1 finishes every row.
    void run(int from, int to) {
        const __m128i zero = _mm_setzero_si128(), low = _mm_set1_epi16(0xff);
        auto widen = [&](std::uint64_t bytes) { return _mm_unpacklo_epi8(_mm_cvtsi64_si128(std::int64_t(bytes)), zero); };
        auto abs = [&](__m128i v) { return _mm_max_epi16(v, _mm_sub_epi16(zero, v)); };
        auto select = [](__m128i mask, __m128i yes, __m128i no) { return _mm_or_si128(_mm_and_si128(mask, yes), _mm_andnot_si128(mask, no)); };
        for (int t = from; t < to; ++t) {
            const bool edge = t < kRows - 1 || t >= pixels_;  // a row not started yet, or done
            auto inside = [&](int k) { return !edge || (t - k >= 0 && t - k < pixels_); };
            std::uint64_t filtered = 0, up = 0, upLeft = 0;
            for (int k = 0; k < kRows; ++k) {
                if (!inside(k)) continue;
                std::uint64_t bytes = 0;
                std::memcpy(&bytes, rows_[k] + size_t(t - k) * BPP, BPP);
                filtered |= bytes << (8 * BPP * k);
            }
            if (t < pixels_) std::memcpy(&up, up_ + size_t(t) * BPP, BPP);
            if (t > 0 && t <= pixels_) std::memcpy(&upLeft, up_ + size_t(t - 1) * BPP, BPP);
            const __m128i a = last_;
            const __m128i b = _mm_or_si128(_mm_slli_si128(last_, 2 * BPP), widen(up));
            const __m128i c = _mm_or_si128(_mm_slli_si128(beforeLast_, 2 * BPP), widen(upLeft));
            // paeth() of png_format.hpp, lane by lane: the same choices, ties included.
            const __m128i pa = abs(_mm_sub_epi16(b, c)), pb = abs(_mm_sub_epi16(a, c));
            const __m128i pc = abs(_mm_sub_epi16(_mm_add_epi16(a, b), _mm_add_epi16(c, c)));
            const __m128i ab = select(_mm_cmplt_epi16(pb, pa), b, a);
            const __m128i predicted = select(_mm_cmplt_epi16(pc, _mm_min_epi16(pa, pb)), c, ab);
            // A row not started yet (t < k) reads no bytes and has only zeros above and left of it, so its
            // lanes stay 0 until it starts: its first pixel then sees the zeros the specification puts there.
            const __m128i out = _mm_and_si128(_mm_add_epi16(widen(filtered), predicted), low);
            const std::uint64_t result = std::uint64_t(_mm_cvtsi128_si64(_mm_packus_epi16(out, zero)));
            for (int k = 0; k < kRows; ++k)
                if (inside(k)) std::memcpy(rows_[k] + size_t(t - k) * BPP, reinterpret_cast<const unsigned char*>(&result) + k * BPP, BPP);
            beforeLast_ = last_;
            last_ = out;
        }
    }

private:
    unsigned char* rows_[kRows];
    const unsigned char* up_;
    int pixels_;
    __m128i last_ = _mm_setzero_si128(), beforeLast_ = _mm_setzero_si128();  // the results of steps t - 1, t - 2
};
constexpr bool kPaethLanes = true;
#else
constexpr bool kPaethLanes = false;
#endif

// Undoes the filters (spec section 9). Rows go in groups (8 / BPP rows, where the Paeth lanes are built;
// else 1), worker k of n taking groups k, k + n, ..., a chunk at a time, each chunk once the group above
// has done it: the groups are undone side by side, as one thread would undo them. A group whose rows are
// all Paeth-filtered (what encoders choose for smooth maps) runs its rows in lanes; any other, row by row.
template <int BPP>
bool unfilter(unsigned char* rows, int height, size_t rowBytes, int threads) {
    const size_t stride = rowBytes + 1;
    for (int y = 0; y < height; ++y)
        if (rows[size_t(y) * stride] > 4) return false;  // checked first: no worker stops half way
#if defined(__SSE2__)
    constexpr int groupRows = PaethLanes<BPP>::kRows;
#else
    constexpr int groupRows = 1;
#endif
    const std::vector<unsigned char> zeros(rowBytes, 0);
    const size_t chunk = unfilterChunk(rowBytes);
    const int groups = (height + groupRows - 1) / groupRows, pixels = int(rowBytes / BPP);
    const int workers = std::min(resolveThreadCount(threads), groups);
    std::vector<std::atomic<size_t>> done(static_cast<size_t>(groups));  // bytes of each group's last row undone
    parallelFor(workers, workers, [&](int firstWorker, int lastWorker) {
        for (int worker = firstWorker; worker < lastWorker; ++worker)
            for (int g = worker; g < groups; g += workers) {
                const int y0 = g * groupRows, count = std::min(groupRows, height - y0);
                unsigned char* const first = rows + size_t(y0) * stride;  // its filter byte
                unsigned char* dataOf[groupRows];
                bool paethAll = kPaethLanes && count == groupRows;
                for (int k = 0; k < count; ++k) {
                    dataOf[k] = first + size_t(k) * stride + 1;
                    paethAll = paethAll && dataOf[k][-1] == 4;
                }
                const unsigned char* up = y0 > 0 ? first - rowBytes : zeros.data();
#if defined(__SSE2__)
                PaethLanes<BPP> lanes(dataOf, up, pixels);
#endif
                for (size_t begin = 0; begin < rowBytes; begin += chunk) {
                    const size_t end = std::min(begin + chunk, rowBytes);
                    if (g > 0 && workers > 1) {
                        std::atomic<size_t>& above = done[size_t(g) - 1];
                        for (size_t have; (have = above.load(std::memory_order_acquire)) < end;)
                            above.wait(have, std::memory_order_acquire);
                    }
                    size_t finished = end;
#if defined(__SSE2__)
                    if (paethAll) {
                        // The last row runs groupRows - 1 pixels behind the first: the last chunk finishes it.
                        const int to = end == rowBytes ? pixels + groupRows - 1 : int(end / BPP);
                        lanes.run(int(begin / BPP), to);
                        finished = end == rowBytes ? rowBytes : size_t(std::max(0, to - (groupRows - 1))) * BPP;
                    }
#endif
                    if (!paethAll)
                        for (int k = 0; k < count; ++k) unfilterSpan<BPP>(dataOf[k][-1], dataOf[k], k > 0 ? dataOf[k - 1] : up, begin, end);
                    done[size_t(g)].store(finished, std::memory_order_release);
                    done[size_t(g)].notify_all();
                }
            }
    });
    return true;
}

}  // namespace

bool unfilter(unsigned char* rows, int height, size_t rowBytes, int bpp, int threads) {
    switch (bpp) {
        case 1: return unfilter<1>(rows, height, rowBytes, threads);
        case 2: return unfilter<2>(rows, height, rowBytes, threads);
        case 4: return unfilter<4>(rows, height, rowBytes, threads);
        default: return false;
    }
}

}  // namespace heightpack::detail
