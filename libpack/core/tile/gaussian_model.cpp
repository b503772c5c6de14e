#include "gaussian_model.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "heightpack/core/parallel.hpp"

#include "sea/counter_normals.hpp"
#include "dft.hpp"

namespace heightpack::detail {

namespace {

using Complex = std::complex<double>;

// A complex normal value of unit variance (each part N(0, 1/2)) for (seed, index) alone: the same noise on
// any thread, from the generator the sea's amplitudes come from.
Complex complexNoise(uint64_t seed, uint64_t index) {
    const NormalPair pair = normalPair(normalStreamKey(seed), index);
    return Complex(pair.first, pair.second) / std::numbers::sqrt2;
}

// Moisan's smooth field of g's edge jumps, in the frequency domain: S = V / lambda, where V is the DFT of
// the jumps (nonzero on the four border lines only, so two 1-D DFTs give it) and lambda the five-point
// Laplacian's symbol, S(0) = 0. apply(r, q, S(q, r)) is called once per frequency with q < columns (w, or
// w/2 + 1 for the half a real field needs), on any thread. Only the jumps across the left/right wrap line,
// or the top/bottom one, are taken when asked.
struct EdgeJumps {
    bool leftRight = true, topBottom = true;
};
template <class At, class Apply>
void forSmoothSpectrum(int w, int h, At at, EdgeJumps jumps, int columns, int threads, Apply apply) {
    cv::Mat leftRight(1, h, CV_64F, cv::Scalar(0)), topBottom(1, w, CV_64F, cv::Scalar(0)), down, across;
    if (jumps.leftRight)
        for (int y = 0; y < h; ++y) leftRight.at<double>(0, y) = double(at(w - 1, y)) - at(0, y);
    if (jumps.topBottom)
        for (int x = 0; x < w; ++x) topBottom.at<double>(0, x) = double(at(x, h - 1)) - at(x, 0);
    cv::dft(leftRight, down, cv::DFT_COMPLEX_OUTPUT);
    cv::dft(topBottom, across, cv::DFT_COMPLEX_OUTPUT);
    // v(0, y) = J(y) and v(w-1, y) = -J(y) have the DFT J^(r) (1 - e^(2 pi i q / w)); likewise along y.
    std::vector<Complex> edgeX(w), edgeY(h);
    std::vector<double> cosX(w), cosY(h);
    for (int q = 0; q < w; ++q) {
        edgeX[q] = 1.0 - std::polar(1.0, 2 * std::numbers::pi * q / w);
        cosX[q] = 2 * std::cos(2 * std::numbers::pi * q / w);
    }
    for (int r = 0; r < h; ++r) {
        edgeY[r] = 1.0 - std::polar(1.0, 2 * std::numbers::pi * r / h);
        cosY[r] = 2 * std::cos(2 * std::numbers::pi * r / h);
    }
    parallelFor(h, threads, [&](int begin, int end) {
        for (int r = begin; r < end; ++r) {
            const cv::Vec2d d = down.at<cv::Vec2d>(0, r);
            for (int q = 0; q < columns; ++q) {
                const cv::Vec2d a = across.at<cv::Vec2d>(0, q);
                apply(r, q, q == 0 && r == 0 ? Complex(0, 0)
                                             : (Complex(d[0], d[1]) * edgeX[q] + Complex(a[0], a[1]) * edgeY[r]) /
                                                   (cosX[q] + cosY[r] - 4));
            }
        }
    });
}

// The DFT of Moisan's periodic component of a w x h field, from the field's own (its half kx <= w/2,
// overwritten): the field's less the smooth field's, the mean set to 0. at(x, y) reads the field (only its
// border lines). The periodic component itself is never needed in space.
template <class At>
void toPeriodicSpectrum(int w, int h, At at, std::vector<std::complex<float>>& half, int threads) {
    const int columns = w / 2 + 1;
    forSmoothSpectrum(w, h, at, {}, columns, threads, [&](int r, int q, Complex s) {
        std::complex<float>& z = half[size_t(r) * columns + q];
        z = r == 0 && q == 0 ? std::complex<float>(0, 0) : std::complex<float>(std::complex<double>(z) - s);
    });
}

// The circular autocovariance along one axis, from the power summed over the other: 1/n^2 of its DFT
// (real: the sums are even in the frequency).
std::vector<double> lagsOf(std::vector<double> marginal, double n) {
    cv::Mat out;
    cv::dft(cv::Mat(1, int(marginal.size()), CV_64F, marginal.data()), out, cv::DFT_COMPLEX_OUTPUT);
    std::vector<double> lags(marginal.size());
    for (size_t d = 0; d < lags.size(); ++d) lags[d] = out.at<cv::Vec2d>(0, int(d))[0] / (n * n);
    return lags;
}

}  // namespace

std::vector<std::complex<float>> periodicHalfSpectrum(const Image& map, int threads) {
    const int w = map.width, h = map.height;
    std::vector<std::complex<float>> half = forwardRealDftToHalf(w, h, threads, [&](int y, float* row) {
        for (int x = 0; x < w; ++x) row[x] = map.at(x, y);
    });
    toPeriodicSpectrum(w, h, [&](int x, int y) { return map.at(x, y); }, half, threads);
    return half;
}

GaussianModel modelOf(const Field& g, double noise, int threads) {
    const int w = g.w, h = g.h, columns = w / 2 + 1;
    const double n = double(w) * h;
    GaussianModel model(w, h);
    // In floats: the power is a statistic, and the transform of a real field's half costs a quarter.
    std::vector<std::complex<float>> half = detail::forwardRealDftToHalf(w, h, threads, [&](int y, float* row) {
        const double* from = &g.v[size_t(y) * w];
        for (int x = 0; x < w; ++x) row[x] = static_cast<float>(from[x]);
    });
    toPeriodicSpectrum(w, h, [&](int x, int y) { return g.at(x, y); }, half, threads);
    const double floor = n * noise;  // the expected |P(k)|^2 of white noise of that variance
    parallelFor(h, threads, [&](int begin, int end) {
        for (int r = begin; r < end; ++r)
            for (int q = 0; q < columns; ++q)
                model.power.at<double>(r, q) = std::max(std::norm(std::complex<double>(half[size_t(r) * columns + q])) - floor, 0.0);
    });
    // The power summed along each axis on all threads: each row's sum in order; the columns' per fixed
    // block of rows, the blocks then in order (the same on any thread count).
    constexpr int kRows = 64;
    const int blocks = (h + kRows - 1) / kRows;
    std::vector<double> marginalX(w, 0.0), marginalY(h, 0.0), blockX(size_t(blocks) * w, 0.0);
    parallelFor(blocks, threads, [&](int begin, int end) {
        for (int b = begin; b < end; ++b) {
            double* columnSums = &blockX[size_t(b) * w];
            for (int r = b * kRows; r < std::min(h, (b + 1) * kRows); ++r) {
                double sum = 0;
                for (int q = 0; q < w; ++q) {  // over the whole row, in order: the half, then its mirror
                    const double p = model.powerAt(q, r);
                    sum += p;
                    columnSums[q] += p;
                }
                marginalY[r] = sum;
            }
        }
    });
    for (int b = 0; b < blocks; ++b)
        for (int q = 0; q < w; ++q) marginalX[q] += blockX[size_t(b) * w + q];
    model.lagX = lagsOf(std::move(marginalX), n);
    model.lagY = lagsOf(std::move(marginalY), n);
    return model;
}

StripField sampleOf(const GaussianModel& model, uint64_t seed, int reachX, int reachY, int threads) {
    const int w = model.w, h = model.h, columns = w / 2 + 1;
    // The sample's spectrum: sqrt(power) times complex white noise of unit variance, Hermitian so the sample
    // is real. Its covariance is the model's: (1/n^2) sum of power e^(2 pi i k.d). Only the half kx <= w/2
    // is stored (the float inverse makes the rest); in its first and last columns, which hold their own
    // partners, each pair of opposite frequencies is drawn once, at the lower row. Floats: the sample is
    // noise, and their transform takes a third of the time.
    const double scale = 1.0 / (double(w) * h);
    std::vector<std::complex<float>> half(size_t(h) * columns);
    parallelFor(h, threads, [&](int begin, int end) {
        for (int r = begin; r < end; ++r)
            for (int q = 0; q < columns; ++q) {
                const bool ownPartner = q == 0 || 2 * q == w;
                const int pr = (h - r) % h;
                if (ownPartner && pr < r) continue;  // drawn with its partner
                const size_t index = size_t(r) * w + q;
                const Complex z = scale * std::sqrt(model.power.at<double>(r, q)) * complexNoise(seed, index);
                if (ownPartner && pr == r) {  // a real frequency: the real part's N(0, 1/2), made N(0, 1)
                    half[size_t(r) * columns + q] = std::complex<float>(float(z.real() * std::numbers::sqrt2), 0.0f);
                    continue;
                }
                half[size_t(r) * columns + q] = std::complex<float>(z);
                if (ownPartner) half[size_t(pr) * columns + q] = std::complex<float>(std::conj(z));
            }
    });
    StripField sample(w, h, reachX, reachY);
    detail::inverseRealDftOfHalf(half.data(), w, h, threads, [&](int y, const float* row) { sample.setRow(y, row); });
    return sample;
}

// The power's 1-D transform across the lines at each k, conjugated and scaled.
cv::Mat lineCovarianceSpectra(const GaussianModel& model, Axis axis, int strip, int threads) {
    const bool across = axis == Axis::X;
    const int w = model.w, h = model.h, along = across ? h : w, length = across ? w : h;
    const double scale = 1.0 / (double(w) * h * length);
    const int lines = along / 2 + 1;
    cv::Mat out(lines, strip, CV_64FC2);
    constexpr int kBlock = 16;
    parallelFor((lines + kBlock - 1) / kBlock, threads, [&](int begin, int end) {
        cv::Mat block(kBlock, length, CV_64F), spectra;
        for (int b = begin; b < end; ++b) {
            const int k0 = b * kBlock, count = std::min(kBlock, lines - k0);
            for (int i = 0; i < count; ++i)
                for (int u = 0; u < length; ++u)
                    block.at<double>(i, u) = across ? model.powerAt(u, k0 + i) : model.powerAt(k0 + i, u);
            cv::dft(block.rowRange(0, count), spectra, cv::DFT_ROWS | cv::DFT_COMPLEX_OUTPUT);
            for (int i = 0; i < count; ++i)
                for (int du = 0; du < strip; ++du) {
                    const cv::Vec2d z = spectra.at<cv::Vec2d>(i, du);
                    out.at<cv::Vec2d>(k0 + i, du) = cv::Vec2d(z[0] * scale, -z[1] * scale);
                }
        }
    });
    return out;
}

StripField topBottomSmoothField(const Field& f, int reachX, int threads) {
    // In floats, from the half spectrum (see sampleOf): the field is only set aside and added back.
    const int w = f.w, h = f.h, columns = w / 2 + 1;
    const double scale = 1.0 / (double(w) * h);
    std::vector<std::complex<float>> half(size_t(h) * columns);
    forSmoothSpectrum(w, h, [&](int x, int y) { return f.at(x, y); }, {.leftRight = false, .topBottom = true}, columns, threads,
                      [&](int r, int q, Complex s) { half[size_t(r) * columns + q] = std::complex<float>(s * scale); });
    StripField out(w, h, reachX, 0);
    detail::inverseRealDftOfHalf(half.data(), w, h, threads, [&](int y, const float* row) { out.setRow(y, row); });
    return out;
}

}  // namespace heightpack::detail
