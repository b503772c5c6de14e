#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "heightpack/core/fresnel.hpp"

using namespace heightpack;

namespace {

// The Fresnel equations in their angle form (Rs = sin^2(i-t)/sin^2(i+t), Rp = tan^2(i-t)/tan^2(i+t)),
// an independent formulation of what libpack computes from cosines.
double referenceFresnel(double thetaDegrees, double n) {
    const double i = thetaDegrees * std::numbers::pi / 180.0;
    if (i == 0.0) return std::pow((n - 1) / (n + 1), 2);
    const double t = std::asin(std::sin(i) / n);
    const double rs = std::pow(std::sin(i - t) / std::sin(i + t), 2);
    const double rp = std::pow(std::tan(i - t) / std::tan(i + t), 2);
    return 0.5 * (rs + rp);
}

}  // namespace

TEST(Fresnel, RampMatchesTheFresnelEquationsForWater) {
    const FresnelOptions options;  // ior 1.333, exact, N.V, 256 texels
    const Image ramp = makeFresnelRamp(options);
    ASSERT_EQ(ramp.width, 256);
    ASSERT_EQ(ramp.channels, 4);
    EXPECT_NEAR(referenceFresnel(0, 1.333), 0.0204, 5e-5);
    for (double degrees : {0.0, 30.0, 60.0, 80.0, 89.0}) {
        const double u = std::cos(degrees * std::numbers::pi / 180.0);
        EXPECT_NEAR(sampleRamp(ramp, u)[3], referenceFresnel(degrees, 1.333), 1e-4) << degrees << " degrees";
        EXPECT_NEAR(fresnelReflectance(u, 1.333, FresnelModel::Exact), referenceFresnel(degrees, 1.333), 1e-9);
    }
}

TEST(Fresnel, ReflectanceFallsMonotonicallyTowardNormalIncidence) {
    const Image ramp = makeFresnelRamp(FresnelOptions{});
    for (int i = 1; i < ramp.width; ++i) ASSERT_LT(ramp.at(i, 0, 3), ramp.at(i - 1, 0, 3)) << "texel " << i;
    EXPECT_GT(ramp.at(0, 0, 3), 0.9);  // grazing: nearly a mirror
}

TEST(Fresnel, SchlickIsSchlicksFormula) {
    FresnelOptions options;
    options.model = FresnelModel::Schlick;
    options.size = 64;
    const Image ramp = makeFresnelRamp(options);
    const double r0 = std::pow(0.333 / 2.333, 2);
    for (int i = 0; i < 64; ++i) {
        const double c = (i + 0.5) / 64;
        ASSERT_NEAR(ramp.at(i, 0, 3), r0 + (1 - r0) * std::pow(1 - c, 5), 1e-7);
    }
}

TEST(Fresnel, TwoNdotVIndexingCoversTheFirstHalf) {
    FresnelOptions options;
    options.index = FresnelIndex::TwoNdotV;
    const Image ramp = makeFresnelRamp(options);
    for (double nv : {0.05, 0.2, 0.35, 0.45}) {
        const double u = std::min(1.0, 2 * nv);
        EXPECT_NEAR(sampleRamp(ramp, u)[3], fresnelReflectance(nv, 1.333, FresnelModel::Exact), 2e-4) << nv;
    }
}

TEST(Fresnel, ColourBlendsFromShallowAtGrazingToDeepLookingDown) {
    FresnelOptions options;
    options.size = 10;
    const Image ramp = makeFresnelRamp(options);
    for (int i = 0; i < 10; ++i) {
        const double c = (i + 0.5) / 10;
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(ramp.at(i, 0, ch), options.shallow[ch] * (1 - c) + options.deep[ch] * c, 1e-6);
    }
}
