// Looping foam from the Jacobian, the Jacobian itself, and the sea-state numbers.
#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "heightpack/core/sea/foam.hpp"
#include "heightpack/core/sea/sea_report.hpp"
#include "heightpack/core/sea/spectrum.hpp"
#include "support/spectral_derivative.hpp"

using namespace heightpack;

namespace {

SpectrumOptions choppySea() {
    SpectrumOptions o;
    o.model = SpectrumModel::Jonswap;
    o.windSpeed = 16.0;
    o.fetch = 150000.0;
    o.tileSize = 96.0;
    o.size = 64;
    o.seed = 3;
    o.loopPeriod = 8.0;
    return o;
}

// d/dx or d/dy of one channel of a periodic field by the test's own DFT (tests/support).
cv::Mat spectralDerivative(const Image& field, int channel, int axis, double tileSize) {
    return test::spectralDerivative([&](int x, int y) { return double(field.at(x, y, channel)); }, field.width, axis,
                                    tileSize);
}

}  // namespace

TEST(Jacobian, IsTheDeterminantOfTheDisplacementsDerivatives) {
    const SpectrumOptions o = choppySea();
    const double lambda = 1.3;
    const SeaFields s = Ocean(o).fields(2.0, {true, true, true}, lambda);
    const cv::Mat xx = spectralDerivative(s.shift, 0, 0, o.tileSize), yy = spectralDerivative(s.shift, 1, 1, o.tileSize);
    const cv::Mat xy = spectralDerivative(s.shift, 0, 1, o.tileSize), yx = spectralDerivative(s.shift, 1, 0, o.tileSize);
    double lowest = 1.0;
    for (int y = 0; y < o.size; ++y)
        for (int x = 0; x < o.size; ++x) {
            const double j = (1 + lambda * xx.at<double>(y, x)) * (1 + lambda * yy.at<double>(y, x)) -
                             lambda * lambda * xy.at<double>(y, x) * yx.at<double>(y, x);
            ASSERT_NEAR(s.jacobian.at(x, y), j, 1e-4) << x << "," << y;
            lowest = std::min(lowest, j);
        }
    EXPECT_LT(lowest, 0.6);  // a choppy sea: the test sees compression, not only J near 1
    // Crests are compressed, troughs stretched (x + lambda D draws a crest's neighbours in).
    double crestJ = 0, troughJ = 0;
    const auto [lo, hi] = std::minmax_element(s.heights.pixels.begin(), s.heights.pixels.end());
    crestJ = s.jacobian.pixels[hi - s.heights.pixels.begin()];
    troughJ = s.jacobian.pixels[lo - s.heights.pixels.begin()];
    EXPECT_LT(crestJ, 1.0);
    EXPECT_GT(troughJ, 1.0);
}

TEST(Foam, TheLoopClosesAndFoamOnlyFormsBelowTheThreshold) {
    const SpectrumOptions o = choppySea();
    const Ocean ocean(o);
    const int frames = 16;
    FoamOptions foam;
    foam.threshold = 0.7;
    foam.decay = 3.0;  // longer than the loop's tenth: the state carries across frames
    std::vector<Image> jacobians;
    for (int f = 0; f < frames; ++f) jacobians.push_back(ocean.fields(f * o.loopPeriod / frames, {false, false, true}, 1.5).jacobian);
    const auto density = loopingFoamDensity(jacobians, o.loopPeriod, foam);
    // The frame after the last, stepped from the last with the sea's own J at t = period.
    std::vector<float> next = density.back();
    advanceFoam(next, ocean.fields(o.loopPeriod, {false, false, true}, 1.5).jacobian, o.loopPeriod / frames, foam);
    const Image first = foamCoverage(density.front(), o.size, o.size), after = foamCoverage(next, o.size, o.size);
    float most = 0;
    for (size_t i = 0; i < first.pixels.size(); ++i) {
        ASSERT_NEAR(after.pixels[i], first.pixels[i], 1e-6);
        most = std::max(most, first.pixels[i]);
    }
    EXPECT_GT(most, 0.2f);
    // Zero wherever J never went below the threshold; positive wherever it did.
    int foamless = 0;
    for (size_t i = 0; i < first.pixels.size(); ++i) {
        double lowest = 2.0;
        for (const Image& j : jacobians) lowest = std::min(lowest, double(j.pixels[i]));
        for (int f = 0; f < frames; ++f) {
            if (lowest >= foam.threshold) {
                ASSERT_EQ(density[f][i], 0.0f);
                ++foamless;
            }
        }
        if (lowest < foam.threshold - 1e-3) {
            EXPECT_GT(density[0][i], 0.0f);
        }
    }
    EXPECT_GT(foamless, 0);
}

