// The frame, blob and echo statistics (core/tile_look.hpp), judged on maps whose look is known by
// construction: exactly periodic fields pass (the calibration's promise, over a family of them), and each
// defect put into such a field by hand is caught by its statistic.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "heightpack/core/tile/look.hpp"
#include "heightpack/core/tile/tileable.hpp"

#include "support/seam_families.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

double stddevOf(const Image& m) {
    double mean = 0, var = 0;
    for (float v : m.pixels) mean += v;
    mean /= double(m.pixels.size());
    for (float v : m.pixels) var += (v - mean) * (v - mean);
    return std::sqrt(var / double(m.pixels.size()));
}

// Distance of texel x from the nearest tile edge (0 on the edge texels).
int edgeDistance(int x, int n) { return std::min(x, n - 1 - x); }

TEST(TileLook, ExactlyPeriodicFieldsPassEveryStatistic) {
    // The family the thresholds were calibrated on, at its every fourth member: spectra k^-1.5 to k^-4,
    // isotropic and directional, 64 to 1024 texels, rounded as stored.
    const int count = scaledCount(48, 12);
    int measured = 0;
    for (int i = 0; i < count; ++i) {
        const MapSpec spec = drawMap(Family::Periodic, 4 * i);
        const TileLook look = measureTileLook(makeMap(spec));
        if (!look.measured) continue;
        ++measured;
        EXPECT_TRUE(look.passes()) << describe(spec) << ": frame " << look.frame << " blobs " << look.blobs << " echo "
                                   << look.echo;
    }
    EXPECT_GT(measured, count / 2);
}

TEST(TileLook, AFrameOfLostContrastIsCaught) {
    // Periodic fields whose finest detail keeps 30% of its amplitude within 1/16 of the tile of every edge
    // (a band that has lost contrast, as a linear crossfade's does). Halved detail scores 6.4 to 7.9.
    int caught = 0, total = 0;
    for (unsigned seed = 1; seed <= 12; ++seed) {
        const Image field = periodicField(256, 256, seed, 2.0, 1.0, 0.0);
        Image framed = field;
        // The field less its own 2-texel-scale detail, near the edges only (a local box mean is the low-pass).
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x) {
                if (std::min(edgeDistance(x, 256), edgeDistance(y, 256)) >= 16) continue;
                double mean = 0;
                for (int dy = -2; dy <= 2; ++dy)
                    for (int dx = -2; dx <= 2; ++dx) mean += field.wrapped(x + dx, y + dy, Wrap::Periodic);
                mean /= 25;
                framed.at(x, y) = static_cast<float>(mean + 0.3 * (field.at(x, y) - mean));
            }
        const TileLook plain = measureTileLook(field), look = measureTileLook(framed);
        EXPECT_TRUE(plain.passes()) << seed;
        caught += look.frame > kDefaultFrameThreshold;
        ++total;
    }
    EXPECT_EQ(caught, total);
}

TEST(TileLook, ABlobAtTheCornerIsCaught) {
    // A bump of six standard deviations, 1/12 of the tile wide (sigma 1/24), centred on the tile corner:
    // the kind Moisan's corner pull and the old slope bend left. (The statistic's power is limited on red
    // spectra: a bump of four deviations scores 6 to 10, about half of them over the threshold.)
    int caught = 0, total = 0;
    for (unsigned seed = 1; seed <= 12; ++seed) {
        Image map = periodicField(256, 256, seed, 2.5, 1.0, 0.0);
        const double amplitude = 6 * stddevOf(map), radius = 256 / 24.0;
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x) {
                const double dx = edgeDistance(x, 256) + 0.5, dy = edgeDistance(y, 256) + 0.5;
                map.at(x, y) += static_cast<float>(amplitude * std::exp(-(dx * dx + dy * dy) / (2 * radius * radius)));
            }
        caught += measureTileLook(map).blobs > kDefaultBlobThreshold;
        ++total;
    }
    EXPECT_EQ(caught, total);
}

TEST(TileLook, AFeatureShownTwiceIsAnEchoAndTheSourcesOwnIsNot) {
    for (unsigned seed = 1; seed <= 6; ++seed) {
        const Image field = periodicField(256, 256, seed, 2.0, 1.0, 0.0);
        // The middle half of the tile copied onto the corners' quarter: what every offset-and-blend shows.
        Image echoed = field;
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x)
                if (edgeDistance(x, 256) < 48 && edgeDistance(y, 256) < 48)
                    echoed.at(x, y) = field.at((x + 128) % 256, (y + 128) % 256);
        const TileLook plain = measureTileLook(field), look = measureTileLook(echoed);
        EXPECT_LT(plain.echo, kDefaultEchoThreshold) << seed;
        EXPECT_GT(look.echo, kDefaultEchoThreshold) << seed;
        // Judged against itself as the source, the same map has no echo of its own making.
        EXPECT_LT(measureTileLook(echoed, {&echoed, 0, std::nullopt}).echo, 0.02) << seed;
    }
}

TEST(TileLook, TheOffsetAndBlendCrossfadeLeavesTheEchoItIsDocumentedToLeave) {
    const MapSpec spec = drawMap(Family::Crop, 3);
    const Image crop = makeMap(spec);
    const TileLook look = measureTileLook(crossfadeTile(crop, 0.1), {&crop, 0, std::nullopt});
    EXPECT_GT(look.echo, kDefaultEchoThreshold) << describe(spec);
}

TEST(TileLook, SmallMapsAreNotMeasured) {
    EXPECT_FALSE(measureTileLook(periodicField(32, 256, 1, 2.0, 1.0, 0.0)).measured);
    EXPECT_TRUE(measureTileLook(periodicField(64, 64, 1, 2.0, 1.0, 0.0)).passes());
}

}  // namespace

TEST(TileLook, ScoresAreTheSameOnAnyThreadCount) {
    // The statistics sum over rows and blocks of rows in fixed orders: a crop (that does not tile, so every
    // score is away from its floor) scores the same to the bit on one, two and five threads.
    for (unsigned seed = 1; seed <= 3; ++seed) {
        const Image big = periodicField(384, 320, seed, 2.5, 1.0, 0.0);
        Image crop(200, 136, 1);
        for (int y = 0; y < crop.height; ++y)
            for (int x = 0; x < crop.width; ++x) crop.at(x, y) = big.at(x + 31, y + 17);
        LookOptions one;
        one.threads = 1;
        const TileLook reference = measureTileLook(crop, one);
        ASSERT_TRUE(reference.measured);
        for (int threads : {2, 5}) {
            LookOptions options;
            options.threads = threads;
            const TileLook look = measureTileLook(crop, options);
            EXPECT_EQ(look.frame, reference.frame) << seed << " on " << threads;
            EXPECT_EQ(look.blobs, reference.blobs) << seed << " on " << threads;
            EXPECT_EQ(look.echo, reference.echo) << seed << " on " << threads;
        }
    }
}
