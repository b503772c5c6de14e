// The CPU water sampler against an independent double-precision bilinear of the plain chain
// (test::referenceBilinear), over many random points, maps, wraps and times. The viewer test
// (tests/viewer) compares the same sampler with the heights the GPU computes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "heightpack/core/mip.hpp"
#include "heightpack/core/pack.hpp"
#include "heightpack/core/water_sampler.hpp"

#include "support/test_support.hpp"

using namespace heightpack;
using heightpack::test::randomImage;
using heightpack::test::referenceBilinear;

namespace {

struct Chains {
    std::vector<Image> plain, packed;
};

Chains chainsOf(const Image& level0, Wrap wrap) {
    MipOptions mip;
    mip.wrap = wrap;
    Chains c;
    c.plain = generateMipChain(level0, mip);
    for (const Image& level : c.plain) c.packed.push_back(packNeighbour4(level, wrap));
    return c;
}

// Float rounding of a few operations on values of order one: far below any height that matters.
constexpr double kFloatTolerance = 2e-5;

}  // namespace

TEST(WaterSampler, PointQueriesAreTheBilinearOfTheMapScaledScrolledAndCentred) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coordinate(-200.0f, 200.0f), time(0.0f, 60.0f);
    for (Wrap wrap : {Wrap::Periodic, Wrap::Clamp}) {
        for (unsigned seed = 1; seed <= 8; ++seed) {
            const Image map = randomImage(32 << (seed % 2), 16 << (seed % 3), seed, -1.0f, 2.0f);
            const Chains c = chainsOf(map, wrap);
            WaterSampler sampler;
            SampledLayer layer;
            layer.frames = {c.packed};
            layer.wrap = wrap;
            layer.tileSize = 10.0f + seed;
            layer.scroll = {0.013f * seed, -0.007f};
            layer.amplitude = 0.5f + 0.25f * seed;
            layer.midStored = midStoredOf(layer.frames);
            sampler.layers = {layer};
            EXPECT_FLOAT_EQ(layer.midStored, c.plain.back().pixels[0]);
            for (int i = 0; i < 200; ++i) {
                const float x = coordinate(rng), y = coordinate(rng), t = time(rng);
                const double u = double(x) / layer.tileSize + double(layer.scroll[0]) * t;
                const double v = double(y) / layer.tileSize + double(layer.scroll[1]) * t;
                const bool periodic = wrap == Wrap::Periodic;
                const double cu = periodic ? u : std::clamp(u, 0.0, 1.0), cv = periodic ? v : std::clamp(v, 0.0, 1.0);
                const double expected = layer.amplitude * (referenceBilinear(c.plain[0], cu, cv, periodic) - layer.midStored);
                // Coordinates of a few hundred tiles lose float digits: the tolerance grows with |u|.
                const double slack = kFloatTolerance * (1.0 + std::abs(u) + std::abs(v)) * layer.amplitude * 8;
                ASSERT_NEAR(sampleWaterHeight(sampler, x, y, t), expected, slack)
                    << wrapName(wrap) << " seed " << seed << " at " << x << "," << y << " t " << t;
            }
        }
    }
}

