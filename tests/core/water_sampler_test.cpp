// The CPU water sampler against an independent double-precision bilinear of the plain chain
// (test::referenceBilinear), over many random points, maps, wraps and times. The viewer test
// (tests/viewer) compares the same sampler with the heights the GPU computes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
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

namespace {

// A trochoidal (Gerstner) wave along one axis: heights a cos(k p) and synth's D = -sin(k p) toward the
// crests, sampled at texel centres of an n-texel tile (n large enough that the bilinear of the cosine is
// within 2e-7 m of it). The point that starts at p ends at X = p - c a sin(k p), at height a cos(k p): the
// displaced surface in closed form, parametrised by p, whose slope stays below 1 (no fold) while
// c a k < 1.
struct Trochoid {
    float tileSize = 64.0f, amplitude = 2.0f, choppiness = 3.0f;
    int axis = 0;  // 0: crests along y, the wave runs along x; 1: the other way round
    double k() const { return 2 * M_PI / tileSize; }
    double lambda() const { return double(choppiness) * amplitude; }
    double displaced(double p) const { return p - lambda() * std::sin(k() * p); }
    double height(double p) const { return amplitude * std::cos(k() * p); }

    SampledLayer layer(int n = 8192) const {
        const int w = axis == 0 ? n : 2, h = axis == 0 ? 2 : n;
        Image heights(w, h, 1), along(w, h, 1), across(w, h, 1, 0.0f);
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) {
                const double phase = 2 * M_PI * ((axis == 0 ? i : j) + 0.5) / n;
                heights.pixels[size_t(j) * w + i] = float(std::cos(phase));
                along.pixels[size_t(j) * w + i] = float(-std::sin(phase));
            }
        SampledLayer l;
        l.frames = {{packNeighbour4(heights, Wrap::Periodic)}};
        l.shiftX = {{packNeighbour4(axis == 0 ? along : across, Wrap::Periodic)}};
        l.shiftY = {{packNeighbour4(axis == 0 ? across : along, Wrap::Periodic)}};
        l.tileSize = tileSize;
        l.amplitude = amplitude;
        l.choppiness = choppiness;
        l.scroll = {0.0f, 0.0f};
        l.midStored = 0.0f;  // the cosine's mean
        return l;
    }
};

}  // namespace

TEST(WaterSampler, ChoppyShiftAndTheHeightOverAPointFollowATrochoid) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> start(-100.0, 100.0), across(-50.0, 50.0);
    for (int axis : {0, 1}) {
        Trochoid wave;
        wave.axis = axis;
        ASSERT_LT(wave.lambda() * wave.k(), 0.6);  // no fold: the iteration contracts by 0.59 a step at worst
        WaterSampler sampler;
        sampler.layers = {wave.layer()};
        ASSERT_TRUE(isChoppy(sampler));
        int worstSteps = 0;
        for (int i = 0; i < 300; ++i) {
            const double p = start(rng), q = across(rng);
            // The point that starts at p moves by -c a sin(k p) along the wave, not at all across it.
            const float sx = axis == 0 ? float(p) : float(q), sy = axis == 0 ? float(q) : float(p);
            const std::array<float, 2> shift = sampleWaterShift(sampler, sx, sy, 0.0f);
            ASSERT_NEAR(shift[axis], -wave.lambda() * std::sin(wave.k() * (axis == 0 ? sx : sy)), 2e-5) << p;
            ASSERT_EQ(shift[1 - axis], 0.0f);
            // Over X = p - c a sin(k p) the surface stands at a cos(k p).
            const double X = wave.displaced(p);
            const float x = axis == 0 ? float(X) : float(q), y = axis == 0 ? float(q) : float(X);
            const SurfaceHeight s = sampleSurfaceHeight(sampler, x, y, 0.0f);
            ASSERT_TRUE(s.converged) << "X " << X << " after " << s.iterations << " steps, residual " << s.residual;
            EXPECT_NEAR(s.height, wave.height(p), 1e-5) << "axis " << axis << " X " << X;
            EXPECT_NEAR(s.origin[axis], p, 1e-4);
            EXPECT_EQ(s.origin[1 - axis], axis == 0 ? y : x);
            worstSteps = std::max(worstSteps, s.iterations);
        }
        EXPECT_LE(worstSteps, SurfaceSearch{}.maxIterations);
        std::printf("axis %d: at most %d fixed-point steps\n", axis, worstSteps);
    }
}

