#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "heightpack/bake/check_job.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/pack.hpp"
#include "heightpack/core/tile/tileable.hpp"

#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// A smooth random field: a sum of waves with random directions and phases. With whole wave numbers it
// is periodic over the tile; with fractional ones it is not.
Image waveField(int w, int h, unsigned seed, bool periodic) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> k(1.0, 7.0), phase(0, 2 * std::numbers::pi), sign(-1, 1);
    struct Wave { double kx, ky, a, p; };
    std::vector<Wave> waves;
    for (int i = 0; i < 12; ++i) {
        double kx = k(rng) * (sign(rng) < 0 ? -1 : 1), ky = k(rng) * (sign(rng) < 0 ? -1 : 1);
        if (periodic) {
            kx = std::round(kx);
            ky = std::round(ky);
        }
        waves.push_back({kx, ky, 0.05 / (1 + std::hypot(kx, ky) / 4), phase(rng)});
    }
    return makeImage(w, h, [&](int x, int y) {
        double v = 0.5;
        for (const Wave& wave : waves) v += wave.a * std::cos(2 * std::numbers::pi * (wave.kx * x / w + wave.ky * y / h) + wave.p);
        return static_cast<float>(v);
    });
}

// Periodic, with fine stripes four texels apart that the mip filters must remove: where a filter clamps
// at the tile edge instead of wrapping, the stripes survive at the edge texels and a seam appears.
Image stripedField(int size) {
    return makeImage(size, size, [&](int x, int y) {
        return static_cast<float>(0.5 + 0.2 * std::sin(2 * std::numbers::pi * (2.0 * (x + 0.5) / size + double(y) / size)) +
                                  0.2 * std::sin(2 * std::numbers::pi * (x + 0.5) / 4 + 0.3));
    });
}

bool chainTiles(const Image& map, Wrap wrap = Wrap::Periodic) {
    MipOptions o;
    o.wrap = wrap;
    for (const Image& level : generateMipChain(map, o))
        if (!levelTiles(measureSeams(level))) return false;
    return true;
}

// The 5-point Laplacian at (x, y); neighbours outside the map come from `outside`.
template <class Outside>
double laplacian(const Image& m, int x, int y, Outside outside) {
    auto at = [&](int i, int j) {
        if (i >= 0 && i < m.width && j >= 0 && j < m.height) return double(m.at(i, j));
        return outside(i, j);
    };
    return at(x + 1, y) + at(x - 1, y) + at(x, y + 1) + at(x, y - 1) - 4 * at(x, y);
}

double stddev(const std::vector<double>& v) {
    double mean = 0, sq = 0;
    for (double x : v) mean += x;
    mean /= v.size();
    for (double x : v) sq += (x - mean) * (x - mean);
    return std::sqrt(sq / v.size());
}

}  // namespace

TEST(Tileable, PeriodicFieldsTileAtEveryLevelAndOthersDoNot) {
    for (unsigned seed = 1; seed <= 5; ++seed) {
        EXPECT_TRUE(chainTiles(waveField(256, 128, seed, true))) << "periodic seed " << seed;
        EXPECT_FALSE(levelTiles(measureSeams(waveField(256, 128, seed, false)))) << "non-periodic seed " << seed;
    }
}

TEST(Tileable, MatchingHeightsWithBrokenSlopesFail) {
    // sin(pi x / W): zero at both ends (heights meet), slope +pi/W at the left, -pi/W at the right.
    const Image kink = makeImage(128, 64, [](int x, int y) {
        return static_cast<float>(0.5 * std::sin(std::numbers::pi * (x + 0.5) / 128) + 0.1 * std::cos(2 * std::numbers::pi * y / 64));
    });
    const LevelSeams s = measureSeams(kink);
    EXPECT_LT(s.leftRight.value, 1.0);  // the edge heights are closer than neighbours' are
    EXPECT_GT(s.leftRight.slope, kDefaultSeamThreshold * 5);
    EXPECT_FALSE(seamPasses(s.leftRight));
    EXPECT_TRUE(seamPasses(s.topBottom));  // the y direction is periodic
}

TEST(Tileable, ClampedFilteringBreaksATileableMapBelowLevelZero) {
    const Image map = stripedField(128);
    EXPECT_TRUE(chainTiles(map, Wrap::Periodic));
    EXPECT_TRUE(levelTiles(measureSeams(map)));
    EXPECT_FALSE(chainTiles(map, Wrap::Clamp));
}

