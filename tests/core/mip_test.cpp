#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "heightpack/core/mip.hpp"

#include "support/test_support.hpp"

using namespace heightpack;
using heightpack::test::makeImage;
using heightpack::test::randomImage;
using heightpack::test::referenceBilinear;

namespace {

const Filter kFilters[] = {Filter::Box, Filter::Triangle, Filter::Lanczos3, Filter::Kaiser};
const Wrap kWraps[] = {Wrap::Periodic, Wrap::Clamp};

MipOptions options(Filter filter, Wrap wrap) {
    MipOptions o;
    o.filter = filter;
    o.wrap = wrap;
    return o;
}

// The image shifted by (dx, dy) texels with wraparound: out(x, y) = in(x - dx, y - dy).
Image roll(const Image& in, int dx, int dy) {
    return makeImage(in.width, in.height, [&](int x, int y) {
        return in.at(((x - dx) % in.width + in.width) % in.width, ((y - dy) % in.height + in.height) % in.height);
    });
}

}  // namespace

TEST(Mip, ChainOfNonSquareMapGoesDownTo1x1) {
    const auto chain = generateMipChain(randomImage(64, 16, 1), Filter::Kaiser);
    const int expected[][2] = {{64, 16}, {32, 8}, {16, 4}, {8, 2}, {4, 1}, {2, 1}, {1, 1}};
    ASSERT_EQ(chain.size(), 7u);
    for (size_t i = 0; i < chain.size(); ++i) {
        EXPECT_EQ(chain[i].width, expected[i][0]) << "level " << i;
        EXPECT_EQ(chain[i].height, expected[i][1]) << "level " << i;
    }
    EXPECT_EQ(mipLevelCount(1, 1), 1);
    EXPECT_EQ(mipLevelCount(4096, 4096), 13);
}

TEST(Mip, BoxHalvesByAveragingTwoByTwo) {
    Image in(4, 2);
    in.pixels = {1, 3, 5, 7,
                 2, 4, 6, 10};
    const auto chain = generateMipChain(in, Filter::Box);
    ASSERT_EQ(chain.size(), 3u);
    EXPECT_FLOAT_EQ(chain[1].at(0, 0), (1 + 3 + 2 + 4) / 4.0f);
    EXPECT_FLOAT_EQ(chain[1].at(1, 0), (5 + 7 + 6 + 10) / 4.0f);
    EXPECT_FLOAT_EQ(chain[2].at(0, 0), (1 + 3 + 5 + 7 + 2 + 4 + 6 + 10) / 8.0f);
}

TEST(Mip, TriangleHalvingUsesOneThreeThreeOneWeights) {
    // Halving with a tent centred between texels 2i and 2i+1 weighs texels 2i-1..2i+2 as 1/8, 3/8, 3/8, 1/8.
    Image in(8, 1);
    in.pixels = {0, 1, 2, 3, 4, 5, 6, 7};
    const Image out = resample(in, 4, 1, options(Filter::Triangle, Wrap::Periodic));
    for (int i = 0; i < 4; ++i) {
        auto h = [&](int t) { return in.pixels[((t % 8) + 8) % 8]; };
        const double expected = (h(2 * i - 1) + 3 * h(2 * i) + 3 * h(2 * i + 1) + h(2 * i + 2)) / 8.0;
        EXPECT_NEAR(out.at(i, 0), expected, 1e-6) << "texel " << i;
    }
}

TEST(Mip, EveryFilterKeepsAConstantConstant) {
    const Image flat = makeImage(16, 8, [](int, int) { return 0.7f; });
    for (Filter f : kFilters)
        for (Wrap w : kWraps)
            for (const Image& level : generateMipChain(flat, options(f, w)))
                for (float v : level.pixels) ASSERT_NEAR(v, 0.7f, 1e-6) << filterName(f) << " " << wrapName(w);
}

TEST(Mip, PeriodicChainIsShiftInvariant) {
    // Level L of a map rolled by 2^L texels is level L of the map rolled by one texel: no edge effects.
    const Image map = randomImage(64, 32, 7);
    for (Filter f : kFilters) {
        const auto chain = generateMipChain(map, options(f, Wrap::Periodic));
        for (int level = 1; level < 5; ++level) {
            const int step = 1 << level;
            const auto rolledChain = generateMipChain(roll(map, step, 2 * step), options(f, Wrap::Periodic));
            const Image back = roll(rolledChain[level], -1, -2);
            for (size_t i = 0; i < back.pixels.size(); ++i)
                ASSERT_NEAR(back.pixels[i], chain[level].pixels[i], 1e-6)
                    << filterName(f) << " level " << level << " texel " << i;
        }
    }
}

TEST(Mip, LevelsStayAlignedOnASmoothPeriodicField) {
    // One sine period across the tile, sampled at texel centres. Where the sine is resolved (the coarser
    // level has at least 32 texels a period), bilinear samples of level L and L+1 at the same uv agree.
    const int w = 256, h = 128;
    const Image field = makeImage(w, h, [&](int x, int y) {
        return static_cast<float>(0.5 + 0.25 * std::sin(2 * std::numbers::pi * (x + 0.5) / w) + 0.25 * std::cos(2 * std::numbers::pi * (y + 0.5) / h));
    });
    const double amplitude = 1.0;  // peak to peak
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uv(-0.5, 1.5);
    for (Filter f : kFilters) {
        for (Wrap wrap : {Wrap::Periodic}) {
            const auto chain = generateMipChain(field, options(f, wrap));
            for (size_t level = 0; level + 1 < chain.size() && chain[level + 1].height >= 32; ++level) {
                double worst = 0.0;
                for (int k = 0; k < 2000; ++k) {
                    const double u = uv(rng), v = uv(rng);
                    const double a = referenceBilinear(chain[level], u, v, true);
                    const double b = referenceBilinear(chain[level + 1], u, v, true);
                    worst = std::max(worst, std::abs(a - b));
                }
                EXPECT_LT(worst, 0.01 * amplitude) << filterName(f) << " levels " << level << "/" << level + 1;
            }
        }
    }
}

