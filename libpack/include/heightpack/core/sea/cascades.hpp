// Cascades: one spectrum baked into several tiles of different sizes, each keeping its own band of
// wavenumbers, so that together they reach from swell to ripples with every wave counted once.
#pragma once

#include <cstdint>
#include <vector>

#include "heightpack/core/sea/spectrum.hpp"

namespace heightpack {

// Tile c is tileSize * (17/61)^c across. 61 and 17 are primes, so no two tile sizes share a small common
// factor: the sum of the tiles repeats only where all of them do, at their least common multiple
// (17 tiles of cascade 0 for two cascades, 289 for three), where tiles whose sizes halve would repeat
// with the largest tile and show its pattern every tile.
inline constexpr double kCascadeRatio = 17.0 / 61.0;

// At most 4 cascades (the last of 4 is (17/61)^3 = 2% of the first), each at least 32 texels across:
// a band between half the coarser tile's Nyquist and its own needs several rings of wave vectors.
inline constexpr int kMaxCascades = 4;
inline constexpr int kCascadeMinSize = 32;

struct CascadeBand {
    double tileSize = 0.0;  // m
    double low = 0.0;       // rad/m: the band this tile keeps is low <= |k| < high
    double high = 0.0;
    uint64_t seed = 0;      // its own random stream, so the tiles are independent
};

// The bands of `count` cascades over `size`-texel tiles, the first tileSize across: they partition
// [0, the last tile's Nyquist pi size / its tile size). Each boundary is at half the larger tile's
// Nyquist wavenumber, where that tile still samples every wave at 4 texels or more and the next, finer
// tile already has several rings of wave vectors. count 1: one band [0, Nyquist).
std::vector<CascadeBand> cascadeBands(double tileSize, int size, int count, uint64_t seed);

// The options of cascade `band` of a sea: its tile size, band and seed.
SpectrumOptions cascadeOptions(const SpectrumOptions& sea, const CascadeBand& band);

}  // namespace heightpack
