// The endpoint search of one BC4 block (block_compression.cpp's encoder): which endpoint pairs are
// tried for 16 values in [0, 1], how each decodes, and which is kept.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

namespace heightpack::bc4 {

// An endpoint pair tried (e0 > e1: eight interpolated values; e0 <= e1: six with 0 and 1), the squared
// error of the block's values decoded with it and the worst. No member initialisers: a block's
// Candidates would otherwise write all 96 before trying a few.
struct Tried {
    int e0, e1;
    float error, worst;
};

// The pairs tried for a block, in the order tried, and the least worst error among them. With
// onlyChoosable, pairs that choose could not take (their worst error bound too large) are not scored.
struct Candidates {
    std::array<Tried, 96> tried;
    int count = 0;
    float leastWorst = 1e30f;
    bool onlyChoosable = false;
    void add(const Tried& t) {
        if (count < int(tried.size())) tried[std::size_t(count++)] = t, leastWorst = std::min(leastWorst, t.worst);
    }
};

// The 8 decoded values of endpoints e0, e1 (codes 0..7), as the specification's table computes them.
std::array<float, 8> palette(int e0, int e1);

// Tries endpoint pairs for the values v (in [0, 1]) into out, thoroughly (the quick pass is
// bc4_quick.hpp's): within a code of the values' range and within two of the least-squares fit to them,
// in the eight-value mode and, for blocks with values near 0 or 1, the six.
void search(const float v[16], Candidates& out);

// The pair with the smallest squared error among those whose worst error is within a quarter code of
// the smallest worst; the first of equals.
const Tried& choose(const Candidates& c);

// Each value's code: its nearest entry of the palette of e0, e1; with decoded, the values they decode to.
std::array<std::uint8_t, 16> codesOf(const float v[16], int e0, int e1, float decoded[16] = nullptr);

// The 8 bytes of a block: the endpoints, then the 16 codes of 3 bits.
void writeBlock(int e0, int e1, const std::array<std::uint8_t, 16>& codes, std::uint8_t* out);

}  // namespace heightpack::bc4
