#include "smoothing.hpp"

#include <algorithm>
#include <cmath>

#include "heightpack/core/parallel.hpp"

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

}  // namespace heightpack::detail
