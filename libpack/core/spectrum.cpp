#include "heightpack/core/spectrum.hpp"

#include <opencv2/core.hpp>

#include <cassert>
#include <cmath>
#include <random>

#include "heightpack/core/mip.hpp"

namespace heightpack {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Standard normal deviates from a generator the C++ standard pins down bit for bit (mt19937_64), by
// Box-Muller, so a seed gives the same map with any standard library.
class Gaussian {
public:
    explicit Gaussian(uint64_t seed) : engine_(seed) {}
    double next() {
        if (hasSpare_) {
            hasSpare_ = false;
            return spare_;
        }
        double u1 = 0.0;
        while (u1 <= 0.0) u1 = uniform();
        const double u2 = uniform();
        const double r = std::sqrt(-2.0 * std::log(u1));
        spare_ = r * std::sin(2 * kPi * u2);
        hasSpare_ = true;
        return r * std::cos(2 * kPi * u2);
    }

private:
    double uniform() { return double(engine_() >> 11) * (1.0 / 9007199254740992.0); }
    std::mt19937_64 engine_;
    double spare_ = 0.0;
    bool hasSpare_ = false;
};

}  // namespace


double omnidirectionalSpectrum(const SpectrumOptions& o, double k) {
    if (k <= 0.0) return 0.0;
    const double g = kGravity;
    if (o.model == SpectrumModel::Phillips) {
        const double lw = o.windSpeed * o.windSpeed / g;  // the largest wave the wind raises
        const double l = o.smallWaveLength > 0 ? o.smallWaveLength : lw / 1000.0;
        return 0.5 * o.phillipsAlpha * std::pow(k, -3.0) * std::exp(-1.0 / (k * lw * k * lw)) * std::exp(-k * k * l * l);
    }
    // JONSWAP in frequency, moved to wavenumber with w = sqrt(g k): S(k) = S(w) dw/dk.
    const double u = o.windSpeed, f = o.fetch;
    const double alpha = 0.076 * std::pow(u * u / (f * g), 0.22);
    const double wp = 22.0 * std::pow(g * g / (u * f), 1.0 / 3.0);
    const double w = std::sqrt(g * k);
    const double sigma = w <= wp ? 0.07 : 0.09;
    const double r = std::exp(-(w - wp) * (w - wp) / (2 * sigma * sigma * wp * wp));
    const double sw = alpha * g * g * std::pow(w, -5.0) * std::exp(-1.25 * std::pow(wp / w, 4.0)) * std::pow(o.gamma, r);
    return sw * 0.5 * std::sqrt(g / k);
}

double directionalSpectrum(const SpectrumOptions& o, double kx, double ky) {
    const double k = std::hypot(kx, ky);
    if (k <= 0.0) return 0.0;
    const double wind = o.windDirection * kPi / 180.0;
    const double c = (kx * std::cos(wind) + ky * std::sin(wind)) / k;  // cos(theta - wind)
    if (c <= 0.0) return 0.0;
    return omnidirectionalSpectrum(o, k) / k * (2.0 / kPi) * c * c;
}

double spectrumVariance(const SpectrumOptions& o) {
    // Trapezoids in log k from far below to far above any peak the models have.
    double sum = 0.0;
    const int steps = 20000;
    const double lo = std::log(1e-5), hi = std::log(1e4);
    double previous = 0.0;
    for (int i = 0; i <= steps; ++i) {
        const double lk = lo + (hi - lo) * i / steps, k = std::exp(lk);
        const double f = omnidirectionalSpectrum(o, k) * k;  // dk = k d(log k)
        if (i > 0) sum += 0.5 * (f + previous) * (hi - lo) / steps;
        previous = f;
    }
    return sum;
}

double angularFrequency(const SpectrumOptions& o, double k) {
    const double w = std::sqrt(kGravity * k);
    if (o.loopPeriod <= 0.0) return w;
    const double w0 = 2 * kPi / o.loopPeriod;
    return std::floor(w / w0) * w0;
}

