#include "gaussian_model.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "heightpack/core/parallel.hpp"

#include "counter_normals.hpp"
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
// Laplacian's symbol, S(0) = 0. apply(r, q, S(q, r)) is called once per frequency, on any thread. Only the
// jumps across the left/right wrap line, or the top/bottom one, are taken when asked.
struct EdgeJumps {
    bool leftRight = true, topBottom = true;
};
template <class Apply>
void forSmoothSpectrum(const Field& g, EdgeJumps jumps, int threads, Apply apply) {
    const int w = g.w, h = g.h;
    cv::Mat leftRight(1, h, CV_64F, cv::Scalar(0)), topBottom(1, w, CV_64F, cv::Scalar(0)), down, across;
    if (jumps.leftRight)
        for (int y = 0; y < h; ++y) leftRight.at<double>(0, y) = g.at(w - 1, y) - g.at(0, y);
    if (jumps.topBottom)
        for (int x = 0; x < w; ++x) topBottom.at<double>(0, x) = g.at(x, h - 1) - g.at(x, 0);
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
            for (int q = 0; q < w; ++q) {
                const cv::Vec2d a = across.at<cv::Vec2d>(0, q);
                apply(r, q, q == 0 && r == 0 ? Complex(0, 0)
                                             : (Complex(d[0], d[1]) * edgeX[q] + Complex(a[0], a[1]) * edgeY[r]) /
                                                   (cosX[q] + cosY[r] - 4));
            }
        }
    });
}

// The DFT of Moisan's periodic component of g, from g's own (spectrum, overwritten): G less the smooth
// field's, the mean set to 0. The periodic component itself is never needed in space.
void toPeriodicSpectrum(const Field& g, cv::Mat& spectrum, int threads) {
    forSmoothSpectrum(g, {}, threads, [&](int r, int q, Complex s) {
        cv::Vec2d& z = spectrum.at<cv::Vec2d>(r, q);
        z = r == 0 && q == 0 ? cv::Vec2d(0, 0) : cv::Vec2d(z[0] - s.real(), z[1] - s.imag());
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

GaussianModel modelOf(const Field& g, double noise, int threads) {
    const int w = g.w, h = g.h;
    const double n = double(w) * h;
    GaussianModel model(w, h);
    cv::Mat spectrum = detail::forwardDft(cv::Mat(h, w, CV_64F, const_cast<double*>(g.v.data())), threads);
    toPeriodicSpectrum(g, spectrum, threads);
    const double floor = n * noise;  // the expected |P(k)|^2 of white noise of that variance
    parallelFor(h, threads, [&](int begin, int end) {
        for (int r = begin; r < end; ++r)
            for (int q = 0; q < w; ++q) {
                const cv::Vec2d a = spectrum.at<cv::Vec2d>(r, q);
                model.power.at<double>(r, q) = std::max(a[0] * a[0] + a[1] * a[1] - floor, 0.0);
            }
    });
    std::vector<double> marginalX(w, 0.0), marginalY(h, 0.0);
    for (int r = 0; r < h; ++r)
        for (int q = 0; q < w; ++q) {
            const double p = model.power.at<double>(r, q);
            marginalX[q] += p;
            marginalY[r] += p;
        }
    model.lagX = lagsOf(std::move(marginalX), n);
    model.lagY = lagsOf(std::move(marginalY), n);
    return model;
}

Field sampleOf(const GaussianModel& model, uint64_t seed, int threads) {
    const int w = model.power.cols, h = model.power.rows;
    // The sample's spectrum: sqrt(power) times complex white noise of unit variance, Hermitian so the sample
    // is real (each pair of opposite frequencies drawn once, at the lower index). Its covariance is the
    // model's: (1/n^2) sum of power e^(2 pi i k.d).
    cv::Mat spectrum(h, w, CV_64FC2);
    parallelFor(h, threads, [&](int begin, int end) {
        for (int r = begin; r < end; ++r)
            for (int q = 0; q < w; ++q) {
                const int pr = (h - r) % h, pq = (w - q) % w;
                const size_t index = size_t(r) * w + q, partner = size_t(pr) * w + pq;
                if (partner < index) continue;  // drawn with its partner
                const Complex z = std::sqrt(model.power.at<double>(r, q)) * complexNoise(seed, index);
                if (partner == index) {  // a real frequency: the real part's N(0, 1/2), made N(0, 1)
                    spectrum.at<cv::Vec2d>(r, q) = cv::Vec2d(z.real() * std::numbers::sqrt2, 0.0);
                    continue;
                }
                spectrum.at<cv::Vec2d>(r, q) = cv::Vec2d(z.real(), z.imag());
                spectrum.at<cv::Vec2d>(pr, pq) = cv::Vec2d(z.real(), -z.imag());
            }
    });
    Field sample(w, h);
    cv::Mat values = sample.mat();
    detail::inverseDft(spectrum, values, threads);
    return sample;
}

// The power's 1-D transform across the lines at each k, conjugated and scaled.
cv::Mat lineCovarianceSpectra(const cv::Mat& power, Axis axis, int strip, int threads) {
    const bool across = axis == Axis::X;
    const int w = power.cols, h = power.rows, along = across ? h : w, length = across ? w : h;
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
                    block.at<double>(i, u) = across ? power.at<double>(k0 + i, u) : power.at<double>(u, k0 + i);
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

Field topBottomSmoothField(const Field& f, int threads) {
    cv::Mat spectrum(f.h, f.w, CV_64FC2);
    forSmoothSpectrum(f, {.leftRight = false, .topBottom = true}, threads,
                      [&](int r, int q, Complex s) { spectrum.at<cv::Vec2d>(r, q) = cv::Vec2d(s.real(), s.imag()); });
    Field out(f.w, f.h);
    cv::Mat values = out.mat();
    detail::inverseDft(spectrum, values, threads);
    return out;
}

}  // namespace heightpack::detail
