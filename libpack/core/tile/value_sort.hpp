// Internal: a stable sort of float values by value, with their indices: the exact ranks that the
// Gaussianiser (gaussianise.hpp) falls back on and the quantisation measure of tile/resynthesis.cpp uses.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "buffer.hpp"

namespace heightpack::detail {

// The permutation that sorts values (finite, fewer than 2^32) by value, equal values in index order; on
// `threads` threads (0 = all cores), with one result whatever their number.
std::vector<uint32_t> stableOrder(std::span<const float> values, int threads);
// The same sort as (key << 32 | index) items, the key a value's bits in an order that sorts as the float
// does (-0 as +0).
Buffer<uint64_t> sortedItems(std::span<const float> values, int threads);

// A float's bits as an unsigned key that sorts as the float does (negatives flipped, positives with the
// sign bit set); -0 counts as +0, as comparison has it.
inline uint32_t keyOf(float v) {
    uint32_t u;
    const float canonical = v == 0.0f ? 0.0f : v;
    std::memcpy(&u, &canonical, sizeof u);
    return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

inline float valueOfKey(uint32_t key) {
    const uint32_t u = (key & 0x80000000u) ? (key & 0x7fffffffu) : ~key;
    float v;
    std::memcpy(&v, &u, sizeof v);
    return v;
}


}  // namespace heightpack::detail
