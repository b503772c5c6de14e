// Issue 15's spectra and directions, each against its published formula or a direct integration.
#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <cmath>
#include <numbers>

#include "heightpack/core/sea/dispersion.hpp"
#include "heightpack/core/sea/spectrum.hpp"
#include "heightpack/core/sea/spreading.hpp"

using namespace heightpack;

namespace {

constexpr double g = kGravity;

// kd from w_h^2 = kd tanh(kd) by bisection: the test's own root, independent of the library's Newton.
double kdFor(double omegaH) {
    double lo = 0.0, hi = omegaH * omegaH + omegaH + 1.0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (mid * std::tanh(mid) < omegaH * omegaH ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// Kitaigorodskii's factor from its definition: k^-3 dk/dw at depth over its deep-water value, the
// derivative by central differences of the bisection root.
double phiByDefinition(double omega, double depth) {
    auto k = [&](double w) { return kdFor(w * std::sqrt(depth / g)) / depth; };
    const double h = 1e-5 * omega;
    const double dkdw = (k(omega + h) - k(omega - h)) / (2 * h);
    const double kd = k(omega);
    return std::pow(kd, -3.0) * dkdw / (2 * g * g * std::pow(omega, -5.0));
}

// Simpson's rule over [a, b].
template <class F>
double integrate(F f, double a, double b, int steps = 20000) {
    const double h = (b - a) / steps;
    double sum = f(a) + f(b);
    for (int i = 1; i < steps; ++i) sum += f(a + i * h) * (i % 2 ? 4 : 2);
    return sum * h / 3;
}

SpectrumOptions sea(SpectrumModel model) {
    SpectrumOptions o;
    o.model = model;
    o.windSpeed = 12.0;
    o.fetch = 80000.0;
    return o;
}

}  // namespace

TEST(Dispersion, DeepShallowAndInverse) {
    EXPECT_DOUBLE_EQ(dispersionFrequency(0.1, 0.0), std::sqrt(g * 0.1));
    EXPECT_NEAR(dispersionFrequency(0.1, 1000.0), std::sqrt(g * 0.1), 1e-12);
    // Shallow water: w = k sqrt(g d), every wave at the same speed.
    EXPECT_NEAR(dispersionFrequency(0.001, 2.0) / 0.001, std::sqrt(g * 2.0), 1e-5);
    for (double depth : {0.0, 3.0, 30.0, 300.0})
        for (double k : {0.001, 0.05, 1.0, 40.0}) {
            const double w = dispersionFrequency(k, depth);
            EXPECT_NEAR(dispersionWavenumber(w, depth), k, 1e-10 * k) << depth << " " << k;
            const double h = 1e-6 * k;
            EXPECT_NEAR(dispersionSlope(k, depth), (dispersionFrequency(k + h, depth) - dispersionFrequency(k - h, depth)) / (2 * h),
                        1e-6 * dispersionSlope(k, depth));
        }
}

TEST(Tma, KitaigorodskiiFactorAtKnownDepths) {
    for (double depth : {2.0, 10.0, 30.0}) {
        for (double omegaH : {0.05, 0.3, 0.7, 1.0, 1.4, 2.0, 3.0}) {
            const double omega = omegaH * std::sqrt(g / depth);
            const double kd = kdFor(omegaH);
            const double closed = std::pow(std::tanh(kd), 2) / (1 + 2 * kd / std::sinh(2 * kd));
            EXPECT_NEAR(kitaigorodskiiFactor(omega, depth), closed, 1e-9) << omegaH;
            EXPECT_NEAR(kitaigorodskiiFactor(omega, depth), phiByDefinition(omega, depth), 1e-4) << omegaH;
            // Thompson & Vincent's (1983) piecewise fit, which the TMA papers quote, to within 0.03.
            const double fit = omegaH <= 1 ? 0.5 * omegaH * omegaH : omegaH < 2 ? 1 - 0.5 * std::pow(2 - omegaH, 2) : 1.0;
            EXPECT_NEAR(kitaigorodskiiFactor(omega, depth), fit, 0.03) << omegaH;
        }
    }
    // The limits: 1 in deep water, w_h^2 / 2 in shallow.
    EXPECT_NEAR(kitaigorodskiiFactor(3.0 * std::sqrt(g / 10.0), 10.0), 1.0, 1e-3);
    const double omegaH = 0.02, depth = 5.0;
    EXPECT_NEAR(kitaigorodskiiFactor(omegaH * std::sqrt(g / depth), depth) / (0.5 * omegaH * omegaH), 1.0, 1e-3);
    EXPECT_EQ(kitaigorodskiiFactor(1.0, 0.0), 1.0);
}

TEST(Tma, JonswapAtDepthHasTheFrequencyIntegralsHs) {
    // The variance over k (through the finite-depth dispersion) equals the integral over w of JONSWAP
    // (written out here) times phi: the two routes agree only if S(k) = E(w) dw/dk is right.
    SpectrumOptions o = sea(SpectrumModel::Jonswap);
    o.depth = 12.0;
    const double u = o.windSpeed, f = o.fetch;
    const double alpha = 0.076 * std::pow(u * u / (f * g), 0.22), wp = 22 * std::pow(g * g / (u * f), 1.0 / 3);
    auto jonswap = [&](double w) {
        const double sigma = w <= wp ? 0.07 : 0.09;
        const double r = std::exp(-std::pow(w - wp, 2) / (2 * sigma * sigma * wp * wp));
        return alpha * g * g * std::pow(w, -5) * std::exp(-1.25 * std::pow(wp / w, 4)) * std::pow(3.3, r);
    };
    const double m0 = integrate([&](double w) { return jonswap(w) * phiByDefinition(w, o.depth); }, 0.2, 12.0, 4000);
    EXPECT_NEAR(4 * std::sqrt(spectrumVariance(o)), 4 * std::sqrt(m0), 0.005 * 4 * std::sqrt(m0));
    // Shallower water holds less energy; deep enough water is JONSWAP itself.
    SpectrumOptions deep = o, shallower = o;
    deep.depth = 500.0, shallower.depth = 4.0;
    EXPECT_NEAR(spectrumVariance(deep), spectrumVariance(sea(SpectrumModel::Jonswap)), 1e-6 * spectrumVariance(deep));
    EXPECT_LT(spectrumVariance(shallower), 0.9 * spectrumVariance(o));
}

TEST(PiersonMoskowitz, PeakAndHeightAreThePublishedOnes) {
    // Stewart, Introduction to Physical Oceanography (16.3): wp = 0.877 g / U19.5, Hs = 0.21 U19.5^2 / g,
    // with U19.5 = 1.026 U10.
    const SpectrumOptions o = sea(SpectrumModel::PiersonMoskowitz);
    const double u195 = 1.026 * o.windSpeed;
    EXPECT_NEAR(spectrumPeakOmega(o), 0.877 * g / u195, 0.002 * g / u195);
    EXPECT_NEAR(4 * std::sqrt(spectrumVariance(o)), 0.21 * u195 * u195 / g, 0.01 * 0.21 * u195 * u195 / g);
    const SeaSpectrum spectrum(o);
    const double m0 = integrate([&](double w) { return spectrum.windFrequencySpectrum(w); }, 0.05, 20.0);
    EXPECT_NEAR(spectrumVariance(o), m0, 2e-3 * m0);
}

TEST(Swell, AddsItsOwnHsAtItsOwnPeak) {
    SpectrumOptions o = sea(SpectrumModel::Jonswap);
    const double wind = spectrumVariance(o);
    o.swell.significantHeight = 2.5;
    o.swell.peakPeriod = 12.0;
    o.swell.direction = 250.0;
    EXPECT_NEAR(spectrumVariance(o) - wind, 2.5 * 2.5 / 16, 0.005 * 2.5 * 2.5 / 16);
    double best = 0, bestOmega = 0;
    const SeaSpectrum spectrum(o);
    for (double w = 0.2; w < 1.0; w += 1e-4)
        if (spectrum.swellFrequencySpectrum(w) > best) best = spectrum.swellFrequencySpectrum(w), bestOmega = w;
    EXPECT_NEAR(bestOmega, 2 * std::numbers::pi / 12.0, 2e-4);
    // The normalisation against DNV-RP-C205's A_gamma = 1 - 0.287 ln(gamma), good to a few per cent.
    for (double gamma : {1.0, 2.0, 3.3, 5.0, 7.0})
        EXPECT_NEAR(1.0 / jonswapEnhancementIntegral(gamma), 1 - 0.287 * std::log(gamma), 0.03) << gamma;
    EXPECT_NEAR(jonswapEnhancementIntegral(1.0), 1.0, 1e-12);
    // Its energy travels toward 250 degrees: the directional spectrum at the swell's peak wavenumber.
    const double kp = std::pow(2 * std::numbers::pi / 12.0, 2) / g, dir = 250.0 * std::numbers::pi / 180;
    EXPECT_GT(spectrum.directional(kp * std::cos(dir), kp * std::sin(dir)),
              100 * spectrum.directional(-kp * std::cos(dir), -kp * std::sin(dir)));
}

TEST(Spreading, EveryFunctionIntegratesToOneOverDirection) {
    for (Spreading kind : {Spreading::Cos2, Spreading::Cos2s, Spreading::DonelanBanner}) {
        for (double exponent : {0.0, 2.0, 75.0}) {
            if (exponent > 0 && kind != Spreading::Cos2s) continue;
            const SpreadingOptions o{kind, exponent, 1.0, 12.0};
            for (double ratio : {0.3, 0.8, 1.0, 1.3, 2.5, 6.0}) {
                const double total = integrate([&](double t) { return spreadingFunction(o, t, ratio); }, -std::numbers::pi, std::numbers::pi);
                EXPECT_NEAR(total, 1.0, 1e-4) << nameOf(kind) << " s " << exponent << " w/wp " << ratio;
            }
        }
    }
    // The published forms at a few points.
    EXPECT_NEAR(cos2sNormalisation(1.0), 1.0 / (2 * std::numbers::pi) * 2, 1e-12);  // G(1) = 1/pi: (1 + cos)/2 integrates to pi
    EXPECT_NEAR(mitsuyasuExponent(1.0, 1.0, g), 11.5, 1e-12);          // wp U / g = 1
    EXPECT_NEAR(mitsuyasuExponent(2.0, 1.0, g), 11.5 * std::pow(2.0, -2.5), 1e-12);
    EXPECT_NEAR(donelanBannerBeta(0.9), 2.61 * std::pow(0.9, 1.3), 1e-12);
    EXPECT_NEAR(donelanBannerBeta(1.2), 2.28 * std::pow(1.2, -1.3), 1e-12);
    EXPECT_NEAR(donelanBannerBeta(2.0), std::pow(10.0, -0.4 + 0.8393 * std::exp(-0.567 * std::log(4.0))), 1e-12);
}

TEST(Spreading, TheDirectionalSpectrumKeepsTheOmnidirectionalOne) {
    // Integrated over direction at fixed |k|, S(k, theta) k dtheta gives back S(k): spreading and swell
    // move energy between directions only.
    for (Spreading kind : {Spreading::Cos2, Spreading::Cos2s, Spreading::DonelanBanner}) {
        SpectrumOptions o = sea(SpectrumModel::Jonswap);
        o.spreading = kind;
        o.depth = 25.0;
        o.windDirection = 40.0;
        o.swell.significantHeight = 1.5;
        o.swell.direction = -100.0;
        const SeaSpectrum spectrum(o);
        for (double k : {0.02, 0.06, 0.1, 0.3}) {
            const double around = integrate([&](double t) { return spectrum.directional(k * std::cos(t), k * std::sin(t)) * k; },
                                            -std::numbers::pi, std::numbers::pi);
            EXPECT_NEAR(around, spectrum.omnidirectional(k), 1e-5 * spectrum.omnidirectional(k)) << nameOf(kind) << " " << k;
        }
    }
}

TEST(Spectrum, WavesRunWithTheWind) {
    // Each wave vector along the wind carries one term, h0(k) e^{i(k.x - w t)}: between two instants its
    // DFT bin turns by -w dt, which an independent forward DFT of the heights measures.
    SpectrumOptions o = sea(SpectrumModel::Jonswap);
    o.size = 64, o.tileSize = 200.0, o.depth = 15.0, o.windDirection = 20.0;
    const Ocean ocean(o);
    const double dt = 0.3;
    auto spectrumAt = [&](double t) {
        const Image h = ocean.heights(t);
        cv::Mat field(o.size, o.size, CV_64F), f;
        for (int y = 0; y < o.size; ++y)
            for (int x = 0; x < o.size; ++x) field.at<double>(y, x) = h.at(x, y);
        cv::dft(field, f, cv::DFT_COMPLEX_OUTPUT);
        return f;
    };
    const cv::Mat a = spectrumAt(1.0), b = spectrumAt(1.0 + dt);
    const double dk = 2 * std::numbers::pi / o.tileSize, wind = 20.0 * std::numbers::pi / 180;
    // The heights are float, and so is the transform that makes them: a bin below 1e-5 of the largest is
    // mostly their rounding, and its phase measures nothing.
    const double floor = 1e-5 * cv::norm(a, cv::NORM_INF);
    int checked = 0;
    for (int my = -8; my <= 8; ++my)
        for (int mx = 1; mx <= 8; ++mx) {
            const double kx = mx * dk, ky = my * dk;
            if (kx * std::cos(wind) + ky * std::sin(wind) <= 0.2 * std::hypot(kx, ky)) continue;
            const cv::Vec2d za = a.at<cv::Vec2d>((my + o.size) % o.size, mx), zb = b.at<cv::Vec2d>((my + o.size) % o.size, mx);
            if (std::hypot(za[0], za[1]) < floor) continue;
            const double turned = std::atan2(za[0] * zb[1] - za[1] * zb[0], za[0] * zb[0] + za[1] * zb[1]);
            // To float rounding of the stored heights; running against the wind would be off by 2 w dt.
            EXPECT_NEAR(turned, std::remainder(-dispersionFrequency(std::hypot(kx, ky), o.depth) * dt, 2 * std::numbers::pi), 1e-3);
            ++checked;
        }
    EXPECT_GT(checked, 20);
}

TEST(Spectrum, FiniteDepthSeasStillLoop) {
    SpectrumOptions o = sea(SpectrumModel::PiersonMoskowitz);
    o.size = 64, o.tileSize = 128.0, o.depth = 6.0, o.loopPeriod = 10.0, o.spreading = Spreading::DonelanBanner;
    const Ocean ocean(o);
    const SeaFields a = ocean.fields(0.5, {true, true, true}), b = ocean.fields(10.5, {true, true, true});
    for (size_t i = 0; i < a.heights.pixels.size(); ++i) {
        ASSERT_NEAR(a.heights.pixels[i], b.heights.pixels[i], 1e-5);
        ASSERT_NEAR(a.jacobian.pixels[i], b.jacobian.pixels[i], 1e-5);
    }
    EXPECT_DOUBLE_EQ(std::fmod(angularFrequency(o, 0.3) / (2 * std::numbers::pi / 10.0), 1.0), 0.0);
    EXPECT_LE(angularFrequency(o, 0.3), dispersionFrequency(0.3, 6.0));
}
