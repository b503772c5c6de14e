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
#include <cstring>
#include <utility>

namespace heightpack::bc4 {

namespace {

using namespace lanes;

// A block's values as rows of lanes, each value's distance to the nearer of 0 and 1, and their range.
struct Block {
    Lanes row[4], toFixed[4], scaled[4];  // scaled: in 0..255 units, as least squares fits them
    float lo = 1.0f, hi = 0.0f;
    explicit Block(const float v[16]) {
        const Rows rows(v);
        for (int r = 0; r < 4; ++r) row[r] = rows.row[r], toFixed[r] = min(row[r], 1.0f - row[r]), scaled[r] = row[r] * 255.0f;
        // A tree of four-lane minima and maxima: no chain of 16 (the least and largest do not depend on order).
        lo = smallest(min(min(min(row[0], row[1]), min(row[2], row[3])), splat(1.0f)));
        hi = largest(max(max(max(row[0], row[1]), max(row[2], row[3])), splat(0.0f)));
    }
};

// How far above the smallest worst error a candidate may go for a smaller squared error: a quarter code.
// The block's worst texel decides a map's worst error, its squared error the RMS: the smallest squared
// error alone gives a smaller RMS than encoders that quantise first but at times a larger worst.
constexpr float kWorstSlack = 0.25f / 255.0f;

// Endpoint codes as values, and the reciprocals of their differences: no division per pair scored.
struct Tables {
    float unit[256];
    float perCode[511];  // 255 / (e1 - e0) at e1 - e0 + 255; 0 at equal endpoints
    Tables() {
        for (int e = 0; e < 256; ++e) unit[e] = float(e) / 255.0f;
        for (int d = -255; d <= 255; ++d) perCode[d + 255] = d == 0 ? 0.0f : 255.0f / float(d);
    }
};
const Tables kTables;

// The squared error and worst error of the values decoded with e0, e1: each value's nearest interpolated
// entry is its rounded position along them (they are evenly spaced), and in the six-value mode the fixed
// 0 or 1 when nearer. The sums run in a fixed order, so a block scores the same on any thread.
Tried score(const Block& v, int e0, int e1) {
    const bool eight = e0 > e1;
    const float steps = eight ? 7.0f : 5.0f;
    const float r0 = kTables.unit[e0], perStep = steps * kTables.perCode[e1 - e0 + 255];
    const Lanes at0 = splat(r0), step = splat((kTables.unit[e1] - r0) / steps), n = splat(steps), zero = splat(0.0f);
    Lanes squares = zero, worst = zero;
    for (int r = 0; r < 4; ++r) {
        const Lanes x = v.row[r];
        const Lanes k = roundUp(min(max((x - at0) * perStep, zero), n));
        Lanes d = abs(x - (at0 + k * step));
        if (!eight) d = min(d, v.toFixed[r]);
        squares += d * d;
        worst = max(worst, d);
    }
    return {e0, e1, sum(squares), largest(worst)};
}

// The least worst error e0, e1 can have: the values beyond their range are at least as far from the
// nearest endpoint (or, in the six-value mode, from 0 or 1).
float worstBound(const Block& v, int e0, int e1) {
    const float top = kTables.unit[std::max(e0, e1)], bottom = kTables.unit[std::min(e0, e1)];
    float above = std::max(v.hi - top, 0.0f), below = std::max(bottom - v.lo, 0.0f);
    if (e0 <= e1) above = std::min(above, std::min(1.0f - v.hi, v.hi)), below = std::min(below, std::min(v.lo, 1.0f - v.lo));
    return std::max(above, below);
}

// Whether choose could take e0, e1 when out keeps only what it could: their least worst error is within
// kWorstSlack of the least so far (and a float's rounding: the bound and the score sum differently).
bool worthScoring(const Block& v, int e0, int e1, const Candidates& out) {
    return !out.onlyChoosable || worstBound(v, e0, e1) <= out.leastWorst + kWorstSlack + 1e-6f;
}

// The least-squares fit of a block's values (in 0..255 units) to the codes that e0, e1 give them (as score
// assigns them, but through its own reciprocal of the pair's span; the six-value mode's fixed 0 and 1
// take no part): where a row goes along the pair, and the sums of its weights and values.
struct FitAlong {
    bool eight;
    Lanes at0, at1, n, inv, perStep;
    FitAlong(int e0, int e1) {
        const float r0 = kTables.unit[e0], r1 = kTables.unit[e1];  // e / 255.0f
        eight = e0 > e1;
        const float steps = eight ? 7.0f : 5.0f;
        at0 = splat(r0), at1 = splat(r1), n = splat(steps), inv = splat(eight ? 1.0f / 7.0f : 1.0f / 5.0f);
        perStep = splat(e0 == e1 ? 0.0f : steps / (r1 - r0));
    }
};
struct FitSums {
    float aa, ab, bb, av, bv;
};

// Row r of v (at `along` from e0) added to the sums aa, ab, bb, av, bv (in that order in sums).
inline void addFitRow(const FitAlong& f, const Block& v, int r, Lanes along, Lanes sums[5]) {
    const Lanes x = v.row[r], zero = splat(0.0f);
    const Lanes k = roundUp(min(max(along * f.perStep, zero), f.n));
    Lanes w = k * f.inv, u = 1.0f - w;
    if (!f.eight) {
        const auto interpolated = abs(x - (f.at0 * (f.n - k) + f.at1 * k) * f.inv) <= v.toFixed[r];
        w = interpolated ? w : zero, u = interpolated ? u : zero;
    }
    sums[0] += u * u, sums[1] += u * w, sums[2] += w * w, sums[3] += u * v.scaled[r], sums[4] += w * v.scaled[r];
}

FitSums summed(const Lanes sums[5]) { return {sum(sums[0]), sum(sums[1]), sum(sums[2]), sum(sums[3]), sum(sums[4])}; }

// The fitted endpoints (0..255 units, unrounded), or false when the codes give no fit.
bool solve(const FitSums& s, double& a, double& b) {
    const float det = s.aa * s.bb - s.ab * s.ab;
    if (det <= 1e-4f * s.aa * s.bb) return false;  // all texels at one weight, but for rounding
    const float inverse = 1.0f / det;
    a = (s.av * s.bb - s.bv * s.ab) * inverse;
    b = (s.bv * s.aa - s.av * s.ab) * inverse;
    return true;
}

bool leastSquares(const Block& v, int e0, int e1, double& a, double& b) {
    const FitAlong f(e0, e1);
    Lanes sums[5] = {};
    for (int r = 0; r < 4; ++r) addFitRow(f, v, r, v.row[r] - f.at0, sums);
    return solve(summed(sums), a, b);
}

// score and the least-squares sums of the same pair in one pass over the values (each with its own
// operations, so both are exactly theirs): the search fits each pair it keeps as best.
Tried scoreAndFit(const Block& v, int e0, int e1, FitSums& fit) {
    const bool eight = e0 > e1;
    const float steps = eight ? 7.0f : 5.0f;
    const float r0 = kTables.unit[e0], perStep = steps * kTables.perCode[e1 - e0 + 255];
    const Lanes at0 = splat(r0), step = splat((kTables.unit[e1] - r0) / steps), n = splat(steps), zero = splat(0.0f);
    const FitAlong f(e0, e1);
    Lanes squares = zero, worst = zero, sums[5] = {};
    for (int r = 0; r < 4; ++r) {
        const Lanes x = v.row[r], along = x - at0;
        const Lanes k = roundUp(min(max(along * perStep, zero), n));
        Lanes d = abs(x - (at0 + k * step));
        if (!eight) d = min(d, v.toFixed[r]);
        squares += d * d;
        worst = max(worst, d);
        addFitRow(f, v, r, along, sums);
    }
    fit = summed(sums);
    return {e0, e1, sum(squares), largest(worst)};
}

// How far from the range's ends, and from the least-squares fit, the endpoint pairs tried go, in codes.
struct Windows {
    int range, fit;
};
constexpr Windows kThorough{1, 2};

int toEndpoint(double x) { return x >= 0.0 ? int(std::min(x, 255.0) + 0.5) : 0; }  // NaN: 0

// The candidates of one mode: eight values (e0 > e1) or six with 0 and 1 (e0 <= e1). Every pair within
// window.range of the values' range (the six-value mode's without those nearer 0 or 1 than to it), and
// within window.fit of the least-squares endpoints for the best codes of those.
void fitMode(const Block& rows, bool eightValues, Windows window, Candidates& out) {
    float lo = rows.lo, hi = rows.hi;
    if (!eightValues) {
        // Values close to 0 or 1 can take the fixed codes: the endpoints then span the rest.
        Lanes innerLo = splat(1.0f), innerHi = splat(0.0f);
        for (const Lanes& x : rows.row) {
            const auto inner = x > 0.5f / 255.0f && x < 254.5f / 255.0f;
            innerLo = min(innerLo, inner ? x : splat(1.0f)), innerHi = max(innerHi, inner ? x : splat(0.0f));
        }
        if (smallest(innerLo) <= largest(innerHi)) lo = smallest(innerLo), hi = largest(innerHi);
    }
    auto ordered = [&](int a, int b) {
        // Eight values need e0 > e1: the larger endpoint first; six need e0 <= e1.
        if (eightValues) {
            if (a == b) return std::pair{-1, -1};
            return a > b ? std::pair{a, b} : std::pair{b, a};
        }
        return a <= b ? std::pair{a, b} : std::pair{b, a};
    };
    // Each pair tried is added to out; the one of least squared error is kept in best. The last pair
    // scored is kept too: the window around the fit starts at it, and scores are not worked out twice.
    // With it, the least-squares sums of the last pair when it was scored with them (withSums).
    Tried best{}, last{-1, -1, 0.0f, 0.0f};
    FitSums lastFit{};
    bool any = false, lastHasFit = false;
    auto scored = [&](int e0, int e1, bool withSums) {
        if (e0 != last.e0 || e1 != last.e1) {
            last = withSums ? scoreAndFit(rows, e0, e1, lastFit) : score(rows, e0, e1);
            lastHasFit = withSums;
        }
        return last;
    };
    // Every pair within r of (c0, c1) but those within skipR of (skip0, skip1), a window already tried.
    auto around = [&](int c0, int c1, int r, int skip0, int skip1, int skipR) {
        for (int d0 = -r; d0 <= r; ++d0)
            for (int d1 = -r; d1 <= r; ++d1) {
                const int a = c0 + d0, b = c1 + d1;
                if (a < 0 || a > 255 || b < 0 || b > 255) continue;
                if (std::abs(a - skip0) <= skipR && std::abs(b - skip1) <= skipR) continue;
                const auto [e0, e1] = ordered(a, b);
                if (e0 < 0 || !worthScoring(rows, e0, e1, out)) continue;
                const Tried t = scored(e0, e1, r == 0);  // a window of one: least squares starts from it
                out.add(t);
                if (!any || t.error < best.error) best = t, any = true;
            }
    };
    int hiCode = toEndpoint(hi * 255.0f), loCode = toEndpoint(lo * 255.0f);
    if (eightValues && hiCode == loCode) hiCode < 255 ? ++hiCode : --loCode;
    around(hiCode, loCode, window.range, -99, -99, 0);  // the range's ends: what bounds the worst error
    if (!any) return;
    // Least squares from the best codes so far, until the rounded endpoints stop moving. A round that
    // does not improve on best ends it: the next would fit the same codes to the same endpoints.
    int e0 = best.e0, e1 = best.e1;
    for (int round = 0; round < 3; ++round) {
        double a, b;
        const bool fitted = lastHasFit && best.e0 == last.e0 && best.e1 == last.e1 ? solve(lastFit, a, b)
                                                                                 : leastSquares(rows, best.e0, best.e1, a, b);
        if (!fitted) break;
        const auto [n0, n1] = ordered(toEndpoint(a), toEndpoint(b));
        if (n0 < 0 || (n0 == e0 && n1 == e1)) break;
        e0 = n0, e1 = n1;
        if (!worthScoring(rows, e0, e1, out)) break;
        const Tried t = scored(e0, e1, true);
        if (!(t.error < best.error)) break;
        best = t;
    }
    // The window around the fit, less what the first window tried (in either order of the endpoints).
    if (eightValues ? e0 > e1 : e0 <= e1)
        around(e0, e1, window.fit, eightValues ? hiCode : loCode, eightValues ? loCode : hiCode, window.range);
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
    const Block rows(v);
    const Windows window = kThorough;
    fitMode(rows, true, window, out);
    // The six-value mode's fixed 0 and 1 help a block with values near them; elsewhere its five steps
    // between the endpoints are coarser than the eight-value mode's seven, and it is not tried.
    if (rows.lo < 16.0f / 255.0f || rows.hi > 239.0f / 255.0f || out.count == 0) fitMode(rows, false, window, out);
}

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

std::array<std::uint8_t, 16> codesOf(const float v[16], int e0, int e1, float decoded[16]) {
    const bool eight = e0 > e1;
    const float steps = eight ? 7.0f : 5.0f;
    const float r0 = kTables.unit[e0], perStep = steps * kTables.perCode[e1 - e0 + 255];
    const Lanes at0 = splat(r0), step = splat((kTables.unit[e1] - r0) / steps), n = splat(steps), zero = splat(0.0f);
    const IntLanes none{0, 0, 0, 0}, one{1, 1, 1, 1}, six{6, 6, 6, 6}, seven{7, 7, 7, 7};
    const Rows rows(v);
    std::array<std::uint8_t, 16> codes{};
    for (int r = 0; r < 4; ++r) {
        const Lanes x = rows.row[r];
        const Lanes k = roundUp(min(max((x - at0) * perStep, zero), n));
        Lanes value = at0 + k * step;
        // The code at step k from e0: 0 at e0, 1 at e1, k + 1 between (both modes).
        const IntLanes steps = __builtin_convertvector(k, IntLanes);
        IntLanes code = steps == none ? none : k == n ? one : steps + one;
        if (!eight) {
            // The six-value mode's fixed 0 (code 6) when nearer, then its 1 (code 7) when nearer still.
            const Lanes d = abs(x - value);
            const IntLanes toZero = x < d, toOne = (1.0f - x) < min(d, x);
            value = toOne ? splat(1.0f) : toZero ? zero : value;
            code = toOne ? seven : toZero ? six : code;
        }
        for (int i = 0; i < 4; ++i) codes[size_t(4 * r + i)] = std::uint8_t(code[i]);
        if (decoded) std::memcpy(decoded + 4 * r, &value, sizeof value);
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
