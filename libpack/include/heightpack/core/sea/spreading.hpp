// Directional spreading D(theta): how a sea's energy at one frequency shares itself among directions.
// Every function here integrates to 1 over the circle, so it moves energy between directions without
// adding or removing any.
#pragma once

#include <optional>
#include <string_view>

#include "heightpack/core/names.hpp"

namespace heightpack {

enum class Spreading {
    Cos2,           // (2/pi) cos^2(theta) on the half-plane the wind blows toward, nothing against it
    Cos2s,          // Longuet-Higgins et al. 1963: G(s) cos^2s(theta / 2), s from Mitsuyasu 1975 or given
    DonelanBanner,  // Donelan, Hamilton & Hui 1985 (Banner 1990 above 1.6 wp): (beta / 2) sech^2(beta theta)
};
template <>
struct NameTable<Spreading> {
    static constexpr EnumName<Spreading> entries[] = {
        {Spreading::Cos2, "cos2", "(2/pi) cos^2 toward the wind, nothing against it"},
        {Spreading::Cos2s, "cos2s", "cos^2s(theta/2), s from Mitsuyasu's fit or given"},
        {Spreading::DonelanBanner, "donelan-banner", "sech^2 with Donelan-Banner's beta(w/wp)"},
    };
};

// The cos-2s normalisation G(s) = 2^(2s-1) Gamma(s+1)^2 / (pi Gamma(2s+1)), so that
// G(s) cos^2s(theta / 2) integrates to 1 over [-pi, pi]. s >= 0.
double cos2sNormalisation(double s);

// Mitsuyasu et al. 1975's spreading exponent, as Goda writes it: s = s_p (w/wp)^5 below the peak and
// s_p (w/wp)^-2.5 above, with s_p = 11.5 (wp U10 / g)^-2.5 (young seas spread wider).
double mitsuyasuExponent(double omega, double peakOmega, double windSpeed);

// Donelan-Banner's beta(w/wp): 2.61 r^1.3 for r < 0.95 (held at r = 0.56 below it, where the fit ends),
// 2.28 r^-1.3 up to 1.6, and Banner's 10^(-0.4 + 0.8393 exp(-0.567 ln(r^2))) above.
double donelanBannerBeta(double omegaRatio);

// What one spreading function needs besides the angle.
struct SpreadingOptions {
    Spreading kind = Spreading::Cos2;
    double exponent = 0.0;   // cos-2s: s; 0 = Mitsuyasu's s(w)
    double peakOmega = 1.0;  // rad/s: the sea's peak, for Mitsuyasu and Donelan-Banner
    double windSpeed = 10.0; // m/s, for Mitsuyasu's s_p
};

// D(theta) at angular frequency omega, theta the angle (radians) between the wave's travel and the mean
// direction. Integrates to 1 over theta in [-pi, pi) at every omega.
double spreadingFunction(const SpreadingOptions& options, double theta, double omega);

}  // namespace heightpack
