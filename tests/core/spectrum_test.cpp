#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "heightpack/core/mip.hpp"
#include "heightpack/core/sea/spectrum.hpp"
#include "heightpack/core/tile/tileable.hpp"

using namespace heightpack;

namespace {

SpectrumOptions windSea(SpectrumModel model, uint64_t seed = 1) {
    SpectrumOptions o;
    o.model = model;
    o.windSpeed = 10.0;
    o.fetch = 50000.0;
    o.windDirection = 30.0;
    o.tileSize = 512.0;
    o.size = 256;
    o.seed = seed;
    return o;
}

double stddev(const Image& image) {
    double sum = 0, sq = 0;
    for (float v : image.pixels) sum += v, sq += double(v) * v;
    const double n = double(image.pixels.size());
    return std::sqrt(sq / n - (sum / n) * (sum / n));
}

}  // namespace

TEST(Spectrum, JonswapMatchesTheFetchLawsItWasFittedTo) {
    // Fetch-limited growth (Hasselmann et al. 1973, as in the Shore Protection Manual): Hs ~ 1.6e-3 U
    // sqrt(F / g), peak frequency wp = 22 (g^2 / (U F))^(1/3).
    SpectrumOptions o = windSea(SpectrumModel::Jonswap);
    const double hs = 4 * std::sqrt(spectrumVariance(o));
    EXPECT_NEAR(hs, 1.6e-3 * o.windSpeed * std::sqrt(o.fetch / kGravity), 0.25 * hs);
    double best = 0, bestK = 0;
    for (double k = 0.001; k < 2.0; k *= 1.001)
        if (omnidirectionalSpectrum(o, k) * std::sqrt(k) > best)  // S(w) is S(k) dk/dw, and dk/dw ~ sqrt(k)
            best = omnidirectionalSpectrum(o, k) * std::sqrt(k), bestK = k;
    const double wp = 22.0 * std::pow(kGravity * kGravity / (o.windSpeed * o.fetch), 1.0 / 3.0);
    EXPECT_NEAR(std::sqrt(kGravity * bestK), wp, 0.01 * wp);
}

TEST(Spectrum, PhillipsVarianceIsAlphaLw2Over4) {
    // The integral of (alpha/2) k^-3 exp(-1/(k Lw)^2) dk is alpha Lw^2 / 4 (small-wave cut-off aside).
    SpectrumOptions o = windSea(SpectrumModel::Phillips);
    o.smallWaveLength = 1e-6;
    const double lw = o.windSpeed * o.windSpeed / kGravity;
    EXPECT_NEAR(spectrumVariance(o), o.phillipsAlpha * lw * lw / 4, 1e-3 * o.phillipsAlpha * lw * lw / 4);
}

TEST(Spectrum, SynthesisedSeasTileAtEveryLevel) {
    for (SpectrumModel m : {SpectrumModel::Phillips, SpectrumModel::Jonswap}) {
        const Image h = Ocean(windSea(m)).heights(3.0);
        for (const Image& level : generateMipChain(h, Filter::Kaiser))
            EXPECT_TRUE(levelTiles(measureSeams(level))) << spectrumModelName(m) << " " << level.width;
    }
}

TEST(Spectrum, MeasuredPowerSpectrumFollowsTheRequestedOne) {
    // The forward DFT of the map (an independent transform) gives N^2 h(k); its power, summed over rings
    // of |k|, against the spectrum's expected power in the same rings.
    for (SpectrumModel m : {SpectrumModel::Phillips, SpectrumModel::Jonswap}) {
        const SpectrumOptions o = windSea(m, 11);
        const int n = o.size;
        const Image h = Ocean(o).heights(0.0);
        cv::Mat field(n, n, CV_64F);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) field.at<double>(y, x) = h.at(x, y);
        cv::Mat f;
        cv::dft(field, f, cv::DFT_COMPLEX_OUTPUT);
        const double dk = 2 * std::numbers::pi / o.tileSize;
        const int rings = n / 2;
        std::vector<double> measured(rings, 0.0), expected(rings, 0.0);
        std::vector<int> modes(rings, 0);
        for (int r = 0; r < n; ++r) {
            for (int q = 0; q < n; ++q) {
                const int mx = q < n / 2 ? q : q - n, my = r < n / 2 ? r : r - n;
                const int ring = static_cast<int>(std::hypot(mx, my) / 2);
                if (ring >= rings || (mx == 0 && my == 0)) continue;
                const cv::Vec2d z = f.at<cv::Vec2d>(r, q);
                measured[ring] += (z[0] * z[0] + z[1] * z[1]) / (double(n) * n * n * n);
                const double s = directionalSpectrum(o, mx * dk, my * dk) + directionalSpectrum(o, -mx * dk, -my * dk);
                expected[ring] += 0.5 * s * dk * dk;
                ++modes[ring];
            }
        }
        const double peak = *std::max_element(expected.begin(), expected.end());
        std::vector<double> ratios;
        for (int i = 0; i < rings; ++i) {
            if (expected[i] < 0.01 * peak || modes[i] < 30) continue;
            ratios.push_back(measured[i] / expected[i]);
            EXPECT_GT(ratios.back(), 0.5) << spectrumModelName(m) << " ring " << i;
            EXPECT_LT(ratios.back(), 1.8) << spectrumModelName(m) << " ring " << i;
        }
        ASSERT_GT(ratios.size(), 8u);
        std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
        EXPECT_NEAR(ratios[ratios.size() / 2], 1.0, 0.15) << spectrumModelName(m);
    }
}