TEST(Foam, AFrozenSeaSettlesAtBuildUpTimesDecay) {
    // J held still: the periodic state is the fixed point of d/dt = -F / decay + buildUp (threshold - J).
    Image j(4, 1, 1);
    j.pixels = {-0.5f, 0.2f, 0.5f, 1.4f};
    FoamOptions foam;
    const auto looped = loopingFoamDensity({j, j, j, j, j}, 5.0, foam);
    const auto frozen = loopingFoamDensity({j}, 0.0, foam);
    for (int i = 0; i < 4; ++i) {
        const double expected = foam.buildUp * foam.decay * std::max(0.0, foam.threshold - j.pixels[i]);
        EXPECT_NEAR(looped[2][i], expected, 1e-5 * (1 + expected));
        EXPECT_NEAR(frozen[0][i], expected, 1e-5 * (1 + expected));
    }
    // From nothing, one step of dt: buildUp (threshold - J) decay (1 - exp(-dt / decay)).
    std::vector<float> d(4, 0.0f);
    advanceFoam(d, j, 0.5, foam);
    EXPECT_NEAR(d[0], foam.buildUp * 1.0 * foam.decay * (1 - std::exp(-0.5 / foam.decay)), 1e-6);
}

TEST(SeaReport, TheBoundHoldsAndTheNumbersAreTheDirectOnes) {
    const SpectrumOptions o = choppySea();
    const Ocean ocean(o);
    double largest = 0;
    for (double t : {0.0, 1.1, 2.9, 5.3}) {
        const SeaFields s = ocean.fields(t, {true, true, true}, 1.0);
        largest = std::max(largest, largestShift(s.shift, 1.0));
        int folds = 0;
        for (float j : s.jacobian.pixels) folds += j < 0;
        EXPECT_DOUBLE_EQ(foldFraction(s.jacobian), double(folds) / s.jacobian.pixels.size());
        double sum = 0, sq = 0;
        for (float h : s.heights.pixels) sum += h, sq += double(h) * h;
        const double n = double(s.heights.pixels.size());
        EXPECT_NEAR(significantWaveHeight(s.heights), 4 * std::sqrt(sq / n - sum * sum / (n * n)), 1e-6);
    }
    EXPECT_GE(ocean.shiftBound(), largest);
    EXPECT_LT(ocean.shiftBound(), 100 * largest);  // a bound, but not a vacuous one
    // Steepness: Hs over the deep-water peak wavelength g Tp^2 / 2 pi.
    const SeaStateSummary summary = summariseSeaState(o, ocean.resolvedVariance());
    EXPECT_NEAR(summary.peakWavelength, kGravity * summary.peakPeriod * summary.peakPeriod / (2 * std::numbers::pi), 1e-3 * summary.peakWavelength);
    EXPECT_NEAR(summary.steepness, summary.significantWaveHeight / summary.peakWavelength, 1e-12);
    const double wp = 22.0 * std::pow(kGravity * kGravity / (o.windSpeed * o.fetch), 1.0 / 3.0);
    EXPECT_NEAR(summary.peakPeriod, 2 * std::numbers::pi / wp, 0.01 * 2 * std::numbers::pi / wp);
}
