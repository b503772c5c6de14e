#include "heightpack/core/lookup_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "heightpack/core/parallel.hpp"

namespace heightpack {

namespace {

double levelError(const Image& level, Wrap wrap, const TexelRounding& stored, int threads) {
    const int w = level.width, h = level.height, channels = level.channels;
    const size_t rowValues = size_t(w) * channels;
    // A bilinear lookup is linear in its texels, so lookup(stored) - lookup(float) is the lookup of the
    // texels' differences. Each difference of two floats is exact in double; the weights 1/2 and 1/4
    // are too, so this is the difference of the two double-precision lookups to double rounding, for
    // the cost of one.
    const auto differences = [&](int y, std::vector<double>& d) {
        const float* values = level.row(y);
        for (size_t i = 0; i < rowValues; ++i) d[i] = double(stored(values[i])) - double(values[i]);
    };
    double worst = 0.0;
    std::mutex merge;
    parallelFor(h, threads, [&](int begin, int end) {
        double mine = 0.0;
        const auto keep = [&](double e) {
            mine = std::isnan(e) ? std::numeric_limits<double>::infinity() : std::max(mine, std::fabs(e));
        };
        // Each thread rounds its own rows as it goes, two rows at a time (a row and the next), instead of
        // one thread rounding the whole level first into a level-sized buffer.
        std::vector<double> row(rowValues), next(rowValues);
        differences(begin, row);
        for (int y = begin; y < end; ++y) {
            // The next row and column with the wrap mode: with clamp the last one is its own neighbour,
            // as a lookup clamped to the last centre sees it.
            const int y1 = wrapIndex(y + 1, h, wrap);
            if (y1 == y)
                next = row;
            else
                differences(y1, next);
            for (int x = 0; x < w; ++x) {
                const size_t x0 = size_t(x) * channels, x1 = size_t(wrapIndex(x + 1, w, wrap)) * channels;
                for (int c = 0; c < channels; ++c) {
                    const double d00 = row[x0 + c], d10 = row[x1 + c];
                    const double d01 = next[x0 + c], d11 = next[x1 + c];
                    keep(d00);                                // the texel centre
                    keep(0.5 * (d00 + d10));                  // the midpoint along x
                    keep(0.5 * (d00 + d01));                  // along y
                    keep(0.25 * ((d00 + d10) + (d01 + d11)));  // between four centres
                }
            }
            row.swap(next);  // row y + 1's differences, unless y + 1 wrapped: then the loop has ended
        }
        std::lock_guard<std::mutex> lock(merge);
        worst = std::max(worst, mine);  // a maximum: the same whatever the split
    });
    return worst;
}

}  // namespace

std::vector<double> worstLookupError(const std::vector<Image>& chain, Wrap wrap, const TexelRounding& stored,
                                     int threads) {
    std::vector<double> errors;
    errors.reserve(chain.size());
    for (const Image& level : chain) errors.push_back(levelError(level, wrap, stored, threads));
    return errors;
}

}  // namespace heightpack
