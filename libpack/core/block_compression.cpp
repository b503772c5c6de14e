// A BC4 encoder from float values. Fitting each mode's endpoints to the float values (not to values
// rounded to 8 bits first) and searching the neighbouring endpoint pairs by the decoded error is what
// makes it at least as accurate as encoders that quantise the input to 8 bits, in RMS and in the worst
// error (see choose). BC5 normals choose x and y together, by the angle (see encodeBc5Block).
#include "heightpack/core/block_compression.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <utility>

#include "heightpack/core/astc_compression.hpp"
#include "heightpack/core/parallel.hpp"

namespace heightpack {

namespace {

// The 8 decoded values of a block with endpoints e0, e1 (codes 0..7), as decodeBc4Block computes them.
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

// A block's endpoints, the codes of its 16 texels, the squared error they decode with and the worst.
struct Fit {
    int e0 = 0, e1 = 0;
    std::array<std::uint8_t, 16> codes{};
    double error = 0.0;
    float worst = 0.0f;
};

// The endpoint pairs tried for a block, in the order tried.
struct Candidates {
    std::array<Fit, 128> fits;
    int count = 0;
    void add(const Fit& f) {
        if (count < int(fits.size())) fits[size_t(count++)] = f;
    }
};

// How far above the smallest worst error a candidate may go for a smaller squared error: a quarter code.
// The block's worst texel decides a map's worst error, its squared error the RMS: the smallest squared
// error alone gives a smaller RMS than encoders that quantise first but at times a larger worst.
constexpr float kWorstSlack = 0.25f / 255.0f;

// The candidate with the smallest squared error among those whose worst error is within kWorstSlack of
// the smallest worst; the first of equals.
const Fit& choose(const Candidates& c) {
    float leastWorst = c.fits[0].worst;
    for (int i = 1; i < c.count; ++i) leastWorst = std::min(leastWorst, c.fits[size_t(i)].worst);
    const Fit* best = nullptr;
    for (int i = 0; i < c.count; ++i) {
        const Fit& f = c.fits[size_t(i)];
        if (f.worst <= leastWorst + kWorstSlack && (!best || f.error < best->error)) best = &f;
    }
    return *best;
}

// The nearest of the palette's interpolated entries to each value (and, in the six-value mode, of 0 and 1),
// and the squared error. The interpolated entries are evenly spaced from e0 to e1, so the nearest is the
// rounded position along them: no search through the palette.
Fit assign(const float v[16], int e0, int e1) {
    static constexpr std::uint8_t kEightOrder[8] = {0, 2, 3, 4, 5, 6, 7, 1};  // code at each step from e0
    static constexpr std::uint8_t kSixOrder[6] = {0, 2, 3, 4, 5, 1};
    const std::array<float, 8> p = palette(e0, e1);
    const bool eight = e0 > e1;
    const int steps = eight ? 7 : 5;
    const std::uint8_t* order = eight ? kEightOrder : kSixOrder;
    const float perStep = e0 == e1 ? 0.0f : float(steps) / (p[1] - p[0]);
    Fit fit{e0, e1, {}, 0.0};
    for (int i = 0; i < 16; ++i) {
        const float t = std::clamp((v[i] - p[0]) * perStep, 0.0f, float(steps));
        std::uint8_t code = order[int(t + 0.5f)];
        float error = std::fabs(v[i] - p[code]);
        if (!eight) {
            if (v[i] < error) error = v[i], code = 6;                 // the fixed 0
            if (1.0f - v[i] < error) error = 1.0f - v[i], code = 7;  // the fixed 1
        }
        fit.codes[size_t(i)] = code;
        fit.error += double(error) * error;
        fit.worst = std::max(fit.worst, error);
    }
    return fit;
}

// Where code k sits between the endpoints (0 at e0, 1 at e1) in a mode of `steps` intervals; -1 for the
// six-value mode's fixed 0 and 1.
double weightOf(int code, int steps) {
    if (code == 0) return 0.0;
    if (code == 1) return 1.0;
    if (code > steps) return -1.0;
    return double(code - 1) / steps;
}

// The endpoints (in 0..255 units, unrounded) that fit v best by least squares for the codes given.
bool leastSquares(const float v[16], const Fit& fit, int steps, double& a, double& b) {
    double aa = 0, ab = 0, bb = 0, av = 0, bv = 0;
    for (int i = 0; i < 16; ++i) {
        const double w = weightOf(fit.codes[size_t(i)], steps);
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
void fitMode(const float v[16], bool eightValues, Candidates& out) {
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
    Fit best;
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
                const Fit f = assign(v, e0, e1);
                out.add(f);
                if (!any || f.error < best.error) best = f, any = true;
            }
    };
    int hiCode = toEndpoint(double(hi) * 255.0), loCode = toEndpoint(double(lo) * 255.0);
    if (eightValues && hiCode == loCode) hiCode < 255 ? ++hiCode : --loCode;
    around(hiCode, loCode, kRangeWindow, -99, -99, 0);  // the range's ends: what bounds the worst error
    if (!any) return;
    // Least squares from the best codes so far, until the rounded endpoints stop moving.
    int e0 = best.e0, e1 = best.e1;
    const auto [first0, first1] = std::pair{hiCode, loCode};
    for (int round = 0; round < 3; ++round) {
        double a, b;
        if (!leastSquares(v, best, steps, a, b)) break;
        const auto [n0, n1] = ordered(toEndpoint(a), toEndpoint(b));
        if (n0 < 0 || (n0 == e0 && n1 == e1)) break;
        e0 = n0, e1 = n1;
        const Fit f = assign(v, e0, e1);
        if (f.error < best.error) best = f;
    }
    // The window around the fit, less what the first window tried (in either order of the endpoints).
    if (eightValues ? e0 > e1 : e0 <= e1) around(e0, e1, kFitWindow, eightValues ? first0 : first1, eightValues ? first1 : first0, kRangeWindow);
}

void candidatesOf(const float v[16], float clamped[16], Candidates& candidates) {
    for (int i = 0; i < 16; ++i) clamped[i] = std::clamp(v[i], 0.0f, 1.0f);
    fitMode(clamped, true, candidates);
    // The six-value mode's fixed 0 and 1 help a block with values near them; elsewhere its five steps
    // between the endpoints are coarser than the eight-value mode's seven, and it is not tried.
    float lo = 1.0f, hi = 0.0f;
    for (int i = 0; i < 16; ++i) lo = std::min(lo, clamped[i]), hi = std::max(hi, clamped[i]);
    if (lo < 16.0f / 255.0f || hi > 239.0f / 255.0f || candidates.count == 0) fitMode(clamped, false, candidates);
}

void writeBlock(const Fit& best, std::uint8_t* out) {
    out[0] = std::uint8_t(best.e0);
    out[1] = std::uint8_t(best.e1);
    std::uint64_t bits = 0;
    for (int i = 0; i < 16; ++i) bits |= std::uint64_t(best.codes[size_t(i)]) << (3 * i);
    for (int i = 0; i < 6; ++i) out[2 + i] = std::uint8_t(bits >> (8 * i));
}

void encodeBc4Block(const float v[16], std::uint8_t* out) {
    float clamped[16];
    Candidates candidates;
    candidatesOf(v, clamped, candidates);
    writeBlock(choose(candidates), out);
}

// BC5 normals: each channel's candidates of least squared error, paired by the decoded normal's angle.
// Not only those within kWorstSlack of the channel's least worst: a steep normal's rebuilt z turns a small
// error in x or y into a large angle, so the worst angle is not where either channel's worst error is.
// 8 a channel: 16 brings the family's worst angles down by another 4% in twice the time.
constexpr int kJointFits = 8;
// The pair's cost: the block's summed angle (as the chord between the unit normals) plus 4 times its
// worst, which on the family of tests/io/block_format_test.cpp lowers the worst angles without raising
// the medians.
constexpr double kWorstAngleWeight = 4.0;

int leastSquaredFits(const Candidates& c, const Fit* out[kJointFits]) {
    std::array<const Fit*, 128> all{};
    for (int i = 0; i < c.count; ++i) all[size_t(i)] = &c.fits[size_t(i)];
    std::stable_sort(all.begin(), all.begin() + c.count, [](const Fit* a, const Fit* b) { return a->error < b->error; });
    const int n = std::min(c.count, kJointFits);
    for (int i = 0; i < n; ++i) out[i] = all[size_t(i)];
    return n;
}

// A fit's 16 decoded values as normal components: offset + scale * u.
std::array<double, 16> decodedComponents(const Fit& f, const NormalUnits& units) {
    const std::array<float, 8> p = palette(f.e0, f.e1);
    std::array<double, 16> out{};
    for (int t = 0; t < 16; ++t) out[size_t(t)] = units.offset + units.scale * double(p[f.codes[size_t(t)]]);
    return out;
}

// The unit normal of x, y with z rebuilt (x, y past the unit circle: on it, z = 0), as a shader rebuilds it.
std::array<double, 3> rebuilt(double x, double y) {
    const double zz = 1.0 - x * x - y * y;
    if (zz >= 0.0) return {x, y, std::sqrt(zz)};
    const double r = std::sqrt(x * x + y * y);
    return {x / r, y / r, 0.0};
}

void encodeBc5Block(const float x[16], const float y[16], const NormalUnits& units, std::uint8_t* out) {
    float cx[16], cy[16];
    Candidates candX, candY;
    candidatesOf(x, cx, candX);
    candidatesOf(y, cy, candY);
    const Fit *fx[kJointFits], *fy[kJointFits];
    const int nx = leastSquaredFits(candX, fx), ny = leastSquaredFits(candY, fy);
    std::array<std::array<double, 3>, 16> given{};
    for (int t = 0; t < 16; ++t)
        given[size_t(t)] = rebuilt(units.offset + units.scale * double(cx[t]), units.offset + units.scale * double(cy[t]));
    std::array<std::array<double, 16>, kJointFits> ys{};
    for (int j = 0; j < ny; ++j) ys[size_t(j)] = decodedComponents(*fy[j], units);
    double best = 1e300;
    int bi = 0, bj = 0;
    for (int i = 0; i < nx; ++i) {
        const std::array<double, 16> xs = decodedComponents(*fx[i], units);
        for (int j = 0; j < ny; ++j) {
            double sum = 0.0, worst = 0.0;
            for (int t = 0; t < 16; ++t) {
                const std::array<double, 3> n = rebuilt(xs[size_t(t)], ys[size_t(j)][size_t(t)]);
                const std::array<double, 3>& g = given[size_t(t)];
                const double chord = std::sqrt((n[0] - g[0]) * (n[0] - g[0]) + (n[1] - g[1]) * (n[1] - g[1]) + (n[2] - g[2]) * (n[2] - g[2]));
                sum += chord;
                worst = std::max(worst, chord);
            }
            const double cost = sum + kWorstAngleWeight * worst;
            if (cost < best) best = cost, bi = i, bj = j;
        }
    }
    writeBlock(*fx[bi], out);
    writeBlock(*fy[bj], out + 8);
}

}  // namespace

void decodeBc4Block(const std::uint8_t* block, float values[16]) {
    const std::array<float, 8> p = palette(block[0], block[1]);
    std::uint64_t bits = 0;
    for (int i = 0; i < 6; ++i) bits |= std::uint64_t(block[2 + i]) << (8 * i);
    for (int i = 0; i < 16; ++i) values[i] = p[size_t((bits >> (3 * i)) & 7)];
}

std::vector<std::uint8_t> encodeBlocks(const Image& image, BlockFormat format, int threads, std::optional<NormalUnits> normals) {
    if (isAstc(format)) return encodeAstc(image, format, threads, normals.has_value());
    const int channels = blockChannels(format), bytes = blockBytes(format);
    const int across = (image.width + 3) / 4, down = (image.height + 3) / 4;
    std::vector<std::uint8_t> out(blockImageBytes(image.width, image.height, format));
    parallelFor(down, threads, [&](int begin, int end) {
        float v[16];
        for (int by = begin; by < end; ++by)
            for (int bx = 0; bx < across; ++bx)
                {
                    float w[16];
                    for (int i = 0; i < 16; ++i) {
                        const int x = std::min(bx * 4 + i % 4, image.width - 1), y = std::min(by * 4 + i / 4, image.height - 1);
                        v[i] = image.at(x, y, 0);
                        if (channels == 2) w[i] = image.at(x, y, 1);
                    }
                    std::uint8_t* block = out.data() + (size_t(by) * across + bx) * size_t(bytes);
                    if (channels == 2 && normals) {
                        encodeBc5Block(v, w, *normals, block);
                    } else {
                        encodeBc4Block(v, block);
                        if (channels == 2) encodeBc4Block(w, block + 8);
                    }
                }
    });
    return out;
}

Image decodeBlocks(const std::uint8_t* bytes, int width, int height, BlockFormat format, int channels) {
    if (isAstc(format)) return decodeAstc(bytes, width, height, format, channels);
    channels = blockChannels(format);
    const int blockSize = blockBytes(format);
    const int across = (width + 3) / 4;
    Image image(width, height, channels);
    float v[16];
    for (int by = 0; by < (height + 3) / 4; ++by)
        for (int bx = 0; bx < across; ++bx)
            for (int c = 0; c < channels; ++c) {
                decodeBc4Block(bytes + (size_t(by) * across + bx) * size_t(blockSize) + size_t(c) * 8, v);
                for (int i = 0; i < 16; ++i) {
                    const int x = bx * 4 + i % 4, y = by * 4 + i / 4;
                    if (x < width && y < height) image.at(x, y, c) = v[i];
                }
            }
    return image;
}

}  // namespace heightpack
