#include "smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "heightpack/core/parallel.hpp"
#include "heightpack/core/tile/tileable.hpp"

namespace heightpack::detail {

// Every other pass writes to scratch, so that no pass touches fresh pages.
void blur(Field& f, Field& scratch, double sigma, int threads) {
    const int radius = std::max(1, static_cast<int>(std::lround(std::sqrt(sigma * sigma + 0.25) - 0.5)));
    const double width = 2 * radius + 1;
    auto mirror = [](long i, int n) {
        while (i < 0 || i >= n) i = i < 0 ? -1 - i : 2L * n - 1 - i;
        return static_cast<int>(i);
    };
    auto alongRows = [&](const Field& in, Field& out) {
        const int n = in.w;
        parallelFor(in.h, threads, [&](int begin, int end) {
            for (int y = begin; y < end; ++y) {
                double sum = 0;
                for (long i = -radius - 1; i < radius; ++i) sum += in.at(mirror(i, n), y);
                for (int x = 0; x < n; ++x) {
                    sum += in.at(mirror(x + radius, n), y) - in.at(mirror(long(x) - radius - 1, n), y);
                    out.at(x, y) = sum / width;
                }
            }
        });
    };
    // The same running sums down each column, 256 columns at a time so that each step reads a run of a row.
    auto alongColumns = [&](const Field& in, Field& out) {
        const int n = in.h;
        constexpr int kColumns = 256;
        parallelFor((in.w + kColumns - 1) / kColumns, threads, [&](int begin, int end) {
            const int x0 = begin * kColumns, x1 = std::min(end * kColumns, in.w);
            std::vector<double> sums(size_t(x1 - x0), 0.0);
            for (long i = -radius - 1; i < radius; ++i)
                for (int x = x0; x < x1; ++x) sums[x - x0] += in.at(x, mirror(i, n));
            for (int y = 0; y < n; ++y) {
                const int add = mirror(y + radius, n), drop = mirror(long(y) - radius - 1, n);
                for (int x = x0; x < x1; ++x) {
                    sums[x - x0] += in.at(x, add) - in.at(x, drop);
                    out.at(x, y) = sums[x - x0] / width;
                }
            }
        });
    };
    alongRows(f, scratch);
    alongRows(scratch, f);
    alongRows(f, scratch);
    alongColumns(scratch, f);
    alongColumns(f, scratch);
    alongColumns(scratch, f);
}

bool hasTerraces(const Image& map, int threads) {
    const int w = map.width, h = map.height;
    std::vector<size_t> equal(size_t(h), 0);
    parallelFor(h, threads, [&](int begin, int end) {
        for (int y = begin; y < end; ++y) {
            const float* row = &map.pixels[size_t(y) * w];
            const float* below = y + 1 < h ? row + w : nullptr;
            size_t count = 0;
            for (int x = 0; x + 1 < w; ++x) count += row[x] == row[x + 1];
            if (below)
                for (int x = 0; x < w; ++x) count += row[x] == below[x];
            equal[y] = count;
        }
    });
    size_t total = 0;
    for (size_t c : equal) total += c;
    const double pairs = double(w - 1) * h + double(w) * (h - 1);
    return pairs > 0 && double(total) >= pairs / 20;
}

// A smooth map that rounds back to map: starting from the map, blurred and projected back into each
// texel's rounding interval [v - q/2, v + q/2], a few times (projections onto convex sets). The plateaus of
// a quantised gradient become the ramp they were rounded from; no texel leaves its interval.
std::vector<float> dequantised(const Image& map, double quantum, int threads) {
    Field x(map.width, map.height);
    x.v.assign(map.pixels.begin(), map.pixels.end());
    const double half = 0.4999 * quantum;
    Field scratch(map.width, map.height);
    for (int iteration = 0; iteration < 8; ++iteration) {
        blur(x, scratch, 1.5, threads);
        parallelFor(map.height, threads, [&](int begin, int end) {
            for (size_t i = size_t(begin) * map.width; i < size_t(end) * map.width; ++i)
                x.v[i] = std::clamp(x.v[i], double(map.pixels[i]) - half, double(map.pixels[i]) + half);
        });
    }
    return std::vector<float>(x.v.begin(), x.v.end());
}

std::vector<float> largeScaleField(const std::vector<float>& values, int w, int h, double sigma, int threads) {
    int step = 1;
    while (2 * step <= sigma / 8 && w % (2 * step) == 0 && h % (2 * step) == 0 && w / (2 * step) >= 64 && h / (2 * step) >= 64)
        step *= 2;
    const int cw = w / step, ch = h / step;
    Field coarse(cw, ch);
    parallelFor(ch, threads, [&](int begin, int end) {
        for (int cy = begin; cy < end; ++cy)
            for (int y = cy * step; y < (cy + 1) * step; ++y)
                for (int x = 0; x < w; ++x) coarse.at(x / step, cy) += values[size_t(y) * w + x];
    });
    for (double& v : coarse.v) v /= double(step) * step;
    {
        Field scratch(cw, ch);
        detail::blur(coarse, scratch, sigma / step, threads);
    }
    Image low(cw, ch, 1);
    for (size_t i = 0; i < coarse.v.size(); ++i) low.pixels[i] = static_cast<float>(coarse.v[i]);
    const Image lowPeriodic = periodicComponent(low, PeriodicContinuity::Heights);
    Field field(cw, ch);
    for (size_t i = 0; i < field.v.size(); ++i) field.v[i] = double(low.pixels[i]) - lowPeriodic.pixels[i];
    // Texel x lies at (x + 0.5) / step - 0.5 in cells: between cells lo and lo + 1 with weight t of the latter.
    struct Tap {
        int lo, hi;
        double t;
    };
    auto taps = [&](int n, int cells) {
        std::vector<Tap> out(n);
        for (int i = 0; i < n; ++i) {
            const double c = std::clamp((i + 0.5) / step - 0.5, 0.0, double(cells - 1));
            const int lo = std::min(static_cast<int>(c), cells - 1);
            out[i] = {lo, std::min(lo + 1, cells - 1), c - lo};
        }
        return out;
    };
    const std::vector<Tap> tx = taps(w, cw), ty = taps(h, ch);
    std::vector<float> smooth(values.size());
    parallelFor(h, threads, [&](int begin, int end) {
        for (int y = begin; y < end; ++y) {
            const Tap& b = ty[y];
            for (int x = 0; x < w; ++x) {
                const Tap& a = tx[x];
                const double top = field.at(a.lo, b.lo) + a.t * (field.at(a.hi, b.lo) - field.at(a.lo, b.lo));
                const double bottom = field.at(a.lo, b.hi) + a.t * (field.at(a.hi, b.hi) - field.at(a.lo, b.hi));
                smooth[size_t(y) * w + x] = static_cast<float>(top + b.t * (bottom - top));
            }
        }
    });
    return smooth;
}

}  // namespace heightpack::detail
