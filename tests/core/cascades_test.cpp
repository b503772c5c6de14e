#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "heightpack/core/sea/cascades.hpp"
#include "heightpack/core/sea/sea_report.hpp"

using namespace heightpack;

TEST(Cascades, BandsPartitionTheRangeAndSizesShareNoSmallFactor) {
    const auto bands = cascadeBands(1024.0, 128, 3, 9);
    ASSERT_EQ(bands.size(), 3u);
    EXPECT_EQ(bands[0].low, 0.0);
    for (size_t c = 0; c + 1 < bands.size(); ++c) {
        EXPECT_EQ(bands[c].high, bands[c + 1].low);
        EXPECT_LT(bands[c].low, bands[c].high);
        EXPECT_NE(bands[c].seed, bands[c + 1].seed);
        // The ratio of neighbouring sizes is 61/17: integers with no common factor (gcd 1).
        EXPECT_NEAR(bands[c].tileSize / bands[c + 1].tileSize, 61.0 / 17.0, 1e-12);
        EXPECT_EQ(std::gcd(61, 17), 1);
    }
    EXPECT_NEAR(bands.back().high, 3.14159265358979323846 * 128 / bands.back().tileSize, 1e-12);
}

TEST(Cascades, TheirSummedVarianceIsTheSpectrumsOverTheCoveredBand) {
    SpectrumOptions sea;
    sea.model = SpectrumModel::Jonswap;
    sea.windSpeed = 10.0;
    sea.fetch = 50000.0;
    sea.tileSize = 1024.0;
    sea.size = 128;
    const int seeds = 3;
    double realised = 0.0, resolved = 0.0;
    double high = 0.0;
    for (int seed = 1; seed <= seeds; ++seed) {
        for (const CascadeBand& band : cascadeBands(sea.tileSize, sea.size, 3, seed)) {
            const Ocean ocean(cascadeOptions(sea, band));
            const double hs = significantWaveHeight(ocean.heights(0.0));
            realised += hs * hs / 16.0 / seeds;
            resolved += ocean.resolvedVariance() / seeds;
            high = band.high;
        }
    }
    const double integral = spectrumVariance(sea, 0.0, high);
    EXPECT_NEAR(realised, integral, 0.1 * integral);
    EXPECT_NEAR(resolved, integral, 0.05 * integral);
}
