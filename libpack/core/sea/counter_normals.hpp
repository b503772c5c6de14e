// Internal: standard normal deviates addressed by a counter, so any cell's draw is a pure function of
// (seed, index): cells can be drawn on any thread, in any order, or skipped, and the sea stays the same.
// The uniforms are SplitMix64's outputs (Steele, Lea, Flood 2014: the state advances by a fixed odd
// gamma and each output is a 64-bit finaliser of it), which is counter-based by construction and passes
// BigCrush; the normals come from them by Box-Muller.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

namespace heightpack::detail {

inline constexpr uint64_t kSplitMixGamma = 0x9E3779B97F4A7C15ull;

// SplitMix64's finaliser (Stafford's mix 13): a bijection that scatters every input bit over the output.
constexpr uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// The stream of a seed. Mixed first, so seeds one gamma apart (cascadeBands spaces its seeds so) start
// unrelated streams instead of one stream shifted by an index.
constexpr uint64_t normalStreamKey(uint64_t seed) { return mix64(seed ^ 0x6A09E667F3BCC909ull); }

struct NormalPair {
    double first = 0.0, second = 0.0;
    double radius = 0.0;  // Box-Muller's r: the length of (first, second), to rounding, without a root to take
};

// The two independent standard normal deviates of `index` in the stream `key`: r cos(2 pi u2) and
// r sin(2 pi u2), r = sqrt(-2 ln u1), from SplitMix64 outputs 2 index and 2 index + 1 taken to 53 bits;
// u1 is in (0, 1] so the logarithm is finite. The transcendental part is in float, to the precision the
// sea stores its amplitudes in (sincosf and logf take a third of the time of their double forms); the
// smallest u1, 2^-53, is a float, so the tails reach 8.6 standard deviations as before.
inline NormalPair normalPair(uint64_t key, uint64_t index) {
    const uint64_t a = mix64(key + (2 * index + 1) * kSplitMixGamma);
    const uint64_t b = mix64(key + (2 * index + 2) * kSplitMixGamma);
    const float u1 = float(double((a >> 11) + 1) * 0x1p-53), u2 = float(double(b >> 11) * 0x1p-53);
    const float r = std::sqrt(-2.0f * std::log(u1)), angle = 2.0f * std::numbers::pi_v<float> * u2;
    return {double(r * std::cos(angle)), double(r * std::sin(angle)), double(r)};
}

}  // namespace heightpack::detail
