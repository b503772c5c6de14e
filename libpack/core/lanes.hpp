// Four floats at a time through GCC's vector extension (SSE2 on x86-64, plain code elsewhere): the
// block encoders' inner loops over a 4x4 block's texels, a row of four a step.
#pragma once

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <algorithm>
#include <cmath>

namespace heightpack::lanes {

using Lanes = float __attribute__((vector_size(16)));
using IntLanes = int __attribute__((vector_size(16)));

inline Lanes splat(float x) { return Lanes{x, x, x, x}; }
inline Lanes min(Lanes a, Lanes b) { return a < b ? a : b; }
inline Lanes max(Lanes a, Lanes b) { return a > b ? a : b; }
inline Lanes abs(Lanes a) { return max(a, -a); }
// Non-negative t to the nearest whole number (halves up), as float.
inline Lanes roundUp(Lanes t) { return __builtin_convertvector(__builtin_convertvector(t + 0.5f, IntLanes), Lanes); }
inline Lanes sqrt(Lanes a) {
#if defined(__SSE2__)
    return Lanes(_mm_sqrt_ps(__m128(a)));
#else
    return Lanes{std::sqrt(a[0]), std::sqrt(a[1]), std::sqrt(a[2]), std::sqrt(a[3])};
#endif
}
// The lanes' sum in a fixed order, and their largest.
inline float sum(Lanes a) { return (a[0] + a[1]) + (a[2] + a[3]); }
inline float largest(Lanes a) { return std::max(std::max(a[0], a[1]), std::max(a[2], a[3])); }
inline float smallest(Lanes a) { return std::min(std::min(a[0], a[1]), std::min(a[2], a[3])); }

// A block's 16 values (texel (x, y) at 4y + x) as four rows of four lanes.
struct Rows {
    Lanes row[4];
    explicit Rows(const float v[16]) {
        for (int r = 0; r < 4; ++r) row[r] = Lanes{v[4 * r], v[4 * r + 1], v[4 * r + 2], v[4 * r + 3]};
    }
};

}  // namespace heightpack::lanes
