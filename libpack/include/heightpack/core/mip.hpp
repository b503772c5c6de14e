// Resampling and mip chains with a wrap mode honoured by every filter tap.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "heightpack/core/image.hpp"

namespace heightpack {

// Reconstruction filters, each a function of the distance in destination texels.
enum class Filter {
    Box,       // 2x2 average when halving; radius 0.5
    Triangle,  // tent, radius 1
    Lanczos3,  // sinc windowed by sinc, radius 3
    Kaiser,    // sinc windowed by a Kaiser-Bessel window (alpha 4), radius 3; sharp with little ringing
};

template <>
struct NameTable<Filter> {
    static constexpr EnumName<Filter> entries[] = {
        {Filter::Box, "box", "2x2 average when halving"},
        {Filter::Triangle, "triangle", "tent, radius 1"},
        {Filter::Lanczos3, "lanczos3", "sinc windowed by sinc, radius 3"},
        {Filter::Kaiser, "kaiser", "sinc windowed by Kaiser-Bessel, radius 3"},
    };
};
inline const char* filterName(Filter filter) { return nameOf(filter); }

// The filter's value at distance x (in destination texels). Exposed for tests and documentation.
double filterWeight(Filter filter, double x);
// How far from its centre the filter is non-zero, in destination texels.
double filterRadius(Filter filter);

struct MipOptions {
    Filter filter = Filter::Kaiser;
    Wrap wrap = Wrap::Periodic;
    int threads = 0;  // 0 = all cores; the result does not depend on it
};

// Resamples every channel of src to width x height. Texel centres stay aligned: destination texel i
// sits at source position (i + 0.5) * src / dst - 0.5. When shrinking, the filter widens by the ratio so
// it averages rather than aliases. Filters with negative lobes may overshoot the input's range; nothing
// is clamped. width and height must be positive.
Image resample(const Image& src, int width, int height, const MipOptions& options);

// The number of levels of a full chain down to 1x1: 1 + log2(max(width, height)) for power-of-two sizes.
int mipLevelCount(int width, int height);
// The side of level `level` of a chain whose level 0 has side `size` (ROUND_DOWN, never below 1).
inline int mipLevelSide(int size, int level) { return size >> level > 0 ? size >> level : 1; }
bool isPowerOfTwo(int n);
// The smallest power of two not less than n (n >= 1).
int nextPowerOfTwo(int n);

// The full mip chain of level0 (whose sides must be powers of two, not necessarily equal): level L is
// max(1, W >> L) x max(1, H >> L), each made from the level above with the filter and wrap mode.
std::vector<Image> generateMipChain(const Image& level0, const MipOptions& options);
// The same, taking level0 as the chain's first level rather than copying it.
std::vector<Image> generateMipChain(Image&& level0, const MipOptions& options);
// The chain's levels below level0 (1, 2, ...): for a reader of the whole chain that has level0 already.
std::vector<Image> generateMipLevelsBelow(const Image& level0, const MipOptions& options);
inline std::vector<Image> generateMipChain(const Image& level0, Filter filter) {
    MipOptions options;
    options.filter = filter;
    return generateMipChain(level0, options);
}

}  // namespace heightpack
