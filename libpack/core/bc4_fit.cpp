// Fitting each mode's endpoints to the float values (not to values rounded to 8 bits first) and searching
// the neighbouring endpoint pairs by the decoded error is what makes the encoder at least as accurate as
// encoders that quantise the input to 8 bits, in RMS and in the worst error (see choose). A pair is
// scored without keeping its codes, four texels at a time (GCC's vector extension: SSE2 on x86-64, plain
// code elsewhere); only the chosen pair's codes are written.
#include "bc4_fit.hpp"

#include "lanes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>

namespace heightpack::bc4 {

namespace {

using namespace lanes;

// The squared error and worst error of the values decoded with e0, e1: each value's nearest interpolated
// entry is its rounded position along them (they are evenly spaced), and in the six-value mode the fixed
// 0 or 1 when nearer. The sums run in a fixed order, so a block scores the same on any thread.
Tried score(const Rows& v, int e0, int e1) {
    const float r0 = float(e0) / 255.0f, r1 = float(e1) / 255.0f;
    const bool eight = e0 > e1;
    const float steps = eight ? 7.0f : 5.0f;
    const float perStep = e0 == e1 ? 0.0f : steps / (r1 - r0);
    const Lanes at0 = splat(r0), at1 = splat(r1), n = splat(steps), inv = splat(1.0f / steps);
    Lanes squares = splat(0.0f), worst = splat(0.0f);
    for (const Lanes& x : v.row) {
        const Lanes k = roundUp(min(max((x - at0) * perStep, splat(0.0f)), n));
        Lanes d = abs(x - (at0 * (n - k) + at1 * k) * inv);
        if (!eight) d = min(d, min(x, 1.0f - x));
        squares += d * d;
        worst = max(worst, d);
    }
    return {e0, e1, sum(squares), largest(worst)};
}

// Where code k sits between the endpoints (0 at e0, 1 at e1) in a mode of `steps` intervals; -1 for the
// six-value mode's fixed 0 and 1.
double weightOf(int code, int steps) {
    if (code == 0) return 0.0;
    if (code == 1) return 1.0;
    if (code > steps) return -1.0;
    return double(code - 1) / steps;
}

// The endpoints (in 0..255 units, unrounded) that fit v best by least squares for the codes of e0, e1.
bool leastSquares(const float v[16], int e0, int e1, int steps, double& a, double& b) {
    const std::array<std::uint8_t, 16> codes = codesOf(v, e0, e1);
    double aa = 0, ab = 0, bb = 0, av = 0, bv = 0;
    for (int i = 0; i < 16; ++i) {
        const double w = weightOf(codes[size_t(i)], steps);
        if (w < 0.0) continue;
        const double x = double(v[i]) * 255.0;
        aa += (1 - w) * (1 - w), ab += (1 - w) * w, bb += w * w;
        av += (1 - w) * x, bv += w * x;
    }
    const double det = aa * bb - ab * ab;
    if (std::fabs(det) < 1e-12) return false;
    a = (av * bb - bv * ab) / det;
    b = (bv * aa - av * ab) / det;
    return true;
}

// How far from the range's ends, and from the least-squares fit, the endpoint pairs tried go, in codes.
constexpr int kRangeWindow = 1, kFitWindow = 2;

int toEndpoint(double x) { return int(std::clamp(std::lround(x), 0L, 255L)); }

// The candidates of one mode: eight values (e0 > e1) or six with 0 and 1 (e0 <= e1). Every pair within
// kRangeWindow of the values' range (the six-value mode's without those nearer 0 or 1 than to it), and
// within kFitWindow of the least-squares endpoints for the best codes of those.
void fitMode(const float v[16], const Rows& rows, bool eightValues, Candidates& out) {
    float lo = 1.0f, hi = 0.0f;
    for (int i = 0; i < 16; ++i) lo = std::min(lo, v[i]), hi = std::max(hi, v[i]);
    if (!eightValues) {
        // Values close to 0 or 1 can take the fixed codes: the endpoints then span the rest.
        float innerLo = 1.0f, innerHi = 0.0f;
        for (int i = 0; i < 16; ++i)
            if (v[i] > 0.5f / 255.0f && v[i] < 254.5f / 255.0f) innerLo = std::min(innerLo, v[i]), innerHi = std::max(innerHi, v[i]);
        if (innerLo <= innerHi) lo = innerLo, hi = innerHi;
    }
    const int steps = eightValues ? 7 : 5;
    auto ordered = [&](int a, int b) {
        // Eight values need e0 > e1: the larger endpoint first; six need e0 <= e1.
        if (eightValues) {
            if (a == b) return std::pair{-1, -1};
            return a > b ? std::pair{a, b} : std::pair{b, a};
        }
        return a <= b ? std::pair{a, b} : std::pair{b, a};
    };
    // Each pair tried is added to out; the one of least squared error is kept in best.
    Tried best;
    bool any = false;
    // Every pair within r of (c0, c1) but those within skipR of (skip0, skip1), a window already tried.
    auto around = [&](int c0, int c1, int r, int skip0, int skip1, int skipR) {
        for (int d0 = -r; d0 <= r; ++d0)
            for (int d1 = -r; d1 <= r; ++d1) {
                const int a = c0 + d0, b = c1 + d1;
                if (a < 0 || a > 255 || b < 0 || b > 255) continue;
                if (std::abs(a - skip0) <= skipR && std::abs(b - skip1) <= skipR) continue;
                const auto [e0, e1] = ordered(a, b);
                if (e0 < 0) continue;
                const Tried t = score(rows, e0, e1);
                out.add(t);
                if (!any || t.error < best.error) best = t, any = true;
            }
    };
    int hiCode = toEndpoint(double(hi) * 255.0), loCode = toEndpoint(double(lo) * 255.0);
    if (eightValues && hiCode == loCode) hiCode < 255 ? ++hiCode : --loCode;
    around(hiCode, loCode, kRangeWindow, -99, -99, 0);  // the range's ends: what bounds the worst error
    if (!any) return;
    // Least squares from the best codes so far, until the rounded endpoints stop moving.
    int e0 = best.e0, e1 = best.e1;
    for (int round = 0; round < 3; ++round) {
        double a, b;
        if (!leastSquares(v, best.e0, best.e1, steps, a, b)) break;
        const auto [n0, n1] = ordered(toEndpoint(a), toEndpoint(b));
        if (n0 < 0 || (n0 == e0 && n1 == e1)) break;
        e0 = n0, e1 = n1;
        const Tried t = score(rows, e0, e1);
        if (t.error < best.error) best = t;
    }
    // The window around the fit, less what the first window tried (in either order of the endpoints).
    if (eightValues ? e0 > e1 : e0 <= e1)
        around(e0, e1, kFitWindow, eightValues ? hiCode : loCode, eightValues ? loCode : hiCode, kRangeWindow);
}

}  // namespace

std::array<float, 8> palette(int e0, int e1) {
    const float r0 = float(e0) / 255.0f, r1 = float(e1) / 255.0f;
    std::array<float, 8> p{r0, r1};
    if (e0 > e1) {
        for (int k = 2; k < 8; ++k) p[size_t(k)] = (float(8 - k) * r0 + float(k - 1) * r1) / 7.0f;
    } else {
        for (int k = 2; k < 6; ++k) p[size_t(k)] = (float(6 - k) * r0 + float(k - 1) * r1) / 5.0f;
        p[6] = 0.0f;
        p[7] = 1.0f;
    }
    return p;
}

void search(const float v[16], Candidates& out) {
    const Rows rows(v);
    fitMode(v, rows, true, out);
    // The six-value mode's fixed 0 and 1 help a block with values near them; elsewhere its five steps
    // between the endpoints are coarser than the eight-value mode's seven, and it is not tried.
    float lo = 1.0f, hi = 0.0f;
    for (int i = 0; i < 16; ++i) lo = std::min(lo, v[i]), hi = std::max(hi, v[i]);
    if (lo < 16.0f / 255.0f || hi > 239.0f / 255.0f || out.count == 0) fitMode(v, rows, false, out);
}

// How far above the smallest worst error a candidate may go for a smaller squared error: a quarter code.
// The block's worst texel decides a map's worst error, its squared error the RMS: the smallest squared
// error alone gives a smaller RMS than encoders that quantise first but at times a larger worst.
constexpr float kWorstSlack = 0.25f / 255.0f;

const Tried& choose(const Candidates& c) {
    float leastWorst = c.tried[0].worst;
    for (int i = 1; i < c.count; ++i) leastWorst = std::min(leastWorst, c.tried[size_t(i)].worst);
    const Tried* best = nullptr;
    for (int i = 0; i < c.count; ++i) {
        const Tried& t = c.tried[size_t(i)];
        if (t.worst <= leastWorst + kWorstSlack && (!best || t.error < best->error)) best = &t;
    }
    return *best;
}

std::array<std::uint8_t, 16> codesOf(const float v[16], int e0, int e1) {
    static constexpr std::uint8_t kEightOrder[8] = {0, 2, 3, 4, 5, 6, 7, 1};  // code at each step from e0
    static constexpr std::uint8_t kSixOrder[6] = {0, 2, 3, 4, 5, 1};
    const std::array<float, 8> p = palette(e0, e1);
    const bool eight = e0 > e1;
    const int steps = eight ? 7 : 5;
    const std::uint8_t* order = eight ? kEightOrder : kSixOrder;
    const float perStep = e0 == e1 ? 0.0f : float(steps) / (p[1] - p[0]);
    std::array<std::uint8_t, 16> codes{};
    for (int i = 0; i < 16; ++i) {
        const float t = std::clamp((v[i] - p[0]) * perStep, 0.0f, float(steps));
        std::uint8_t code = order[int(t + 0.5f)];
        float error = std::fabs(v[i] - p[code]);
        if (!eight) {
            if (v[i] < error) error = v[i], code = 6;                 // the fixed 0
            if (1.0f - v[i] < error) error = 1.0f - v[i], code = 7;  // the fixed 1
        }
        codes[size_t(i)] = code;
    }
    return codes;
}

void writeBlock(int e0, int e1, const std::array<std::uint8_t, 16>& codes, std::uint8_t* out) {
    out[0] = std::uint8_t(e0);
    out[1] = std::uint8_t(e1);
    std::uint64_t bits = 0;
    for (int i = 0; i < 16; ++i) bits |= std::uint64_t(codes[size_t(i)]) << (3 * i);
    for (int i = 0; i < 6; ++i) out[2 + i] = std::uint8_t(bits >> (8 * i));
}

}  // namespace heightpack::bc4
