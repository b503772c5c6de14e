// The fixes for a map that does not tile: the periodic component (Moisan), crossfades, the mirror.
// The seam measure that judges them is in tileable.cpp.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <complex>
#include <numbers>
#include <numeric>
#include <vector>

#include "heightpack/core/tile/tileable.hpp"

#include "dft.hpp"
#include "gaussianise.hpp"

namespace heightpack {

namespace {

double smoothstep(double edge, double x) {
    const double t = std::clamp(x / edge, 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

// relativeToSlope: the jump across an edge is measured from the line through the slopes beside it
// (the step minus their mean), so a smooth slope running through the edge is kept rather than flattened
// into one level step; Moisan's original measures it from the edge texel repeated.
Image moisanPeriodic(const Image& map, bool relativeToSlope) {
    assert(map.channels == 1);
    const int w = map.width, h = map.height;
    // The boundary image v: what the periodic Laplacian of the map has at the texels beside a tile edge
    // that the map's own interior does not: the jump across the edge. Its sum over each line is zero, so
    // the smooth field has no net curvature to spread over the tile (no dome). Nonzero on the edges alone:
    // kept as the jumps per line and made a row at a time for the transform.
    std::vector<double> acrossX(h), acrossY(w);  // first - last of each row and column, less the slope term
    for (int y = 0; y < h; ++y) {
        const double first = map.at(0, y), last = map.at(w - 1, y);
        const double slope = relativeToSlope && w >= 3 ? 0.5 * (double(map.at(1, y)) - first + last - map.at(w - 2, y)) : 0.0;
        acrossX[y] = last - first + slope;
    }
    for (int x = 0; x < w; ++x) {
        const double first = map.at(x, 0), last = map.at(x, h - 1);
        const double slope = relativeToSlope && h >= 3 ? 0.5 * (double(map.at(x, 1)) - first + last - map.at(x, h - 2)) : 0.0;
        acrossY[x] = last - first + slope;
    }
    // The smooth field s solves the periodic Poisson equation laplacian(s) = v with zero mean (v's spectrum
    // over the Laplacian's symbol, in float half spectra: s is smooth and small, which floats hold to far
    // below a 16-bit step); the map minus s has, everywhere, the Laplacian of the map's interior: no seam,
    // and its mean kept.
    const int columns = w / 2 + 1;
    std::vector<std::complex<float>> half = detail::forwardRealDftToHalf(w, h, 0, [&](int y, float* row) {
        std::fill(row, row + w, 0.0f);
        double first = acrossX[y], last = -acrossX[y];
        if (w == 1) first = last = 0;  // the two ends are one texel: they cancel
        row[0] = float(first);
        row[w - 1] += float(last);
        if (y == 0 || y == h - 1) {
            const double sign = h == 1 ? 0.0 : y == 0 ? 1.0 : -1.0;
            for (int x = 0; x < w; ++x) row[x] += float(sign * acrossY[x]);
        }
    });
    const double scale = 1.0 / (double(w) * h);  // the inverse is unscaled
    // The symbol's two terms, once per column and per row (the same values as computed in place).
    std::vector<double> cosX(static_cast<size_t>(columns)), cosY(static_cast<size_t>(h));
    for (int q = 0; q < columns; ++q) cosX[size_t(q)] = 2 * std::cos(2 * std::numbers::pi * q / w);
    for (int r = 0; r < h; ++r) cosY[size_t(r)] = 2 * std::cos(2 * std::numbers::pi * r / h);
    for (int r = 0; r < h; ++r)
        for (int q = 0; q < columns; ++q) {
            const double symbol = cosX[size_t(q)] + cosY[size_t(r)] - 4;
            std::complex<float>& z = half[size_t(r) * columns + q];
            z = (q == 0 && r == 0) ? 0.0f : z * float(scale / symbol);
        }
    Image out(w, h, 1);
    detail::inverseRealDftOfHalf(half.data(), w, h, 0, [&](int y, const float* row) {
        for (int x = 0; x < w; ++x) out.at(x, y) = static_cast<float>(map.at(x, y) - double(row[x]));
    });
    return out;
}

// The bend's height at distance u (in bands) from the edge: G(u) = integral from u to 1 of w, where the
// slope profile w is 1 up to half the band and eases to 0 by its end with a smoothstep. So the bend's slope
// is constant over the half band next to the edge (the change of slope is cancelled at every scale up
// to half a band, as the coarse mip levels see it too) and its curvature stays spread over the outer half.
double bendProfile(double u) {
    if (u >= 1) return 0.0;
    if (u <= 0.5) return 0.75 - u;
    const double x = 2 * (u - 0.5);
    return 0.5 * (0.5 - x + x * x * x - 0.5 * x * x * x * x);
}

// Removes the change of slope that the periodic component leaves at the left/right tile edge (call it on
// a transposed map for top/bottom). The change is measured per line from the mean slopes over a few
// texels on each side and smoothed along the edge (the part that varies from line to line is like the
// interior's own bends), then bent away within `band` texels on each side: heights stay continuous and
// nothing beyond the band changes. Unlike a global smooth field that matches slopes, which must bend the
// whole tile into a dome when the slopes differ on average, the change is local: at most 3/8 of the
// slope difference times the band.
void bendAwayEdgeKinks(Image& map, int band) {
    const int w = map.width, h = map.height;
    const int span = std::max(1, std::min(4, band / 4));
    std::vector<double> kink(h);
    for (int y = 0; y < h; ++y) {
        const double after = (double(map.at(span, y)) - map.at(0, y)) / span;
        const double before = (double(map.at(w - 1, y)) - map.at(w - 1 - span, y)) / span;
        kink[y] = after - before;
    }
    // Smooth along the edge (itself periodic) with a Gaussian of a sixteenth of its length.
    const double sigma = std::max(1.0, h / 16.0);
    const int reach = static_cast<int>(std::ceil(3 * sigma));
    std::vector<double> weights(2 * reach + 1);
    double total = 0;
    for (int k = -reach; k <= reach; ++k) total += weights[k + reach] = std::exp(-0.5 * k * k / (sigma * sigma));
    std::vector<double> smooth(h, 0.0);
    for (int y = 0; y < h; ++y)
        for (int k = -reach; k <= reach; ++k) smooth[y] += weights[k + reach] / total * kink[wrapIndex(y + k, h, Wrap::Periodic)];
    for (int y = 0; y < h; ++y) {
        // Slope -kink/2 after the edge and +kink/2 before it: the bend's own change of slope is -kink.
        const double amplitude = 0.5 * smooth[y] * band;
        for (int i = 0; i < band && i < w / 2; ++i) {
            const double g = amplitude * bendProfile((i + 0.5) / band);
            map.at(i, y) += static_cast<float>(g);
            map.at(w - 1 - i, y) += static_cast<float>(g);
        }
    }
}

}  // namespace

Image periodicComponent(const Image& map, PeriodicContinuity continuity) {
    const bool slopes = continuity == PeriodicContinuity::HeightsAndSlopes;
    Image out = moisanPeriodic(map, slopes);
    if (!slopes || map.width < 8 || map.height < 8) return out;
    bendAwayEdgeKinks(out, std::max(4, map.width / 8));
    out = transposed(out);
    bendAwayEdgeKinks(out, std::max(4, map.height / 8));
    return transposed(out);
}

double crossfadeWeight(int x, int y, int width, int height, double band) {
    // Distance to the nearest tile edge as a fraction of the tile, zero on the edge texels themselves so the
    // shifted copy (continuous across the edge) is used alone there.
    const double dx = double(std::min(x, width - 1 - x)) / width;
    const double dy = double(std::min(y, height - 1 - y)) / height;
    return smoothstep(band, dx) * smoothstep(band, dy);
}

Image crossfadeTile(const Image& map, double width, CrossfadeBlend blend) {
    assert(map.channels == 1 && width > 0 && width <= 0.5);
    const int w = map.width, h = map.height;
    auto shifted = [&](int x, int y) { return map.at((x + w / 2) % w, (y + h / 2) % h); };
    Image out(w, h, 1);
    if (blend == CrossfadeBlend::Linear) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double a = crossfadeWeight(x, y, w, h, width);
                out.at(x, y) = static_cast<float>(a * map.at(x, y) + (1 - a) * shifted(x, y));
            }
        return out;
    }
    // Four copies: the map, and the map shifted by half a tile in x, in y and in both. Near a left/right
    // edge the x-shifted copy is used (continuous there, its own seam in the middle of the tile), near a
    // top/bottom edge the y-shifted one, near a corner the diagonal one: no copy brings a seam of the map to
    // the middle of an edge. In the Gaussianised domain (the copies share one histogram), the low-pass is
    // blended linearly (the copies' shared large scales add, not their variance) and the high-pass with
    // weights whose squares sum to one, so fine contrast is kept in the band (Heitz & Neyret) without the
    // lows swelling by up to sqrt(2).
    const detail::Gaussianiser g(map.pixels, 0);
    auto field = [&](int x, int y) { return g.gaussian[size_t(y) * w + x]; };
    // The low-pass of the Gaussians, a Gaussian blur in float half spectra (a smooth field; floats hold it
    // to far below what the blend's weights could show).
    const int columns = w / 2 + 1;
    std::vector<std::complex<float>> half = detail::forwardRealDftToHalf(w, h, 0, [&](int y, float* row) {
        for (int x = 0; x < w; ++x) row[x] = static_cast<float>(field(x, y));
    });
    const double sigma = std::max(1.0, width * std::min(w, h) / 3.0);
    for (int r = 0; r < h; ++r)
        for (int q = 0; q < columns; ++q) {
            const double fx = double(q) / w, fy = double(std::min(r, h - r)) / h;
            half[size_t(r) * columns + q] *=
                float(std::exp(-2 * std::numbers::pi * std::numbers::pi * sigma * sigma * (fx * fx + fy * fy)) / (double(w) * h));
        }
    std::vector<float> lowValues(size_t(w) * h);
    detail::inverseRealDftOfHalf(half.data(), w, h, 0, [&](int y, const float* row) { std::copy(row, row + w, &lowValues[size_t(y) * w]); });
    half = {};
    auto low = [&](int x, int y) { return double(lowValues[size_t(y) * w + x]); };
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double ax = smoothstep(width, double(std::min(x, w - 1 - x)) / w);
            const double ay = smoothstep(width, double(std::min(y, h - 1 - y)) / h);
            const double weights[4] = {ax * ay, (1 - ax) * ay, ax * (1 - ay), (1 - ax) * (1 - ay)};
            const int xs[4] = {x, (x + w / 2) % w, x, (x + w / 2) % w};
            const int ys[4] = {y, y, (y + h / 2) % h, (y + h / 2) % h};
            double lowSum = 0, highSum = 0, squares = 0;
            for (int c = 0; c < 4; ++c) {
                const double l = low(xs[c], ys[c]);
                lowSum += weights[c] * l;
                highSum += weights[c] * (field(xs[c], ys[c]) - l);
                squares += weights[c] * weights[c];
            }
            out.at(x, y) = g.back(lowSum + highSum / std::sqrt(squares));
        }
    }
    return out;
}

Image mirrorTile(const Image& map) {
    const int w = map.width, h = map.height;
    Image out(2 * w, 2 * h, map.channels);
    for (int y = 0; y < 2 * h; ++y)
        for (int x = 0; x < 2 * w; ++x)
            for (int c = 0; c < map.channels; ++c)
                out.at(x, y, c) = map.at(x < w ? x : 2 * w - 1 - x, y < h ? y : 2 * h - 1 - y, c);
    return out;
}

}  // namespace heightpack