TEST(Mip, ClampDoesNotBleedTheOppositeEdgeIn) {
    // Left half 0, right half 1. Periodic filters see the 1s across the left edge; clamp must not.
    const Image step = makeImage(32, 4, [](int x, int) { return x < 16 ? 0.0f : 1.0f; });
    for (Filter f : {Filter::Triangle, Filter::Lanczos3, Filter::Kaiser}) {
        const Image periodic = resample(step, 16, 2, options(f, Wrap::Periodic));
        const Image clamp = resample(step, 16, 2, options(f, Wrap::Clamp));
        EXPECT_GT(std::abs(periodic.at(0, 0)), 1e-3) << filterName(f);
        EXPECT_NEAR(clamp.at(0, 0), 0.0f, 1e-6) << filterName(f);
        EXPECT_NEAR(clamp.at(15, 1), 1.0f, 1e-6) << filterName(f);
    }
}

TEST(Mip, ResampleToPowerOfTwoKeepsTexelCentresAligned) {
    // A linear ramp resampled from 1000x600 to 1024x1024: the tent reproduces a ramp exactly, so texel i
    // of the result must hold the ramp's value at source position (i + 0.5) * 1000 / 1024 - 0.5.
    const Image ramp = makeImage(1000, 600, [](int x, int y) { return 0.001f * x + 0.0005f * y; });
    const Image out = resample(ramp, 1024, 1024, options(Filter::Triangle, Wrap::Clamp));
    ASSERT_EQ(out.width, 1024);
    ASSERT_EQ(out.height, 1024);
    for (int y = 4; y < 1020; y += 37) {
        for (int x = 4; x < 1020; x += 29) {
            const double sx = (x + 0.5) * 1000.0 / 1024 - 0.5, sy = (y + 0.5) * 600.0 / 1024 - 0.5;
            ASSERT_NEAR(out.at(x, y), 0.001 * sx + 0.0005 * sy, 2e-6) << x << "," << y;
        }
    }
    EXPECT_TRUE(isPowerOfTwo(1024));
    EXPECT_FALSE(isPowerOfTwo(1000));
    EXPECT_EQ(nextPowerOfTwo(600), 1024);
    EXPECT_EQ(nextPowerOfTwo(512), 512);
}

TEST(Mip, FilterShapes) {
    EXPECT_DOUBLE_EQ(filterWeight(Filter::Lanczos3, 0.0), 1.0);
    EXPECT_NEAR(filterWeight(Filter::Lanczos3, 1.0), 0.0, 1e-12);  // zero at every other integer
    EXPECT_NEAR(filterWeight(Filter::Kaiser, 2.0), 0.0, 1e-12);
    EXPECT_DOUBLE_EQ(filterWeight(Filter::Kaiser, 3.0), 0.0);
    EXPECT_DOUBLE_EQ(filterWeight(Filter::Triangle, 0.25), 0.75);
    for (Filter f : kFilters) EXPECT_EQ(parseName<Filter>(filterName(f)), f);
    EXPECT_FALSE(parseName<Filter>("gauss"));
}

TEST(Mip, ResamplingBothAxesEqualsOneAxisAfterTheOther) {
    // resample filters along y and then along x a destination row at a time, never holding the image
    // between the passes: the same values, to the bit, as a resample along y alone followed by one along
    // x alone, when shrinking (a mip level), growing (--resize pow2) and for several channels, on any
    // number of threads.
    struct Case { int w, h, c, toW, toH; };
    for (const Case& c : {Case{64, 32, 1, 32, 16}, Case{97, 61, 1, 128, 64}, Case{40, 40, 3, 16, 8}, Case{8, 256, 2, 4, 128}}) {
        Image src(c.w, c.h, c.c);
        const Image noise = randomImage(c.w * c.c, c.h, unsigned(c.w + c.h));
        src.pixels = noise.pixels;
        for (const Filter filter : kFilters) {
            for (const Wrap wrap : kWraps) {
                MipOptions o = options(filter, wrap);
                o.threads = 1;
                const Image both = resample(src, c.toW, c.toH, o);
                const Image apart = resample(resample(src, c.w, c.toH, o), c.toW, c.toH, o);
                ASSERT_EQ(both.width, c.toW);
                ASSERT_EQ(both.height, c.toH);
                EXPECT_EQ(both.pixels, apart.pixels) << c.w << "x" << c.h << " " << nameOf(filter) << " " << nameOf(wrap);
                o.threads = 3;
                EXPECT_EQ(resample(src, c.toW, c.toH, o).pixels, both.pixels) << "threads";
            }
        }
    }
}

TEST(Mip, ChainOfAMovedLevelEqualsChainOfACopy) {
    const Image level0 = randomImage(32, 16, 5);
    const MipOptions o = options(Filter::Kaiser, Wrap::Periodic);
    const std::vector<Image> copied = generateMipChain(level0, o);
    const std::vector<Image> moved = generateMipChain(Image(level0), o);
    ASSERT_EQ(copied.size(), moved.size());
    EXPECT_EQ(moved[0].pixels, level0.pixels);
    for (size_t l = 0; l < copied.size(); ++l) EXPECT_EQ(copied[l].pixels, moved[l].pixels) << "level " << l;
}
