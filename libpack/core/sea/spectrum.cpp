#include "heightpack/core/sea/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace heightpack {

namespace {

constexpr double kPmBeta = 0.74;        // Pierson-Moskowitz: exp(-beta (g / (U19.5 w))^4)
constexpr double kU195PerU10 = 1.026;   // the wind at 19.5 m over the wind at 10 m (Stewart's ocean text)

// JONSWAP's peak enhancement exponent r(w): a Gaussian bump of width sigma around the peak.
double enhancementExponent(double omega, double peak) {
    const double sigma = omega <= peak ? 0.07 : 0.09;
    return std::exp(-(omega - peak) * (omega - peak) / (2 * sigma * sigma * peak * peak));
}

// The Pierson-Moskowitz shape in x = w / wp: x^-5 exp(-5/4 x^-4); its integral over x > 0 is 1/5.
double pmShape(double x) { return std::pow(x, -5.0) * std::exp(-1.25 * std::pow(x, -4.0)); }

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// w^-5 exp(-c (p / w)^4) gamma^r(w), the shape JONSWAP, Pierson-Moskowitz (gamma 1) and the swell share.
// Evaluated for every wave vector of a grid (16 million at 4096), so the powers are products, the
// exponential's underflow is returned as the 0 it would give, and the enhancement is skipped where r is
// below e^-50: there gamma^r rounds to exactly 1.
double peakedShape(double omega, double p, double c, double peak, double lnGamma) {
    const double x = p / omega, x2 = x * x, cut = c * x2 * x2;
    if (cut > 746.0) return 0.0;
    const double w2 = omega * omega;
    double shape = std::exp(-cut) / (w2 * w2 * omega);
    if (lnGamma != 0.0) {
        const double sigma = omega <= peak ? 0.07 : 0.09;
        const double d = (omega - peak) / (sigma * peak);
        if (d * d < 100.0) shape *= std::exp(lnGamma * std::exp(-0.5 * d * d));
    }
    return shape;
}

}  // namespace

double jonswapEnhancementIntegral(double gamma) {
    // The enhancement only matters within a few sigma of the peak: outside [0.3, 3] gamma^r - 1 is below
    // 1e-20, so the rest of the integral is the shape's own 1/5, exactly. Simpson's rule on the bump.
    const int steps = 6000;
    const double lo = 0.3, hi = 3.0, h = (hi - lo) / steps;
    double sum = 0.0;
    for (int i = 0; i <= steps; ++i) {
        const double x = lo + i * h;
        const double f = pmShape(x) * (std::pow(gamma, enhancementExponent(x, 1.0)) - 1.0);
        sum += f * (i == 0 || i == steps ? 1.0 : (i % 2 ? 4.0 : 2.0));
    }
    return (0.2 + sum * h / 3.0) / 0.2;
}

SeaSpectrum::SeaSpectrum(const SpectrumOptions& o)
    : options_(o),
      windX_(std::cos(radians(o.windDirection))),
      windY_(std::sin(radians(o.windDirection))),
      lnGamma_(std::log(o.gamma)),
      lnSwellGamma_(std::log(o.swell.gamma)) {
    const double g = kGravity, u = o.windSpeed;
    switch (o.model) {
        case SpectrumModel::Phillips: {
            // The peak of (alpha/2) k^-3 exp(-1/(k Lw)^2) is at k = sqrt(2/3) / Lw.
            const double lw = u * u / g;
            windPeak_ = dispersionFrequency(std::sqrt(2.0 / 3.0) / lw, o.depth);
            break;
        }
        case SpectrumModel::Jonswap:
            jonswapAlpha_ = 0.076 * std::pow(u * u / (o.fetch * g), 0.22);
            windPeak_ = 22.0 * std::pow(g * g / (u * o.fetch), 1.0 / 3.0);
            break;
        case SpectrumModel::PiersonMoskowitz:
            // dS/dw = 0 at w^4 = (4 beta / 5) (g / U19.5)^4.
            windPeak_ = std::pow(0.8 * kPmBeta, 0.25) * g / (kU195PerU10 * u);
            break;
    }
    if (o.swell.significantHeight > 0.0) {
        swellPeak_ = 2 * std::numbers::pi / o.swell.peakPeriod;
        // E(w) = Hs^2/16 * 5 wp^4 w^-5 exp(-5/4 (wp/w)^4) gamma^r / I(gamma): the unenhanced part alone
        // integrates to Hs^2 / 16, and I(gamma) takes the enhancement's share back out.
        const double h = o.swell.significantHeight;
        swellScale_ = h * h / 16.0 * 5.0 * std::pow(swellPeak_, 4.0) / jonswapEnhancementIntegral(o.swell.gamma);
    }
}

double SeaSpectrum::windDeepWater(double omega) const {
    if (omega <= 0.0) return 0.0;
    const SpectrumOptions& o = options_;
    const double g = kGravity;
    if (o.model == SpectrumModel::Jonswap) {
        const double wp = windPeak_;
        return jonswapAlpha_ * g * g * peakedShape(omega, wp, 1.25, wp, lnGamma_);
    }
    if (o.model == SpectrumModel::PiersonMoskowitz) {
        const double w0 = g / (kU195PerU10 * o.windSpeed);
        return 0.0081 * g * g * peakedShape(omega, w0, kPmBeta, w0, 0.0);
    }
    return 0.0;
}

double SeaSpectrum::windFrequencySpectrum(double omega) const {
    return windDeepWater(omega) * kitaigorodskiiFactor(omega, options_.depth);
}

