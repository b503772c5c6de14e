#include "look_spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "heightpack/core/parallel.hpp"

#include "dft.hpp"

namespace heightpack::detail {



HalfSpectrum spectrumOf(const Image& map, int threads) {
    const int w = map.width;
    return {w, map.height, w / 2 + 1, forwardRealDftToHalf(w, map.height, threads, [&](int y, float* row) {
                for (int x = 0; x < w; ++x) row[x] = map.at(x, y);  // the first channel
            })};
}

// The real field of a half spectrum (overwritten), scaled by 1/(w h) as the inverse of spectrumOf.
Field fieldOf(HalfSpectrum& half, int threads) {
    Field out(half.w, half.h, Field::unset);  // every row written by the inverse
    const double scale = 1.0 / (double(half.w) * half.h);
    inverseRealDftOfHalf(half.values.data(), half.w, half.h, threads, [&](int y, const float* row) {
        double* to = &out.v[size_t(y) * half.w];
        for (int x = 0; x < half.w; ++x) to[x] = row[x] * scale;
    });
    return out;
}

namespace {

double gaussianGain(double f, double sigma) { return std::exp(-2 * std::numbers::pi * std::numbers::pi * sigma * sigma * f * f); }

}  // namespace

// The spectrum of the map filtered periodically with a difference of Gaussians of sigmas fine < coarse
// (texels): a band pass. Each Gaussian's gain is the product of its gains along x and y, so no exponential
// per texel. With folds (foldX, foldY) other than 1, the spectrum of that band pass sampled every foldX-th
// column and foldY-th row (w / foldX x h / foldY, which the folds must divide): each frequency of the
// smaller grid sums the frequencies that alias onto it, so its inverse holds exactly those samples.
HalfSpectrum bandPassSpectrum(const HalfSpectrum& spectrum, double fine, double coarse, int threads, int foldX, int foldY) {
    const int h = spectrum.h, w = spectrum.w, columns = spectrum.columns;
    auto gains = [](int n, double sigma) {
        std::vector<double> g(n);
        for (int i = 0; i < n; ++i) g[i] = gaussianGain(double(std::min(i, n - i)) / n, sigma);
        return g;
    };
    const std::vector<double> fineX = gains(w, fine), fineY = gains(h, fine), coarseX = gains(w, coarse), coarseY = gains(h, coarse);
    const int outW = w / foldX, outH = h / foldY, outColumns = outW / 2 + 1;
    HalfSpectrum s{outW, outH, outColumns, std::vector<std::complex<float>>(size_t(outH) * outColumns)};
    if (foldX == 1 && foldY == 1) {
        parallelFor(h, threads, [&](int begin, int end) {
            for (int y = begin; y < end; ++y)
                for (int x = 0; x < columns; ++x)
                    s.values[size_t(y) * columns + x] = spectrum.at(x, y) * float(fineX[x] * fineY[y] - coarseX[x] * coarseY[y]);
        });
        return s;
    }
    // Each output row sums the rows fy = y + j outH, each in the runs of columns fx = x + i outW: the
    // half's own columns, then (fx > w/2) the opposite frequencies' conjugates, read backwards.
    parallelFor(outH, threads, [&](int begin, int end) {
        for (int y = begin; y < end; ++y) {
            std::complex<float>* to = &s.values[size_t(y) * outColumns];
            for (int j = 0; j < foldY; ++j) {
                const int fy = y + j * outH;
                const double a = fineY[fy], b = coarseY[fy];
                const std::complex<float>* row = &spectrum.values[size_t(fy) * columns];
                const std::complex<float>* opposite = &spectrum.values[size_t((h - fy) % h) * columns];
                for (int i = 0; i < foldX; ++i) {
                    const int x0 = i * outW, own = std::clamp(columns - x0, 0, outColumns);
                    for (int x = 0; x < own; ++x) to[x] += row[x0 + x] * float(fineX[x0 + x] * a - coarseX[x0 + x] * b);
                    for (int x = own; x < outColumns; ++x)
                        to[x] += std::conj(opposite[w - x0 - x]) * float(fineX[x0 + x] * a - coarseX[x0 + x] * b);
                }
            }
        }
    });
    return s;
}

Field bandPassed(const HalfSpectrum& spectrum, double fine, double coarse, int threads) {
    HalfSpectrum s = bandPassSpectrum(spectrum, fine, coarse, threads);
    return fieldOf(s, threads);
}

namespace {

// The profiles of the square of the field of s, scaled by `scale`, taken from the
// inverse's rows as they come: no field is stored. The columns are summed per block of rows (each block's
// rows in order, on one thread), the blocks then in order: the same on any thread count.
Profiles squareProfiles(HalfSpectrum s, double scale, int threads) {
    const int w = s.w, h = s.h, blocks = (h + kInverseRowBlock - 1) / kInverseRowBlock;
    std::vector<double> blockColumns(size_t(blocks) * w, 0.0);
    Profiles p{std::vector<double>(w, 0.0), std::vector<double>(h, 0.0)};
    inverseRealDftOfHalf(s.values.data(), w, h, threads, [&](int y, const float* row) {
        double* columns = &blockColumns[size_t(y / kInverseRowBlock) * w];
        double sum = 0;
        for (int x = 0; x < w; ++x) {
            const double v = row[x] * scale;
            sum += v * v;
            columns[x] += v * v;
        }
        p.rows[y] = sum / w;
    });
    for (int b = 0; b < blocks; ++b)
        for (int x = 0; x < w; ++x) p.columns[x] += blockColumns[size_t(b) * w + x];
    for (double& c : p.columns) c /= h;
    return p;
}

// The largest power of two at most `most` that divides n and leaves at least 64.
int foldFor(int n, double most) {
    int fold = 1;
    while (2 * fold <= most && n % (2 * fold) == 0 && n / (2 * fold) >= 64) fold *= 2;
    return fold;
}

}  // namespace

// The profiles of the square of bandPassed(spectrum, fine, coarse). The column means from every
// fold-th row, the row means from every fold-th column, fold up to fine / 2, for 1/fold of the transforms
// each: the band pass keeps e^(-2 pi^2) = 3e-9 of its gain at half that sampling rate, so nothing the
// squares alias onto the means is left above rounding, on any map. (With folds up to `fine` a map of
// fine ripples, examples/maps/ripple.png, moved its frame score by 1%.)
Profiles energyProfiles(const HalfSpectrum& spectrum, double fine, double coarse, int threads) {
    const double scale = 1.0 / (double(spectrum.w) * spectrum.h);
    const int foldX = foldFor(spectrum.w, fine / 2), foldY = foldFor(spectrum.h, fine / 2);
    if (foldX < 4 || foldY < 4)  // two transforms of half the size or more: no saving
        return squareProfiles(bandPassSpectrum(spectrum, fine, coarse, threads), scale, threads);
    return {squareProfiles(bandPassSpectrum(spectrum, fine, coarse, threads, 1, foldY), scale, threads).columns,
            squareProfiles(bandPassSpectrum(spectrum, fine, coarse, threads, foldX, 1), scale, threads).rows};
}

}  // namespace heightpack::detail