TEST(Spectrum, SignificantWaveHeightMatchesTheSpectrumsIntegral) {
    for (SpectrumModel m : {SpectrumModel::Phillips, SpectrumModel::Jonswap}) {
        double measured = 0;
        const int seeds = 4;
        for (int seed = 1; seed <= seeds; ++seed) measured += 4 * stddev(Ocean(windSea(m, seed)).heights(0.0)) / seeds;
        const double expected = 4 * std::sqrt(spectrumVariance(windSea(m)));
        EXPECT_NEAR(measured, expected, 0.1 * expected) << spectrumModelName(m);
    }
}

TEST(Spectrum, TheAnimationLoops) {
    SpectrumOptions o = windSea(SpectrumModel::Jonswap);
    o.size = 128;
    o.tileSize = 128;
    o.loopPeriod = 8.0;
    const Ocean ocean(o);
    const Image start = ocean.heights(0.0), end = ocean.heights(8.0);
    for (size_t i = 0; i < start.pixels.size(); ++i) ASSERT_NEAR(end.pixels[i], start.pixels[i], 1e-5);
    // Frames change smoothly: a shorter step changes the sea less, and a 1/64 loop step only a little.
    auto maxChange = [&](double dt) {
        const Image a = ocean.heights(2.0), b = ocean.heights(2.0 + dt);
        double worst = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i) worst = std::max(worst, double(std::abs(a.pixels[i] - b.pixels[i])));
        return worst;
    };
    const double range = 8 * stddev(start);
    EXPECT_LT(maxChange(8.0 / 64), 0.2 * range);
    EXPECT_LT(maxChange(8.0 / 256), 0.5 * maxChange(8.0 / 64));
    EXPECT_GT(maxChange(8.0 / 64), 0.0);
}

TEST(Spectrum, SameSeedSameSeaOtherSeedsUncorrelated) {
    const SpectrumOptions a = windSea(SpectrumModel::Phillips, 7);
    EXPECT_EQ(Ocean(a).heights(1.5).pixels, Ocean(a).heights(1.5).pixels);
    const Image x = Ocean(a).heights(0.0), y = Ocean(windSea(SpectrumModel::Phillips, 8)).heights(0.0);
    double sxy = 0, sxx = 0, syy = 0;
    for (size_t i = 0; i < x.pixels.size(); ++i) {
        sxy += double(x.pixels[i]) * y.pixels[i];
        sxx += double(x.pixels[i]) * x.pixels[i];
        syy += double(y.pixels[i]) * y.pixels[i];
    }
    EXPECT_LT(std::abs(sxy / std::sqrt(sxx * syy)), 0.15);
}

TEST(Spectrum, TheSameBytesOnAnyThreadCountFrozenOrEvolving) {
    // The amplitudes are drawn per wave vector from a counter-based generator and the transforms split in
    // fixed blocks: one thread, three, or an ocean that keeps t = 0 only give every field bit for bit.
    SpectrumOptions o = windSea(SpectrumModel::Jonswap, 11);
    o.size = 128, o.tileSize = 300.0, o.depth = 40.0, o.swell.significantHeight = 1.0;
    const Ocean one(o, 1), three(o, 3), frozen(o, OceanOptions{2, false});
    for (double t : {0.0, 3.5}) {
        const SeaFields a = one.fields(t, {true, true, true}, 1.3, 1), b = three.fields(t, {true, true, true}, 1.3, 3);
        EXPECT_EQ(a.heights.pixels, b.heights.pixels) << t;
        EXPECT_EQ(a.shift.pixels, b.shift.pixels) << t;
        EXPECT_EQ(a.jacobian.pixels, b.jacobian.pixels) << t;
        if (t == 0.0) {
            EXPECT_EQ(frozen.fields(t, {true, true, true}, 1.3, 2).jacobian.pixels, a.jacobian.pixels);
        }
    }
    EXPECT_EQ(one.resolvedVariance(), three.resolvedVariance());
    EXPECT_EQ(one.shiftBound(), frozen.shiftBound());
}