double SeaSpectrum::swellFrequencySpectrum(double omega) const {
    if (swellScale_ <= 0.0 || omega <= 0.0) return 0.0;
    const double wp = swellPeak_;
    return swellScale_ * peakedShape(omega, wp, 1.25, wp, lnSwellGamma_);
}

double SeaSpectrum::windWavenumberSpectrum(double k) const {
    if (k <= 0.0) return 0.0;
    const SpectrumOptions& o = options_;
    if (o.model == SpectrumModel::Phillips) {
        // Defined over wavenumber: depth only changes how fast its waves run, not their heights.
        const double lw = o.windSpeed * o.windSpeed / kGravity;  // the largest wave the wind raises
        const double l = o.smallWaveLength > 0 ? o.smallWaveLength : lw / 1000.0;
        return 0.5 * o.phillipsAlpha * std::exp(-1.0 / (k * lw * k * lw)) / (k * k * k) * std::exp(-k * k * l * l);
    }
    // S(k) = E(w(k)) dw/dk, the TMA factor taken at this k (no root to find). In deep water this is
    // E(sqrt(g k)) * 0.5 sqrt(g / k), as before depth came in.
    const double w = dispersionFrequency(k, o.depth);
    return windDeepWater(w) * kitaigorodskiiFactorAtWavenumber(k, o.depth) * dispersionSlope(k, o.depth);
}

double SeaSpectrum::swellWavenumberSpectrum(double k) const {
    if (swellScale_ <= 0.0 || k <= 0.0) return 0.0;
    return swellFrequencySpectrum(dispersionFrequency(k, options_.depth)) * dispersionSlope(k, options_.depth);
}

double SeaSpectrum::omnidirectional(double k) const { return windWavenumberSpectrum(k) + swellWavenumberSpectrum(k); }

double SeaSpectrum::directional(double kx, double ky) const { return directional(kx, ky, std::hypot(kx, ky)); }

double SeaSpectrum::directional(double kx, double ky, double k) const {
    if (k <= 0.0) return 0.0;
    const SpectrumOptions& o = options_;
    // Only the spreadings that depend on frequency need it: not taken for cos2 without a swell.
    auto frequency = [&] { return dispersionFrequency(k, o.depth); };
    double sum = 0.0;
    if (o.spreading == Spreading::Cos2) {
        // The common case without an arc tangent: cos(theta - wind) from the dot product. Half the plane
        // (against the wind) is zero: the spectrum is not evaluated there.
        const double c = (kx * windX_ + ky * windY_) / k;
        if (c > 0.0)
            if (const double s = windWavenumberSpectrum(k); s > 0.0) sum += s / k * ((2.0 / std::numbers::pi) * c * c);
    } else if (const double s = windWavenumberSpectrum(k); s > 0.0) {
        sum += s / k * spreadingFunction({o.spreading, o.spreadingExponent, windPeak_, o.windSpeed},
                                         std::atan2(ky, kx) - radians(o.windDirection), frequency());
    }
    if (const double s = swellWavenumberSpectrum(k); s > 0.0) {
        const SpreadingOptions narrow{Spreading::Cos2s, o.swell.spreadingExponent, swellPeak_, o.windSpeed};
        sum += s / k * spreadingFunction(narrow, std::atan2(ky, kx) - radians(o.swell.direction), frequency());
    }
    return sum;
}

double omnidirectionalSpectrum(const SpectrumOptions& options, double k) { return SeaSpectrum(options).omnidirectional(k); }

double directionalSpectrum(const SpectrumOptions& options, double kx, double ky) {
    return SeaSpectrum(options).directional(kx, ky);
}

double spectrumVariance(const SpectrumOptions& o, double lo, double hi) {
    // Trapezoids in log k, 2000 per decade: fine enough for the narrowest peak (a swell's, gamma 5).
    const SeaSpectrum spectrum(o);
    const double a = std::log(std::fmax(lo, 1e-5)), b = std::log(std::fmin(hi, 1e4));
    if (b <= a) return 0.0;
    const int steps = std::max(16, static_cast<int>((b - a) / std::log(10.0) * 2000));
    double sum = 0.0, previous = 0.0;
    for (int i = 0; i <= steps; ++i) {
        const double k = std::exp(a + (b - a) * i / steps);
        const double f = spectrum.omnidirectional(k) * k;  // dk = k d(log k)
        if (i > 0) sum += 0.5 * (f + previous) * (b - a) / steps;
        previous = f;
    }
    return sum;
}

double spectrumVariance(const SpectrumOptions& o) { return spectrumVariance(o, 0.0, 1e4); }

double spectrumPeakOmega(const SpectrumOptions& o) {
    // E(w) = S(k) dk/dw on a log grid of w, 1e-4 apart: the peak to 0.01 %.
    const SeaSpectrum spectrum(o);
    double best = 0.0, bestOmega = 0.0;
    const double lo = std::log(0.01), hi = std::log(100.0);
    const int steps = 92104;
    for (int i = 0; i <= steps; ++i) {
        const double w = std::exp(lo + (hi - lo) * i / steps);
        const double k = dispersionWavenumber(w, o.depth);
        const double e = spectrum.omnidirectional(k) / dispersionSlope(k, o.depth);
        if (e > best) best = e, bestOmega = w;
    }
    return bestOmega;
}

double angularFrequency(const SpectrumOptions& o, double k) {
    const double w = dispersionFrequency(k, o.depth);
    if (o.loopPeriod <= 0.0) return w;
    const double w0 = 2 * std::numbers::pi / o.loopPeriod;
    return std::floor(w / w0) * w0;
}

}  // namespace heightpack