Ocean::Ocean(const SpectrumOptions& options) : options_(options) {
    assert(isPowerOfTwo(options.size) && options.tileSize > 0);
    const int n = options.size;
    const double dk = 2 * kPi / options.tileSize;
    amplitudeRe_.assign(size_t(n) * n, 0.0);
    amplitudeIm_.assign(size_t(n) * n, 0.0);
    omega_.assign(size_t(n) * n, 0.0);
    Gaussian gaussian(options.seed);
    for (int r = 0; r < n; ++r) {
        for (int q = 0; q < n; ++q) {
            // Drawn for every cell in the same order, used or not, so a seed means the same sea at any setting.
            const double xr = gaussian.next(), xi = gaussian.next();
            const int m = q < n / 2 ? q : q - n, p = r < n / 2 ? r : r - n;
            // The Nyquist row and column have no partner -k on the grid: left empty so the field is real.
            if (m == -n / 2 || p == -n / 2) continue;
            const double kx = m * dk, ky = p * dk;
            const double s = directionalSpectrum(options, kx, ky) * dk * dk;
            // Half the variance here, half through the conjugate partner's term in heights().
            const double a = std::sqrt(s / 2.0) / std::sqrt(2.0);
            const size_t i = size_t(r) * n + q;
            amplitudeRe_[i] = a * xr;
            amplitudeIm_[i] = a * xi;
            omega_[i] = angularFrequency(options, std::hypot(kx, ky));
            resolvedVariance_ += s;
        }
    }
}

Image Ocean::transform(double t, int component) const {
    const int n = options_.size;
    const double dk = 2 * kPi / options_.tileSize;
    // h(k, t) = h0(k) e^{i w t} + conj(h0(-k)) e^{-i w t}: Hermitian in k, so the sea is real. Component 1
    // and 2 multiply it by -i kx / |k| and -i ky / |k|, odd and imaginary: still Hermitian.
    cv::Mat spectrum(n, n, CV_64FC2, cv::Scalar(0, 0));
    for (int r = 0; r < n; ++r) {
        for (int q = 0; q < n; ++q) {
            const size_t i = size_t(r) * n + q;
            const size_t j = size_t((n - r) % n) * n + (n - q) % n;  // -k
            const double c = std::cos(omega_[i] * t), s = std::sin(omega_[i] * t);
            double re = amplitudeRe_[i] * c - amplitudeIm_[i] * s + amplitudeRe_[j] * c - amplitudeIm_[j] * s;
            double im = amplitudeRe_[i] * s + amplitudeIm_[i] * c - (amplitudeRe_[j] * s + amplitudeIm_[j] * c);
            if (component > 0) {
                const int m = q < n / 2 ? q : q - n, p = r < n / 2 ? r : r - n;
                const double kx = m * dk, ky = p * dk, k = std::hypot(kx, ky);
                const double f = k > 0 ? (component == 1 ? kx : ky) / k : 0.0;
                const double newRe = im * f, newIm = -re * f;  // (re + i im) * (-i f)
                re = newRe;
                im = newIm;
            }
            spectrum.at<cv::Vec2d>(r, q) = cv::Vec2d(re, im);
        }
    }
    cv::Mat field;
    cv::dft(spectrum, field, cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT);  // no 1/N: h(x) = sum over k
    Image out(n, n, 1);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) out.at(x, y) = static_cast<float>(field.at<double>(y, x));
    return out;
}

Image Ocean::heights(double t) const { return transform(t, 0); }

Image Ocean::displacement(double t) const {
    const Image dx = transform(t, 1), dy = transform(t, 2);
    Image out(dx.width, dx.height, 2);
    for (size_t i = 0; i < dx.pixels.size(); ++i) {
        out.pixels[2 * i] = dx.pixels[i];
        out.pixels[2 * i + 1] = dy.pixels[i];
    }
    return out;
}

}  // namespace heightpack
