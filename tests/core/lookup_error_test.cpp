// The packed-lookup error of a stored chain, against a brute force: a plain double-precision bilinear
// (test_support's referenceBilinear, which shares no code with libpack) of the float chain and of the
// rounded chain, compared at 8 x 8 points per texel, on analytic fields and random maps, both wrap modes.
#include <gtest/gtest.h>

#include <cmath>

#include "heightpack/core/lookup_error.hpp"
#include "heightpack/core/mip.hpp"

#include "support/test_support.hpp"

using namespace heightpack;
using heightpack::test::makeImage;
using heightpack::test::randomImage;
using heightpack::test::referenceBilinear;

namespace {

double bruteForce(const Image& level, const TexelRounding& stored, bool periodic) {
    Image rounded = level;
    for (float& v : rounded.pixels) v = stored(v);
    constexpr int kPerTexel = 8;
    double worst = 0.0;
    for (int sy = 0; sy < level.height * kPerTexel; ++sy)
        for (int sx = 0; sx < level.width * kPerTexel; ++sx) {
            const double u = (double(sx) / kPerTexel + 0.5) / level.width;
            const double v = (double(sy) / kPerTexel + 0.5) / level.height;
            worst = std::max(worst, std::fabs(referenceBilinear(rounded, u, v, periodic) -
                                              referenceBilinear(level, u, v, periodic)));
        }
    return worst;
}

// Rounding to a grid of 1/1024 (about a half float's step in [0.5, 1)) and to 16-bit codes over [lo, hi].
float toGrid(float v) { return static_cast<float>(std::nearbyint(double(v) * 1024.0) / 1024.0); }
TexelRounding codes(double lo, double hi) {
    return [lo, hi](float v) {
        const double u = std::nearbyint((double(v) - lo) / (hi - lo) * 65535.0);
        return static_cast<float>(lo + (hi - lo) * u / 65535.0);
    };
}

}  // namespace

TEST(LookupError, EqualsABruteForceBilinearOfBothChainsAtEveryLevel) {
    const std::vector<Image> fields = {
        makeImage(32, 16, [](int x, int y) { return float(0.5 + 0.4 * std::sin(x * 0.41) * std::cos(y * 0.73)); }),
        makeImage(16, 16, [](int x, int y) { return float(0.01 * x + 0.02 * y); }),  // a ramp: clamp and wrap differ
        randomImage(16, 32, 3), randomImage(32, 8, 17, -2.0f, 5.0f),
    };
    for (size_t f = 0; f < fields.size(); ++f)
        for (const Wrap wrap : {Wrap::Periodic, Wrap::Clamp}) {
            MipOptions mip;
            mip.wrap = wrap;
            const std::vector<Image> chain = generateMipChain(fields[f], mip);
            double lo = 1e30, hi = -1e30;
            for (const Image& level : chain)
                for (float v : level.pixels) lo = std::min(lo, double(v)), hi = std::max(hi, double(v));
            for (const TexelRounding& stored : {TexelRounding(toGrid), codes(lo, hi)}) {
                const std::vector<double> errors = worstLookupError(chain, stored, 2);
                ASSERT_EQ(errors.size(), chain.size());
                for (size_t l = 0; l < chain.size(); ++l) {
                    const double reference = bruteForce(chain[l], stored, wrap == Wrap::Periodic);
                    EXPECT_NEAR(errors[l], reference, 1e-12) << "field " << f << " " << nameOf(wrap) << " level " << l;
                    EXPECT_GT(errors[l], 0.0);
                }
            }
        }
}

TEST(LookupError, FloatIsExactAndAConstantShiftIsItself) {
    const std::vector<Image> chain = generateMipChain(randomImage(16, 16, 5), Filter::Kaiser);
    for (const double e : worstLookupError(chain, TexelRounding([](float v) { return v; }))) EXPECT_EQ(e, 0.0);
    for (const double e : worstLookupError(chain, TexelRounding([](float v) { return v + 0.25f; })))
        EXPECT_NEAR(e, 0.25, 1e-6);
}

TEST(LookupError, EveryChannelCountsAndTheResultIgnoresThreads) {
    // Two channels, only the second rounded: the error is the second's.
    Image two(8, 4, 2);
    for (size_t i = 0; i < two.pixels.size(); ++i) two.pixels[i] = float(i % 2 ? 0.3 + 0.001 * i : 0.5);
    const TexelRounding coarse = [](float v) { return v == 0.5f ? v : float(std::nearbyint(v * 16.0) / 16.0); };
    Image second(8, 4, 1);
    for (size_t t = 0; t < second.texelCount(); ++t) second.pixels[t] = two.pixels[2 * t + 1];
    const double alone = worstLookupError({second}, coarse)[0];
    EXPECT_GT(alone, 0.0);
    EXPECT_EQ(worstLookupError({two}, coarse, 1)[0], alone);
    EXPECT_EQ(worstLookupError({two}, coarse, 3)[0], alone);
}
