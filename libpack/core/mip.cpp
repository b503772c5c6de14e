#include "heightpack/core/mip.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "heightpack/core/parallel.hpp"

namespace heightpack {

namespace {

constexpr double kKaiserAlpha = 4.0;

double sinc(double x) {
    if (std::abs(x) < 1e-9) return 1.0;
    const double px = std::numbers::pi * x;
    return std::sin(px) / px;
}

// Modified Bessel function of the first kind, order 0, by its power series (converges fast for the
// arguments the Kaiser window uses, |x| <= alpha).
double besselI0(double x) {
    double sum = 1.0, term = 1.0;
    const double q = x * x / 4.0;
    for (int k = 1; k < 64; ++k) {
        term *= q / (double(k) * k);
        sum += term;
        if (term < sum * 1e-17) break;
    }
    return sum;
}

// For each destination index along one axis: which source texels it reads, with which weights.
// Weights are normalised to sum to one, so a constant image stays constant at every level.
struct AxisTaps {
    std::vector<int> first;  // offset of output i's taps in index/weight
    std::vector<int> count;
    std::vector<int> index;  // source texel, already wrapped
    std::vector<float> weight;
};

AxisTaps computeTaps(int srcSize, int dstSize, Filter filter, Wrap wrap) {
    AxisTaps taps;
    const double ratio = double(srcSize) / dstSize;
    const double widen = std::max(1.0, ratio);  // shrinking: the filter spans `ratio` source texels per unit
    const double support = filterRadius(filter) * widen;
    std::vector<double> w;
    for (int i = 0; i < dstSize; ++i) {
        const double centre = (i + 0.5) * ratio - 0.5;
        const long long lo = static_cast<long long>(std::ceil(centre - support));
        const long long hi = static_cast<long long>(std::floor(centre + support));
        w.clear();
        double sum = 0.0;
        for (long long t = lo; t <= hi; ++t) {
            w.push_back(filterWeight(filter, (double(t) - centre) / widen));
            sum += w.back();
        }
        taps.first.push_back(static_cast<int>(taps.index.size()));
        int n = 0;
        for (long long t = lo; t <= hi; ++t) {
            const double wt = w[static_cast<size_t>(t - lo)];
            if (wt == 0.0) continue;
            taps.index.push_back(wrapIndex(t, srcSize, wrap));
            taps.weight.push_back(static_cast<float>(wt / sum));
            ++n;
        }
        taps.count.push_back(n);
    }
    return taps;
}

// One row of filtering along x: in (srcWidth texels of c channels) -> out (dstWidth texels).
void filterRow(const float* in, int c, int dstWidth, const AxisTaps& taps, float* out) {
    for (int x = 0; x < dstWidth; ++x) {
        const int* idx = &taps.index[taps.first[x]];
        const float* wt = &taps.weight[taps.first[x]];
        for (int ch = 0; ch < c; ++ch) {
            float acc = 0.0f;
            for (int k = 0; k < taps.count[x]; ++k) acc += wt[k] * in[idx[k] * c + ch];
            out[x * c + ch] = acc;
        }
    }
}

// Row y of filtering src along y into out (a whole source row's values). Whole rows at a time, so the
// inner loop is a contiguous multiply-add that the compiler vectorises.
void filterColumns(const Image& src, int y, const AxisTaps& taps, float* out) {
    const size_t rowLength = static_cast<size_t>(src.width) * src.channels;
    std::fill(out, out + rowLength, 0.0f);
    for (int k = 0; k < taps.count[y]; ++k) {
        const float wt = taps.weight[taps.first[y] + k];
        const float* in = src.row(taps.index[taps.first[y] + k]);
        for (size_t i = 0; i < rowLength; ++i) out[i] += wt * in[i];
    }
}

// Filters along x: src (W x H) -> dst (dstWidth x H).
Image resampleRows(const Image& src, int dstWidth, const AxisTaps& taps, int threads) {
    Image dst(dstWidth, src.height, src.channels);
    parallelFor(src.height, threads, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) filterRow(src.row(y), src.channels, dstWidth, taps, dst.row(y));
    });
    return dst;
}

// Filters along y: src (W x H) -> dst (W x dstHeight).
Image resampleColumns(const Image& src, int dstHeight, const AxisTaps& taps, int threads) {
    Image dst(src.width, dstHeight, src.channels);
    parallelFor(dstHeight, threads, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) filterColumns(src, y, taps, dst.row(y));
    });
    return dst;
}

