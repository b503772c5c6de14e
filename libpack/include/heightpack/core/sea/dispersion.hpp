// How fast a wave of a given length runs: the linear dispersion relation of surface gravity waves,
// w^2 = g k tanh(k d), and the depth factor that follows from it for the TMA spectrum.
#pragma once

namespace heightpack {

inline constexpr double kGravity = 9.81;

// Angular frequency (rad/s) of wavenumber k (rad/m) over water `depth` metres deep: sqrt(g k tanh(k d));
// depth <= 0 means deep water, sqrt(g k). 0 for k <= 0.
double dispersionFrequency(double k, double depth);

// dw/dk at k (m/s, the group velocity): what turns a frequency spectrum S(w) into S(k) = S(w) dw/dk.
double dispersionSlope(double k, double depth);

// The wavenumber whose frequency is omega at this depth (inverse of dispersionFrequency), to 1e-12
// relative. 0 for omega <= 0.
double dispersionWavenumber(double omega, double depth);

// Kitaigorodskii's depth factor phi(w_h), w_h = w sqrt(d / g), that the TMA spectrum multiplies JONSWAP
// by (Bouws et al. 1985): the ratio of k^-3 dk/dw at this depth to its deep-water value, so the
// saturation range keeps its wavenumber form (k^-3) whatever the depth. Closed form, with k the
// finite-depth wavenumber of omega: tanh^2(kd) / (1 + 2kd / sinh(2kd)). Tends to 1 in deep water
// (w_h > 2) and to w_h^2 / 2 in shallow water. 1 for depth <= 0.
double kitaigorodskiiFactor(double omega, double depth);
// The same factor from the wavenumber (no root to find): what the spectrum evaluates per wave vector.
double kitaigorodskiiFactorAtWavenumber(double k, double depth);

}  // namespace heightpack
