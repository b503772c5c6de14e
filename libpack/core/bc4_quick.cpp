// Eight blocks side by side (see bc4_quick.hpp): a lane per block, the texels a loop. One function
// template holds the whole search, instantiated for four lanes (SSE2 or plain code, run twice) and for
// eight (AVX2, where the processor has it): each lane takes the same operations in the same order in
// both, and no fused multiply-add (AVX2 alone does not enable FMA), so a block's bytes do not depend on
// which runs. Vectors never cross a call (everything, its lambdas too, is inlined into the two entry
// points), so how an AVX vector would be passed does not matter (GCC's and Clang's -Wpsabi).
#include "bc4_quick.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "lanes.hpp"

#pragma GCC diagnostic ignored "-Wpsabi"

namespace heightpack::bc4 {

namespace quick {

// The search for lanes first .. first + W - 1 of b, W the lanes of V (float) and I (int), every step on
// all lanes at once: an endpoint code's value e / 255 and 255 / (e1 - e0) are divided out as a table of
// them would hold them, a fit rounded to codes as int(min(x, 255) + 0.5) in double would round it.
template <class V, class I>
[[gnu::always_inline]] inline void searchLanes(QuickBlocks& b, int first) {
    constexpr int W = int(sizeof(V) / sizeof(float));
    const V zero{}, one = zero + 1.0f;
    const I none{}, codeOne = none + 1;
    auto anyOf = [](const I& mask) {
        for (int l = 0; l < W; ++l)
            if (mask[l]) return true;
        return false;
    };
    V x[16], toFixed[16], scaled[16], lo = one, hi = zero;
    for (int t = 0; t < 16; ++t) {
        if (b.source[0]) {
            // Lane by lane from the image: a copy stored texel by texel just before would stall the vector
            // load (a processor does not forward eight stores to one load).
            const float* texel = b.source[t / 4] + (t % 4) * b.step;
            for (int l = 0; l < W; ++l) x[t][l] = texel[(first + l) * 4 * b.step];
        } else {
            std::memcpy(&x[t], &b.value[t][first], sizeof(V));
        }
        x[t] = x[t] < zero ? zero : x[t] > one ? one : x[t];  // as std::clamp (NaN stays)
        std::memcpy(&b.value[t][first], &x[t], sizeof(V));
        const V rest = 1.0f - x[t];
        toFixed[t] = x[t] < rest ? x[t] : rest;  // the distance to the nearer of 0 and 1
        scaled[t] = x[t] * 255.0f;               // 0..255 units, as least squares fits them
        lo = x[t] < lo ? x[t] : lo, hi = x[t] > hi ? x[t] : hi;
    }
    V sumScaled = zero;
    for (int t = 0; t < 16; ++t) sumScaled += scaled[t];
    // Code x in 0..255 units (NaN and below 0: 0): halves up, as int(x + 0.5) in exact arithmetic.
    auto toEndpoint = [&](const V& x255) {
        const V units = x255 >= zero ? (x255 < 255.0f ? x255 : zero + 255.0f) : zero;
        const I whole = __builtin_convertvector(units, I);
        return whole - (units - __builtin_convertvector(whole, V) >= 0.5f);
    };
    // Each lane's best so far: eight-value mode first, then six-value where it is smaller (equals: eight).
    I bestE0 = none, bestE1 = none;
    V bestError = zero, bestWorst = zero;
    for (int mode = 0; mode < 2; ++mode) {
        const bool eight = mode == 0;
        V modeLo = lo, modeHi = hi;
        I tried = none - 1;
        if (!eight) {
            // The six-value mode's fixed 0 and 1 help blocks with values near them; elsewhere its five steps
            // between the endpoints are coarser than the eight-value mode's seven. Values close to 0 or 1
            // take the fixed codes: the endpoints then span the rest.
            tried = lo < 16.0f / 255.0f || hi > 239.0f / 255.0f;
            if (!anyOf(tried)) break;
            V innerLo = one, innerHi = zero;
            for (int t = 0; t < 16; ++t) {
                const auto inner = x[t] > 0.5f / 255.0f && x[t] < 254.5f / 255.0f;
                innerLo = inner && x[t] < innerLo ? x[t] : innerLo;
                innerHi = inner && x[t] > innerHi ? x[t] : innerHi;
            }
            const auto someInner = innerLo <= innerHi;
            modeLo = someInner ? innerLo : modeLo, modeHi = someInner ? innerHi : modeHi;
        }
        // The pair of codes a, b in the mode's order: eight values need e0 > e1 (equal codes: not valid),
        // six need e0 <= e1.
        I e0, e1, valid;
        auto order = [&](const I& a, const I& c) {
            const I larger = a > c ? a : c, smaller = a > c ? c : a;
            e0 = eight ? larger : smaller, e1 = eight ? smaller : larger;
            valid = eight ? a != c : none - 1;
        };
        // The range's ends, then least squares from the best pair while the rounded fit moves and improves.
        I hiCode = toEndpoint(modeHi * 255.0f), loCode = toEndpoint(modeLo * 255.0f);
        if (eight) {
            const I same = hiCode == loCode, top = hiCode == 255;
            hiCode = same && !top ? hiCode + 1 : hiCode, loCode = same && top ? loCode - 1 : loCode;
        }
        order(hiCode, loCode);
        I active = none - 1, modeE0 = e0, modeE1 = e1;
        const float steps = eight ? 7.0f : 5.0f;
        const V n = zero + steps;
        // Of the best pair: its errors, and the sums its least-squares fit needs over the interpolated
        // texels (k steps from e0 of n, value s in 0..255 units): their count, the sums of k, k^2, k s and s.
        V modeError = zero, modeWorst = zero, fit[5] = {};
        for (int round = -1; round < 3; ++round) {
            if (round >= 0) {
                // The least-squares endpoints (0..255 units) for the best pair's codes: with weights
                // (n - k) / n of e0 and k / n of e1, the normal equations times n^2 have whole-number
                // coefficients (exact in floats): sum (n - k)^2, sum (n - k) k, sum k^2.
                const V count = fit[0], sumK = fit[1], sumKK = fit[2], sumKS = fit[3], sumS = fit[4];
                const V aa = count * (n * n) - 2.0f * n * sumK + sumKK, ab = n * sumK - sumKK, bb = sumKK;
                const V as = n * sumS - sumKS, bs = sumKS;
                const V det = aa * bb - ab * ab;
                const I fitted = det > 0.0f;  // not all texels at one weight
                const V scale = n / det;
                const V a = (as * bb - bs * ab) * scale, c = (bs * aa - as * ab) * scale;
                const I was0 = e0, was1 = e1;
                order(toEndpoint(a), toEndpoint(c));
                active = active && fitted && valid && (e0 != was0 || e1 != was1);
                if (!anyOf(active)) break;
            }
            // Each lane's pair scored: a value's nearest interpolated entry is its rounded position along
            // the pair (k steps from e0), or in the six-value mode the fixed 0 or 1 when nearer; the
            // least-squares sums over the interpolated texels.
            const V at0 = __builtin_convertvector(e0, V) / 255.0f, at1 = __builtin_convertvector(e1, V) / 255.0f;
            const I span = e1 - e0;
            const V step = (at1 - at0) / steps;
            const V perStep = steps * (span == none ? zero : 255.0f / __builtin_convertvector(span, V));
            V squares = zero, worst = zero, sums[5] = {zero + 16.0f, zero, zero, zero, sumScaled};
            for (int t = 0; t < 16; ++t) {
                V k = (x[t] - at0) * perStep;
                k = k > zero ? k : zero;
                k = k < n ? k : n;
                k = __builtin_convertvector(__builtin_convertvector(k + 0.5f, I), V);
                const V off = x[t] - (at0 + k * step);
                V d = off > -off ? off : -off;
                if (!eight) {
                    const auto interpolated = d <= toFixed[t];
                    d = interpolated ? d : toFixed[t];
                    // The texels at the fixed 0 and 1 out of the fit's sums.
                    sums[0] -= interpolated ? zero : one, sums[4] -= interpolated ? zero : scaled[t];
                    k = interpolated ? k : zero;
                }
                squares += d * d;
                worst = d > worst ? d : worst;
                sums[1] += k, sums[2] += k * k, sums[3] += k * scaled[t];
            }
            const I keep = round < 0 ? none - 1 : active && squares < modeError;
            active = active && keep;
            modeError = keep ? squares : modeError, modeWorst = keep ? worst : modeWorst;
            modeE0 = keep ? e0 : modeE0, modeE1 = keep ? e1 : modeE1;
            for (int s = 0; s < 5; ++s) fit[s] = keep ? sums[s] : fit[s];
        }
        const I take = eight ? none - 1 : tried && modeError < bestError;
        bestE0 = take ? modeE0 : bestE0, bestE1 = take ? modeE1 : bestE1;
        bestError = take ? modeError : bestError, bestWorst = take ? modeWorst : bestWorst;
    }
    // The chosen pairs' codes and decoded values: code 0 at e0, 1 at e1, k + 1 between (both modes); in the
    // six-value mode 6 for the fixed 0 and 7 for the fixed 1 where nearer.
    const I six = bestE0 <= bestE1, span = bestE1 - bestE0;
    const V steps = six ? zero + 5.0f : zero + 7.0f;
    const V at0 = __builtin_convertvector(bestE0, V) / 255.0f, at1 = __builtin_convertvector(bestE1, V) / 255.0f;
    const V step = (at1 - at0) / steps, perStep = steps * (span == none ? zero : 255.0f / __builtin_convertvector(span, V));
    std::memcpy(&b.e0[first], &bestE0, sizeof bestE0);
    std::memcpy(&b.e1[first], &bestE1, sizeof bestE1);
    std::memcpy(&b.error[first], &bestError, sizeof bestError);
    std::memcpy(&b.worst[first], &bestWorst, sizeof bestWorst);
    for (int t = 0; t < 16; ++t) {
        V k = (x[t] - at0) * perStep;
        k = k > zero ? k : zero;
        k = k < steps ? k : steps;
        k = __builtin_convertvector(__builtin_convertvector(k + 0.5f, I), V);
        V value = at0 + k * step;
        const I stepsAlong = __builtin_convertvector(k, I);
        I code = stepsAlong == none ? none : k == steps ? codeOne : stepsAlong + codeOne;
        const V off = x[t] - value, d = off > -off ? off : -off;
        const I toZero = six & (x[t] < d), toOne = six & ((1.0f - x[t]) < (d < x[t] ? d : x[t]));
        value = toOne ? one : toZero ? zero : value;
        code = toOne ? none + 7 : toZero ? none + 6 : code;
        std::memcpy(&b.decoded[t][first], &value, sizeof value);
        for (int l = 0; l < W; ++l) b.code[t][first + l] = std::uint8_t(code[l]);
    }
}

// quickWorstChords for lanes first .. first + W - 1.
template <class V>
[[gnu::always_inline]] inline void chordLanes(const QuickBlocks& bx, const QuickBlocks& by, float offset, float scale, float* worstOut, int first) {
    constexpr int W = int(sizeof(V) / sizeof(float));
    const V zero{};
    auto sqrtOf = [](const V& a) {
        V r;
        for (int l = 0; l < W; ++l) r[l] = std::sqrt(a[l]);
        return r;
    };
    auto rebuilt = [&](const V& x, const V& y, V n[3]) {
        const V rr = x * x + y * y, rest = 1.0f - rr;
        const V s = rr > 1.0f ? 1.0f / sqrtOf(rr) : zero + 1.0f;
        n[0] = x * s, n[1] = y * s, n[2] = sqrtOf(rest > zero ? rest : zero);
    };
    V worst = zero;
    for (int t = 0; t < 16; ++t) {
        V gx, gy, dx, dy, g[3], d[3];
        std::memcpy(&gx, &bx.value[t][first], sizeof gx);
        std::memcpy(&gy, &by.value[t][first], sizeof gy);
        std::memcpy(&dx, &bx.decoded[t][first], sizeof dx);
        std::memcpy(&dy, &by.decoded[t][first], sizeof dy);
        rebuilt(offset + scale * gx, offset + scale * gy, g);
        rebuilt(offset + scale * dx, offset + scale * dy, d);
        const V ex = d[0] - g[0], ey = d[1] - g[1], ez = d[2] - g[2];
        const V chord = sqrtOf(ex * ex + ey * ey + ez * ez);
        worst = worst > chord ? worst : chord;
    }
    std::memcpy(worstOut + first, &worst, sizeof worst);
}

}  // namespace quick

[[gnu::flatten]] void quickSearchPortable(QuickBlocks& blocks) {
    for (int first = 0; first < kQuickBlocks; first += 4) quick::searchLanes<lanes::Lanes, lanes::IntLanes>(blocks, first);
}

#if defined(__x86_64__)
// Whether the processor runs AVX2 (asked once).
static bool hasAvx2() {
    static const bool avx2 = __builtin_cpu_supports("avx2");
    return avx2;
}

using Lanes8 = float __attribute__((vector_size(32)));
using IntLanes8 = int __attribute__((vector_size(32)));
[[gnu::flatten, gnu::target("avx2")]] static void quickSearchAvx2(QuickBlocks& blocks) {
    quick::searchLanes<Lanes8, IntLanes8>(blocks, 0);
}
#endif

[[gnu::flatten]] void quickWorstChordsPortable(const QuickBlocks& x, const QuickBlocks& y, float offset, float scale, float worst[kQuickBlocks]) {
    for (int first = 0; first < kQuickBlocks; first += 4) quick::chordLanes<lanes::Lanes>(x, y, offset, scale, worst, first);
}

#if defined(__x86_64__)
[[gnu::flatten, gnu::target("avx2")]] static void quickChordsAvx2(const QuickBlocks& x, const QuickBlocks& y, float offset, float scale,
                                                                 float* worst) {
    quick::chordLanes<Lanes8>(x, y, offset, scale, worst, 0);
}
#endif

void quickWorstChords(const QuickBlocks& x, const QuickBlocks& y, float offset, float scale, float worst[kQuickBlocks]) {
#if defined(__x86_64__)
    if (hasAvx2()) return quickChordsAvx2(x, y, offset, scale, worst);
#endif
    quickWorstChordsPortable(x, y, offset, scale, worst);
}

void quickSearch(QuickBlocks& blocks) {
#if defined(__x86_64__)
    if (hasAvx2()) return quickSearchAvx2(blocks);
#endif
    quickSearchPortable(blocks);
}

}  // namespace heightpack::bc4