TEST(WaterSampler, TrilinearPicksTheFootprintsLevelAndBlendsOnlyInsideTheBand) {
    const Image map = randomImage(64, 64, 3);
    const Chains c = chainsOf(map, Wrap::Periodic);
    WaterSampler sampler;
    SampledLayer layer;
    layer.frames = {c.packed};
    layer.tileSize = 32.0f;  // 2 texels per metre at level 0
    sampler.layers = {layer};
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> coordinate(0.0f, 32.0f);
    for (int level = 0; level + 1 < int(c.plain.size()); ++level) {
        for (float fraction : {0.1f, 0.29f, 0.31f, 0.5f, 0.69f, 0.71f, 0.9f}) {
            const float lod = level + fraction;
            const float footprint = std::exp2(lod) / 2.0f;  // metres per sample: 2^lod texels
            ASSERT_NEAR(layerLevelOfDetail(layer, footprint), lod, 1e-5);
            for (int i = 0; i < 20; ++i) {
                const float x = coordinate(rng), y = coordinate(rng);
                const double fine = referenceBilinear(c.plain[level], x / 32.0, y / 32.0, true);
                const double coarse = referenceBilinear(c.plain[level + 1], x / 32.0, y / 32.0, true);
                const double weight = std::clamp((fraction - 0.3) / 0.4, 0.0, 1.0);
                const double expected = fine + (coarse - fine) * weight - layer.midStored;
                ASSERT_NEAR(sampleWaterHeight(sampler, x, y, 0.0f, footprint), expected, 1e-4)
                    << "level " << level << " fraction " << fraction;
            }
        }
    }
    // A footprint beyond the chain holds the coarsest level; bilinear ignores the footprint.
    EXPECT_NEAR(sampleWaterHeight(sampler, 3.0f, 5.0f, 0.0f, 1e6f), c.plain.back().pixels[0] - layer.midStored, 1e-6);
    sampler.filter = LevelFilter::Bilinear;
    EXPECT_NEAR(sampleWaterHeight(sampler, 3.0f, 5.0f, 0.0f, 1e6f),
                referenceBilinear(c.plain[0], 3.0 / 32, 5.0 / 32, true) - layer.midStored, 1e-5);
}

TEST(WaterSampler, SequencesShowEachFrameOnItsTimeAndBlendBetween) {
    constexpr int kFrames = 5;
    constexpr double kPeriod = 10.0;
    WaterSampler sampler;
    SampledLayer layer;
    std::vector<Chains> frames;
    for (int f = 0; f < kFrames; ++f) {
        frames.push_back(chainsOf(randomImage(16, 16, 100 + f), Wrap::Periodic));
        layer.frames.push_back(frames.back().packed);
    }
    layer.loopPeriod = kPeriod;
    layer.tileSize = 8.0f;
    layer.midStored = midStoredOf(layer.frames);
    sampler.layers = {layer};
    auto reference = [&](int f, float x, float y) {
        return referenceBilinear(frames[f % kFrames].plain[0], x / 8.0, y / 8.0, true) - layer.midStored;
    };
    for (int f = 0; f <= kFrames; ++f) {
        const float t = static_cast<float>(f * kPeriod / kFrames);
        EXPECT_NEAR(sampleWaterHeight(sampler, 1.3f, 2.9f, t), reference(f, 1.3f, 2.9f), 1e-5) << "frame " << f;
        // A quarter of the way to the next frame: three parts this frame, one part the next.
        const float later = static_cast<float>((f + 0.25) * kPeriod / kFrames);
        EXPECT_NEAR(sampleWaterHeight(sampler, 1.3f, 2.9f, later),
                    0.75 * reference(f, 1.3f, 2.9f) + 0.25 * reference(f + 1, 1.3f, 2.9f), 1e-5)
            << "frame " << f;
    }
    // Negative time runs the loop backwards from the end.
    EXPECT_NEAR(sampleWaterHeight(sampler, 1.3f, 2.9f, float(-kPeriod / kFrames)), reference(kFrames - 1, 1.3f, 2.9f), 1e-5);
}

TEST(WaterSampler, LayersAdd) {
    const Chains a = chainsOf(randomImage(32, 32, 21), Wrap::Periodic), b = chainsOf(randomImage(8, 8, 22), Wrap::Periodic);
    WaterSampler both, first, second;
    SampledLayer la, lb;
    la.frames = {a.packed};
    la.tileSize = 64.0f;
    la.amplitude = 1.5f;
    la.midStored = midStoredOf(la.frames);
    lb.frames = {b.packed};
    lb.tileSize = 16.0f;
    lb.amplitude = 0.4f;
    lb.scroll = {-0.006f, 0.011f};
    lb.midStored = midStoredOf(lb.frames);
    both.layers = {la, lb};
    first.layers = {la};
    second.layers = {lb};
    for (float x = -50; x < 50; x += 7.3f)
        EXPECT_NEAR(sampleWaterHeight(both, x, 0.5f * x, 3.0f, 0.2f),
                    sampleWaterHeight(first, x, 0.5f * x, 3.0f, 0.2f) + sampleWaterHeight(second, x, 0.5f * x, 3.0f, 0.2f), 1e-6);
}
