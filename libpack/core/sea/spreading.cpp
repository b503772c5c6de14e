#include "heightpack/core/sea/spreading.hpp"

#include <cmath>
#include <numbers>

namespace heightpack {

namespace {

// The angle brought into [-pi, pi].
double wrapAngle(double theta) { return std::remainder(theta, 2 * std::numbers::pi); }
}  // namespace

double cos2sNormalisation(double s) {
    // Through log-gamma: s reaches the hundreds for swell, where Gamma(2s + 1) overflows.
    return std::exp((2 * s - 1) * std::log(2.0) + 2 * std::lgamma(s + 1) - std::lgamma(2 * s + 1)) / std::numbers::pi;
}

double mitsuyasuExponent(double omega, double peakOmega, double windSpeed) {
    const double sp = 11.5 * std::pow(peakOmega * windSpeed / 9.81, -2.5);
    const double r = omega / peakOmega;
    return r < 1.0 ? sp * std::pow(r, 5.0) : sp * std::pow(r, -2.5);
}

double donelanBannerBeta(double omegaRatio) {
    const double r = omegaRatio;
    if (r < 0.95) return 2.61 * std::pow(std::fmax(r, 0.56), 1.3);
    if (r < 1.6) return 2.28 * std::pow(r, -1.3);
    return std::pow(10.0, -0.4 + 0.8393 * std::exp(-0.567 * std::log(r * r)));
}

double spreadingFunction(const SpreadingOptions& o, double theta, double omega) {
    theta = wrapAngle(theta);
    switch (o.kind) {
        case Spreading::Cos2: {
            const double c = std::cos(theta);
            return c > 0.0 ? (2.0 / std::numbers::pi) * c * c : 0.0;
        }
        case Spreading::Cos2s: {
            const double s = o.exponent > 0.0 ? o.exponent : mitsuyasuExponent(omega, o.peakOmega, o.windSpeed);
            // cos(theta / 2) >= 0 on [-pi, pi]; pow of 0 is 0 for s > 0, and 1 (uniform) for s = 0.
            return cos2sNormalisation(s) * std::pow(std::cos(0.5 * theta), 2 * s);
        }
        case Spreading::DonelanBanner: {
            const double beta = donelanBannerBeta(omega / o.peakOmega);
            const double c = std::cosh(beta * theta);
            // (beta/2) sech^2 integrates to tanh(beta pi) over [-pi, pi], not quite 1 for the broad
            // spreading far above the peak: divided by it, so no energy is lost behind the circle.
            return 0.5 * beta / (c * c) / std::tanh(beta * std::numbers::pi);
        }
    }
    return 0.0;
}

}  // namespace heightpack
