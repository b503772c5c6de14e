#include "heightpack/core/lookup_error.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "heightpack/core/normal_angle.hpp"
#include "heightpack/core/parallel.hpp"

namespace heightpack {

namespace {

// The worst |double(stored[i]) - double(values[i])| of a run, and whether any difference is NaN. The
// maximum of non-negative doubles is the same in any order, so two lanes at a time (SSE2, every x86-64)
// give the loop's own result; maxpd keeps the running maximum when a difference is NaN, as std::max does.
struct RunWorst {
    double worst = 0.0;
    bool nan = false;
};
void worstOfRun(const float* stored, const float* values, size_t n, RunWorst& run) {
    size_t i = 0;
#if defined(__SSE2__)
    __m128d worst = _mm_set1_pd(run.worst), nan = _mm_setzero_pd();
    const __m128d magnitude = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL));
    for (; i + 4 <= n; i += 4) {
        const __m128 s = _mm_loadu_ps(stored + i), v = _mm_loadu_ps(values + i);
        const __m128d low = _mm_sub_pd(_mm_cvtps_pd(s), _mm_cvtps_pd(v));
        const __m128d high = _mm_sub_pd(_mm_cvtps_pd(_mm_movehl_ps(s, s)), _mm_cvtps_pd(_mm_movehl_ps(v, v)));
        worst = _mm_max_pd(_mm_and_pd(low, magnitude), worst);
        worst = _mm_max_pd(_mm_and_pd(high, magnitude), worst);
        nan = _mm_or_pd(nan, _mm_or_pd(_mm_cmpunord_pd(low, low), _mm_cmpunord_pd(high, high)));
    }
    double lanes[2];
    _mm_storeu_pd(lanes, worst);
    run.worst = std::max(lanes[0], lanes[1]);
    run.nan |= _mm_movemask_pd(nan) != 0;
#endif
    for (; i < n; ++i) {
        const double d = double(stored[i]) - double(values[i]);
        run.worst = std::max(run.worst, std::fabs(d));
        run.nan |= d != d;
    }
}

double levelError(const Image& level, const TexelRowRounding& stored, int threads) {
    const size_t rowValues = size_t(level.width) * level.channels;
    double worst = 0.0;
    bool notFinite = false;
    std::mutex merge;
    parallelFor(level.height, threads, [&](int begin, int end) {
        std::vector<float> readBack(rowValues);
        RunWorst mine;
        for (int y = begin; y < end; ++y) {
            stored(level.row(y), rowValues, readBack.data());
            worstOfRun(readBack.data(), level.row(y), rowValues, mine);
        }
        std::lock_guard<std::mutex> lock(merge);
        worst = std::max(worst, mine.worst);  // a maximum: the same whatever the split
        notFinite |= mine.nan;
    });
    return notFinite ? std::numeric_limits<double>::infinity() : worst;
}

// The worst angle between level's normals and the same normals through stored, in degrees.
double levelAngleError(const Image& level, const TexelRowRounding& stored, int threads) {
    const size_t rowValues = size_t(level.width) * level.channels;
    const int c = level.channels;
    double worst = 0.0;
    std::mutex merge;
    parallelFor(level.height, threads, [&](int begin, int end) {
        std::vector<float> readBack(rowValues);
        double mine = 0.0;
        for (int y = begin; y < end; ++y) {
            const float* given = level.row(y);
            stored(given, rowValues, readBack.data());
            for (int x = 0; x < level.width; ++x) {
                const float* g = given + size_t(x) * c;
                const float* r = readBack.data() + size_t(x) * c;
                double a[3], b[3];
                if (c == 2) {
                    normalFromXy(g[0], g[1], a);
                    normalFromXy(r[0], r[1], b);
                } else {
                    normalFromXyz(g[0], g[1], g[2], a);
                    normalFromXyz(r[0], r[1], r[2], b);
                }
                const double degrees = angleBetween(a, b) * kDegreesPerRadian;
                // NaN compares false: a non-finite read back is the worst angle there is.
                mine = std::max(mine, degrees == degrees ? degrees : 180.0);
            }
        }
        std::lock_guard<std::mutex> lock(merge);
        worst = std::max(worst, mine);  // a maximum: the same whatever the split
    });
    return worst;
}

}  // namespace

std::vector<double> worstAngleErrorDegrees(const std::vector<Image>& chain, const TexelRowRounding& stored, int threads) {
    std::vector<double> errors;
    errors.reserve(chain.size());
    for (const Image& level : chain) errors.push_back(level.channels >= 2 ? levelAngleError(level, stored, threads) : 0.0);
    return errors;
}

std::vector<double> worstLookupError(const std::vector<Image>& chain, const TexelRowRounding& stored, int threads) {
    std::vector<double> errors;
    errors.reserve(chain.size());
    for (const Image& level : chain) errors.push_back(levelError(level, stored, threads));
    return errors;
}

std::vector<double> worstLookupError(const std::vector<Image>& chain, const TexelRounding& stored, int threads) {
    const TexelRowRounding rows = [&stored](const float* values, size_t n, float* readBack) {
        for (size_t i = 0; i < n; ++i) readBack[i] = stored(values[i]);
    };
    return worstLookupError(chain, rows, threads);
}

}  // namespace heightpack