TEST(Spectrum, FieldsIntoOneInterleavedImageEqualEachFieldAlone) {
    // fieldsInto keeps its transforms' work in the heights' storage until the heights are written: into
    // one interleaved image (heights, Dx, Dy, J) every field must come out as the same field asked for
    // alone, where each has storage of its own, frozen or evolving, on any thread count.
    SpectrumOptions o = windSea(SpectrumModel::Jonswap, 17);
    o.size = 64, o.tileSize = 200.0;
    const Ocean ocean(o, 2);
    for (double t : {0.0, 2.25})
        for (int threads : {1, 3}) {
            const int n = o.size;
            std::vector<float> image(size_t(n) * n * 4);
            SeaFieldTargets to;
            to.heights = {image.data(), 4}, to.shiftX = {image.data() + 1, 4};
            to.shiftY = {image.data() + 2, 4}, to.jacobian = {image.data() + 3, 4};
            ocean.fieldsInto(t, to, 0.8, threads);
            const Image h = ocean.fields(t, {true, false, false}, 0.8, threads).heights;
            const Image d = ocean.fields(t, {false, true, false}, 0.8, threads).shift;
            const Image j = ocean.fields(t, {false, false, true}, 0.8, threads).jacobian;
            for (size_t i = 0; i < h.texelCount(); ++i) {
                ASSERT_EQ(image[4 * i], h.pixels[i]) << t << " on " << threads << " at " << i;
                ASSERT_EQ(image[4 * i + 1], d.pixels[2 * i]) << t << " on " << threads << " at " << i;
                ASSERT_EQ(image[4 * i + 2], d.pixels[2 * i + 1]) << t << " on " << threads << " at " << i;
                ASSERT_EQ(image[4 * i + 3], j.pixels[i]) << t << " on " << threads << " at " << i;
            }
        }
}

TEST(Spectrum, DisplacementIsTheHeightTurnedAlongEachWave) {
    // D(k) = i k/|k| h(k): by Parseval, var(Dx) + var(Dy) = var(h) exactly (k = 0 carries nothing), and
    // the DFT of Dx is the height's DFT times i kx/|k|, checked on an independent transform.
    SpectrumOptions o = windSea(SpectrumModel::Jonswap, 5);
    o.size = 64;
    o.tileSize = 256;
    const Ocean ocean(o);
    const Image h = ocean.heights(1.25), d = ocean.shift(1.25);
    double vh = 0, vx = 0, vy = 0;
    for (size_t i = 0; i < h.texelCount(); ++i) {
        vh += double(h.pixels[i]) * h.pixels[i];
        vx += double(d.pixels[2 * i]) * d.pixels[2 * i];
        vy += double(d.pixels[2 * i + 1]) * d.pixels[2 * i + 1];
    }
    EXPECT_NEAR(vx + vy, vh, 1e-4 * vh);
    const int n = o.size;
    cv::Mat hf(n, n, CV_64F), dxf(n, n, CV_64F);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) hf.at<double>(y, x) = h.at(x, y), dxf.at<double>(y, x) = d.at(x, y, 0);
    cv::Mat H, DX;
    cv::dft(hf, H, cv::DFT_COMPLEX_OUTPUT);
    cv::dft(dxf, DX, cv::DFT_COMPLEX_OUTPUT);
    double peak = 0;
    for (int r = 0; r < n; ++r)
        for (int q = 0; q < n; ++q) peak = std::max(peak, cv::norm(H.at<cv::Vec2d>(r, q)));
    for (int r = 0; r < n; ++r) {
        for (int q = 0; q < n; ++q) {
            const cv::Vec2d z = H.at<cv::Vec2d>(r, q);
            if (cv::norm(z) < 0.01 * peak) continue;
            const int mx = q < n / 2 ? q : q - n, my = r < n / 2 ? r : r - n;
            const double f = mx / std::hypot(double(mx), double(my));
            const cv::Vec2d expected(-z[1] * f, z[0] * f);  // (re + i im)(i f)
            EXPECT_LT(cv::norm(DX.at<cv::Vec2d>(r, q) - expected), 1e-3 * peak) << mx << "," << my;
        }
    }
}
