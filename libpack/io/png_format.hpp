// Internal: what the PNG decoder (png_fast.cpp) and encoder (png_write.cpp) share of the format.
#pragma once

#include <algorithm>
#include <cstdlib>

namespace heightpack::detail {

inline constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

// The Paeth predictor (PNG spec 9.4), written so the compiler can use conditional moves: on noisy
// heights a branchy version mispredicts on most bytes.
inline int paeth(int a, int b, int c) {
    const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
    const int ab = pb < pa ? b : a;
    return pc < std::min(pa, pb) ? c : ab;
}

}  // namespace heightpack::detail