TEST(WaterSampler, AFoldGivesATruePointOrSaysItDidNotConverge) {
    // c a k = 3: around each crest the surface folds over itself (X(p) runs backwards), so a point there
    // lies under the surface three times; the fixed points at all three repel (slopes 3 and -1.95), and the
    // steps wander.
    Trochoid wave;
    wave.choppiness = 15.28f;
    ASSERT_GT(wave.lambda() * wave.k(), 2.99);
    WaterSampler sampler;
    sampler.layers = {wave.layer()};
    int converged = 0, not_converged = 0;
    for (double X = -3.0; X <= 3.0; X += 0.05) {
        const SurfaceHeight s = sampleSurfaceHeight(sampler, float(X), 1.0f, 0.0f);
        ASSERT_TRUE(std::isfinite(s.height) && std::isfinite(s.residual));
        // Whatever it returns is the height at the origin it names, whose residual it reports truly.
        EXPECT_FLOAT_EQ(s.height, sampleWaterHeight(sampler, s.origin[0], s.origin[1], 0.0f));
        const double landed = s.origin[0] + sampleWaterShift(sampler, s.origin[0], s.origin[1], 0.0f)[0];
        EXPECT_NEAR(s.residual, std::abs(landed - float(X)), 1e-5);
        if (s.converged) {
            // One of the (up to three) surface points over X: the trochoid's own height there.
            EXPECT_LE(s.residual, 1e-5);
            EXPECT_NEAR(s.height, wave.height(s.origin[0]), 1e-5);
            ++converged;
        } else {
            EXPECT_EQ(s.iterations, SurfaceSearch{}.maxIterations);
            EXPECT_GT(s.residual, 1e-6);
            ++not_converged;
        }
    }
    EXPECT_GT(not_converged, 0) << "the fold's middle should defeat the iteration somewhere";
    std::printf("fold: %d converged, %d not\n", converged, not_converged);
    // A search cut short says so, with its best iterate.
    Trochoid steep;  // c a k = 0.59: slow enough that three steps do not reach 1e-6 m
    WaterSampler slow;
    slow.layers = {steep.layer()};
    SurfaceSearch three;
    three.maxIterations = 3;
    const SurfaceHeight s = sampleSurfaceHeight(slow, float(steep.displaced(3.0)), 0.0f, 0.0f, 0.0f, three);
    EXPECT_FALSE(s.converged);
    EXPECT_EQ(s.iterations, 3);
    EXPECT_GT(s.residual, 1e-6);
}

TEST(WaterSampler, ChoppinessZeroTakesTheUnshiftedPathBitForBit) {
    Trochoid wave;
    WaterSampler sampler;
    sampler.layers = {wave.layer(256)};
    sampler.layers[0].choppiness = 0.0f;  // Dx, Dy present, choppiness off
    WaterSampler plain = sampler;
    plain.layers[0].shiftX.clear();
    plain.layers[0].shiftY.clear();
    for (float x = -40.0f; x < 40.0f; x += 3.7f) {
        const SurfaceHeight s = sampleSurfaceHeight(sampler, x, 0.3f * x, 1.5f, 0.1f);
        EXPECT_EQ(s.height, sampleWaterHeight(plain, x, 0.3f * x, 1.5f, 0.1f));
        EXPECT_EQ(s.iterations, 0);
        EXPECT_TRUE(s.converged);
        EXPECT_EQ(sampleWaterShift(sampler, x, 0.0f, 1.5f)[0], 0.0f);
    }
}
