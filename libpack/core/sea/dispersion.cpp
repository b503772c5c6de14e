#include "heightpack/core/sea/dispersion.hpp"

#include <cmath>

namespace heightpack {

namespace {
// Beyond k d = 20, tanh(k d) is 1 to double precision and cosh would only overflow later: deep water.
constexpr double kDeepKd = 20.0;
bool deep(double k, double depth) { return depth <= 0.0 || k * depth > kDeepKd; }
}  // namespace

double dispersionFrequency(double k, double depth) {
    if (k <= 0.0) return 0.0;
    if (deep(k, depth)) return std::sqrt(kGravity * k);
    return std::sqrt(kGravity * k * std::tanh(k * depth));
}

double dispersionSlope(double k, double depth) {
    if (k <= 0.0) return deep(1.0, depth) ? 0.0 : std::sqrt(kGravity * depth);  // the shallow-water speed
    if (deep(k, depth)) return 0.5 * std::sqrt(kGravity / k);
    const double kd = k * depth, t = std::tanh(kd), c = std::cosh(kd);
    return kGravity * (t + kd / (c * c)) / (2.0 * dispersionFrequency(k, depth));
}

double dispersionWavenumber(double omega, double depth) {
    if (omega <= 0.0) return 0.0;
    const double kDeep = omega * omega / kGravity;
    if (depth <= 0.0) return kDeep;
    // Newton on f(k) = w(k) - omega from the larger of the deep (omega^2 / g) and the shallow-water
    // (omega / sqrt(g d)) guesses, both at or below the root since tanh(x) <= min(1, x): w(k) is increasing
    // and concave, so from below every step stays below the root and the iteration cannot overshoot.
    double k = std::fmax(kDeep, omega / std::sqrt(kGravity * depth));
    for (int i = 0; i < 100; ++i) {
        const double step = (dispersionFrequency(k, depth) - omega) / dispersionSlope(k, depth);
        k -= step;
        if (std::abs(step) <= 1e-14 * k) break;
    }
    return k;
}

double kitaigorodskiiFactorAtWavenumber(double k, double depth) {
    if (depth <= 0.0 || k <= 0.0) return depth <= 0.0 ? 1.0 : 0.0;
    const double kd = k * depth;
    if (kd > kDeepKd) return 1.0;
    const double t = std::tanh(kd);
    return t * t / (1.0 + 2.0 * kd / std::sinh(2.0 * kd));
}

double kitaigorodskiiFactor(double omega, double depth) {
    if (depth <= 0.0) return 1.0;
    return kitaigorodskiiFactorAtWavenumber(dispersionWavenumber(omega, depth), depth);
}

}  // namespace heightpack