TEST(Tileable, PeriodicComponentSatisfiesMoisansEquation) {
    // Moisan: the periodic Laplacian of p equals the map's interior Laplacian, where a missing neighbour
    // repeats the edge texel.
    const Image u = waveField(64, 32, 9, false);
    const Image heights = periodicComponent(u, PeriodicContinuity::Heights);
    auto wrapped = [](const Image& m) {
        return [&m](int i, int j) { return double(m.at((i + m.width) % m.width, (j + m.height) % m.height)); };
    };
    auto repeated = [&](int i, int j) {
        return double(u.at(std::clamp(i, 0, u.width - 1), std::clamp(j, 0, u.height - 1)));
    };
    double meanU = 0, meanP = 0;
    for (int y = 0; y < u.height; ++y) {
        for (int x = 0; x < u.width; ++x) {
            ASSERT_NEAR(laplacian(heights, x, y, wrapped(heights)), laplacian(u, x, y, repeated), 1e-5) << x << "," << y;
            meanU += u.at(x, y);
            meanP += heights.at(x, y);
        }
    }
    EXPECT_NEAR(meanP, meanU, 1e-3);  // the mean is kept (sums over 2048 texels)
}

TEST(Tileable, PeriodicComponentMeetsEdgesWithoutADomeAndKeepsTheMiddle) {
    for (unsigned seed = 1; seed <= 4; ++seed) {
        const Image u = waveField(256, 256, seed, false);
        ASSERT_FALSE(levelTiles(measureSeams(u)));
        const Image p = periodicComponent(u);
        auto change = [&](int x, int y) { return double(u.at(x, y)) - p.at(x, y); };
        // Across each edge, p steps as the slopes beside the edge predict (no jump, no flat step); the
        // worst miss is a small part of the worst jump the map had there.
        double maxJump = 0, maxMiss = 0;
        for (int i = 0; i < 256; ++i) {
            maxJump = std::max({maxJump, std::abs(double(u.at(255, i)) - u.at(0, i)),
                                std::abs(double(u.at(i, 255)) - u.at(i, 0))});
            const double stepX = double(p.at(0, i)) - p.at(255, i);
            const double slopeX = 0.5 * (double(p.at(1, i)) - p.at(0, i) + p.at(255, i) - p.at(254, i));
            const double stepY = double(p.at(i, 0)) - p.at(i, 255);
            const double slopeY = 0.5 * (double(p.at(i, 1)) - p.at(i, 0) + p.at(i, 255) - p.at(i, 254));
            maxMiss = std::max({maxMiss, std::abs(stepX - slopeX), std::abs(stepY - slopeY)});
        }
        EXPECT_LT(maxMiss, 0.05 * maxJump) << "seed " << seed;
        // No dome: the change is bounded by the jumps it replaces plus the local bend (3/8 of the slope
        // difference times an eighth of the tile), not by the tile's size.
        double maxChange = 0;
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x) maxChange = std::max(maxChange, std::abs(change(x, y)));
        EXPECT_LT(maxChange, 1.5 * maxJump) << "seed " << seed;
        // Beyond the bands where the slopes are bent together (an eighth of the tile), the change is
        // harmonic: the middle keeps the map's own curvature.
        double maxBend = 0;
        for (int y = 40; y < 216; ++y)
            for (int x = 40; x < 216; ++x)
                maxBend = std::max(maxBend, std::abs(change(x + 1, y) + change(x - 1, y) + change(x, y + 1) +
                                                     change(x, y - 1) - 4 * change(x, y)));
        EXPECT_LT(maxBend, 1e-5) << "seed " << seed;
    }
}

TEST(Tileable, CrossfadeKeepsContrastWhereALinearBlendWashesItOut) {
    // White noise: a linear 50/50 blend of two independent copies has 1/sqrt(2) of their deviation.
    const Image noise = randomImage(256, 256, 77);
    const double band = 0.25;
    const Image kept = crossfadeTile(noise, band);
    const Image washed = crossfadeTile(noise, band, CrossfadeBlend::Linear);
    std::vector<double> middleKept, middleWashed, rest;
    for (int y = 0; y < 256; ++y) {
        for (int x = 0; x < 256; ++x) {
            const double a = crossfadeWeight(x, y, 256, 256, band);
            if (std::abs(a - 0.5) < 0.1) {
                middleKept.push_back(kept.at(x, y));
                middleWashed.push_back(washed.at(x, y));
            } else if (a == 1.0) {
                rest.push_back(kept.at(x, y));
            }
        }
    }
    ASSERT_GT(middleKept.size(), 500u);
    const double reference = stddev(rest);
    EXPECT_NEAR(stddev(middleKept), reference, 0.1 * reference);
    EXPECT_NEAR(stddev(middleWashed) / reference, 1 / std::sqrt(2.0), 0.05);  // about 30% lost
    // Both tile: the tile edges hold the half-shifted copy, which is continuous there.
    const Image smooth = crossfadeTile(waveField(256, 256, 5, false), 0.1);
    EXPECT_TRUE(levelTiles(measureSeams(smooth)));
}

