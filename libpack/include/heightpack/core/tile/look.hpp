// What the eye sees in a tiled map beyond its seams: a frame around every tile, blobs along its edges and
// at its corners, and an echo of one feature repeated inside the tile. Each is a statistic of the
// tile-aligned grid compared with the same statistic on every other placement of the grid over the same
// map, so that a map whose tile edges are like any other cut scores like any cut.
#pragma once

#include <optional>

#include "heightpack/core/image.hpp"

namespace heightpack {

// Thresholds calibrated on exactly periodic fields, which must all pass: tests/bench/heightpack_look_rates
// --count 1000 (power-law spectra k^-1.5 to k^-4, isotropic and up to 3:1 directional, 64 to 1024 texels,
// 8-bit, 16-bit and float) gives at most frame 6.9, blobs 7.3, echo 0.10 on them (p99 4.7, 4.3, 0.06).
// Frame and blobs are z-scores (how many standard deviations the tile-aligned grid lies from the other
// placements); echo is a correlation. The old default on the bundled painting scored frame 8.7 and echo 0.23;
// a band of 1/16 of the tile keeping 30% of its finest detail scores frame 8 to 10; a bump of six
// deviations at the corner, blobs 9 to 14; an offset-and-blend, echo 0.2 to 0.4.
inline constexpr double kDefaultFrameThreshold = 7.5;
inline constexpr double kDefaultBlobThreshold = 8.0;
inline constexpr double kDefaultEchoThreshold = 0.15;

struct LookThresholds {
    double frame = kDefaultFrameThreshold;
    double blobs = kDefaultBlobThreshold;
    double echo = kDefaultEchoThreshold;
};

struct TileLook {
    bool measured = false;  // false below 64 texels a side: too few placements to compare with
    // Frame: the local band-pass energy (octaves from 1-2 texels to 1/64-1/32 of the tile) averaged in
    // rings at each distance from the tile's edges (1, 2, 4, ... texels out to an eighth of the tile), as a
    // log ratio to the map's mean energy; the largest |z| of a ring against the rings of the grid placed
    // anywhere else.
    double frame = 0.0;
    // Blobs: the squared standardised band-pass at a blob's scale (1/128 to 1/32 of the tile) averaged in
    // the same rings along the edges and in squares of 1/16 and 1/8 of the tile around the corner; the
    // largest |z| (of logs: squared values are skewed).
    double blobs = 0.0;
    // Echo: the largest autocorrelation of the tile whitened by its own smoothed spectrum (so a field's
    // natural correlation divides out) at lags beyond 1/16 of the tile, less the same of the map it was
    // made from when there is one (echoBaseline), else as it is; never below 0.
    double echo = 0.0;
    double echoBaseline = 0.0;  // the source's own (0 when not given)
    bool passes(const LookThresholds& t = {}) const {
        return !measured || (frame <= t.frame && blobs <= t.blobs && echo <= t.echo);
    }
};

struct LookOptions {
    // The map a tile was made from: its own echo is subtracted (a map with a repeated feature keeps it).
    const Image* source = nullptr;
    int threads = 0;  // 0 = all cores; the result does not depend on it
    // sourceEchoOf(*source), when the caller judges several tiles of one source and has measured it once.
    std::optional<double> sourceEcho;
};

// The statistics of one level (channel 0), as a tile (periodic). Maps larger than 2048 texels on a side
// are judged on a 2x box-reduced copy: the statistics are of scales the eye sees at that size.
TileLook measureTileLook(const Image& map, const LookOptions& options = {});

// The largest autocorrelation of the whitened map at lags beyond 1/16 of its size (circular).
double echoOf(const Image& map, int threads = 0);

// The echo a tile made from source inherits from it (of its periodic component, at most 2048 texels a
// side, never below 0): what measureTileLook subtracts as echoBaseline.
double sourceEchoOf(const Image& source, int threads = 0);

}  // namespace heightpack