// Filters along y, then along x, one destination row at a time: each thread filters a row along y into
// a row of its own and that row along x, so the image between the two passes (half the source, for a
// mip level) is never held. The same sums in the same order as resampleRows(resampleColumns(src)).
Image resampleBoth(const Image& src, int dstWidth, int dstHeight, const AxisTaps& rowTaps,
                   const AxisTaps& columnTaps, int threads) {
    Image dst(dstWidth, dstHeight, src.channels);
    parallelFor(dstHeight, threads, [&](int y0, int y1) {
        std::vector<float> filtered(static_cast<size_t>(src.width) * src.channels);
        for (int y = y0; y < y1; ++y) {
            filterColumns(src, y, columnTaps, filtered.data());
            filterRow(filtered.data(), src.channels, dstWidth, rowTaps, dst.row(y));
        }
    });
    return dst;
}

}  // namespace

double filterRadius(Filter filter) {
    switch (filter) {
        case Filter::Box: return 0.5;
        case Filter::Triangle: return 1.0;
        case Filter::Lanczos3: return 3.0;
        case Filter::Kaiser: return 3.0;
    }
    return 0.0;
}

double filterWeight(Filter filter, double x) {
    const double ax = std::abs(x);
    switch (filter) {
        case Filter::Box: return (x >= -0.5 && x < 0.5) ? 1.0 : 0.0;  // half-open: ties go to one side
        case Filter::Triangle: return ax < 1.0 ? 1.0 - ax : 0.0;
        case Filter::Lanczos3: return ax < 3.0 ? sinc(x) * sinc(x / 3.0) : 0.0;
        case Filter::Kaiser: {
            if (ax >= 3.0) return 0.0;
            const double r = x / 3.0;
            return sinc(x) * besselI0(kKaiserAlpha * std::sqrt(1.0 - r * r)) / besselI0(kKaiserAlpha);
        }
    }
    return 0.0;
}

Image resample(const Image& src, int width, int height, const MipOptions& options) {
    assert(width > 0 && height > 0 && !src.empty());
    // Columns first: that pass streams whole rows and vectorises, so it takes the larger share of work.
    auto columnTaps = [&] { return computeTaps(src.height, height, options.filter, options.wrap); };
    auto rowTaps = [&] { return computeTaps(src.width, width, options.filter, options.wrap); };
    if (height != src.height && width != src.width)
        return resampleBoth(src, width, height, rowTaps(), columnTaps(), options.threads);
    if (height != src.height) return resampleColumns(src, height, columnTaps(), options.threads);
    return width != src.width ? resampleRows(src, width, rowTaps(), options.threads) : src;
}

bool isPowerOfTwo(int n) { return n > 0 && (n & (n - 1)) == 0; }

int nextPowerOfTwo(int n) {
    int p = 1;
    while (p < n) p <<= 1;
    return p;
}

int mipLevelCount(int width, int height) {
    int levels = 1;
    for (int side = std::max(width, height); side > 1; side >>= 1) ++levels;
    return levels;
}

std::vector<Image> generateMipChain(const Image& level0, const MipOptions& options) {
    return generateMipChain(Image(level0), options);
}

std::vector<Image> generateMipChain(Image&& level0, const MipOptions& options) {
    std::vector<Image> below = generateMipLevelsBelow(level0, options);
    std::vector<Image> chain;
    chain.reserve(below.size() + 1);
    chain.push_back(std::move(level0));
    for (Image& level : below) chain.push_back(std::move(level));
    return chain;
}

std::vector<Image> generateMipLevelsBelow(const Image& level0, const MipOptions& options) {
    assert(isPowerOfTwo(level0.width) && isPowerOfTwo(level0.height));
    const int levels = mipLevelCount(level0.width, level0.height);
    std::vector<Image> below;
    below.reserve(levels - 1);
    for (int level = 1; level < levels; ++level) {
        const Image& above = level == 1 ? level0 : below.back();
        // Each level is made from the one above (not from level 0): the filter at ratio 2 has a fixed
        // set of weights, so the chain is exactly shift-invariant for periodic maps.
        below.push_back(resample(above, std::max(1, above.width / 2), std::max(1, above.height / 2), options));
    }
    return below;
}

}  // namespace heightpack