TEST(Tileable, MirrorTilingIsTheMapAndItsMirrorImages) {
    const Image u = waveField(32, 16, 2, false);
    const Image m = mirrorTile(u);
    ASSERT_EQ(m.width, 64);
    ASSERT_EQ(m.height, 32);
    EXPECT_EQ(m.at(3, 5), u.at(3, 5));
    EXPECT_EQ(m.at(63 - 3, 5), u.at(3, 5));
    EXPECT_EQ(m.at(3, 31 - 5), u.at(3, 5));
    EXPECT_EQ(m.at(63 - 3, 31 - 5), u.at(3, 5));
    // The edges repeat each other: no step at all across them, less than at any other cut.
    const LevelSeams seams = measureSeams(mirrorTile(waveField(64, 32, 2, false)));
    EXPECT_LT(seams.leftRight.value, 0.0);
    EXPECT_LT(seams.topBottom.value, 0.0);
}

TEST(Tileable, PackingCheckFindsAWrongTexel) {
    const auto chain = generateMipChain(waveField(32, 32, 4, true), Filter::Kaiser);
    auto packed = packMipChain(chain, Wrap::Periodic);
    EXPECT_TRUE(checkPacking(packed, Wrap::Periodic).consistent);
    EXPECT_FALSE(checkPacking(packed, Wrap::Clamp).consistent);  // the edge texels differ under clamp
    packed[2].at(3, 4, 2) += 0.01f;
    const PackingCheck bad = checkPacking(packed, Wrap::Periodic);
    EXPECT_FALSE(bad.consistent);
    EXPECT_EQ(bad.firstBadLevel, 2);
    EXPECT_NEAR(bad.maxError, 0.01, 1e-6);
}

TEST(Tileable, PreviewMarksExactlyTheFailingEdges) {
    // A ramp along x (seam at the left/right edges), periodic along y.
    const Image ramp = makeImage(128, 64, [](int x, int y) {
        return static_cast<float>(x / 128.0 * 0.5 + 0.2 * std::sin(2 * std::numbers::pi * y / 64));
    });
    const LevelSeams seams = measureSeams(ramp);
    ASSERT_FALSE(seamPasses(seams.leftRight));
    ASSERT_TRUE(seamPasses(seams.topBottom));
    const Image preview = seamPreview(ramp, seams);
    EXPECT_EQ(preview.width, 512);  // 2 x 128 = 256, scaled by 2 into [512, 1024]
    EXPECT_EQ(preview.height, 256);
    EXPECT_EQ(preview.channels, 3);
    auto isGrey = [&](int x, int y) {
        return preview.at(x, y, 0) == preview.at(x, y, 1) && preview.at(x, y, 1) == preview.at(x, y, 2);
    };
    auto isRedTinted = [&](int x, int y) { return preview.at(x, y, 0) > preview.at(x, y, 1) + 0.2f; };
    for (int y = 0; y < 256; y += 17) {
        EXPECT_TRUE(isRedTinted(256, y)) << "vertical seam line at y " << y;
        EXPECT_TRUE(isGrey(150, y));
    }
    for (int x = 0; x < 512; x += 23) {
        if (std::abs(x - 256) > 4) {
            EXPECT_TRUE(isGrey(x, 128)) << "no horizontal line at x " << x;
        }
    }
}

TEST(Tileable, CheckFileUsesATexturesOwnLevels) {
    ScratchDir dir;
    const Image map = stripedField(128);
    writeImage(dir.file("map.exr"), map, OIIO::TypeDesc::FLOAT);
    CheckOptions options;
    auto report = checkFile(dir.file("map.exr"), options);
    ASSERT_TRUE(report.ok()) << report.error().what;
    EXPECT_EQ(report->kind, "image");
    EXPECT_EQ(report->levels.size(), 8u);
    EXPECT_TRUE(report->tiles);
    options.mip.wrap = Wrap::Clamp;
    auto clamped = checkFile(dir.file("map.exr"), options);
    ASSERT_TRUE(clamped.ok());
    EXPECT_FALSE(clamped->tiles);
    EXPECT_TRUE(levelTiles(clamped->levels[0]));
}
