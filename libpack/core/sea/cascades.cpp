#include "heightpack/core/sea/cascades.hpp"

#include <cmath>
#include <numbers>

namespace heightpack {

std::vector<CascadeBand> cascadeBands(double tileSize, int size, int count, uint64_t seed) {
        std::vector<CascadeBand> bands(count);
    for (int c = 0; c < count; ++c) {
        CascadeBand& b = bands[c];
        b.tileSize = tileSize * std::pow(kCascadeRatio, c);
        const double nyquist = std::numbers::pi * size / b.tileSize;
        b.low = c == 0 ? 0.0 : bands[c - 1].high;
        b.high = c + 1 == count ? nyquist : 0.5 * nyquist;
        // A fixed odd constant (2^64 / golden ratio) apart: the streams of seed s and s + 1 never coincide
        // for different cascades, as plain seed + c would make them.
        b.seed = seed + uint64_t(c) * 0x9E3779B97F4A7C15ull;
    }
    return bands;
}

SpectrumOptions cascadeOptions(const SpectrumOptions& sea, const CascadeBand& band) {
    SpectrumOptions o = sea;
    o.tileSize = band.tileSize;
    o.bandLow = band.low;
    o.bandHigh = band.high;
    o.seed = band.seed;
    return o;
}

}  // namespace heightpack
