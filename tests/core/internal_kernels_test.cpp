// The core floor's internal kernels against independent computations: the threaded 2-D DFTs
// (libpack/core/dft.hpp) against OpenCV's own single-threaded cv::dft, the radix sort behind the rank
// Gaussianisation (libpack/core/tile/gaussianise.hpp) against std::stable_sort, and the sea's counter-based
// normal deviates (libpack/core/sea/counter_normals.hpp) against the standard normal's moments.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstring>
#include <functional>
#include <numeric>
#include <random>
#include <vector>

#include "sea/counter_normals.hpp"
#include "dft.hpp"
#include "tile/gaussianise.hpp"
#include "tile/strip_field.hpp"

using namespace heightpack;

namespace {

double largest(const cv::Mat& m) { return cv::norm(m, cv::NORM_INF); }

}  // namespace

TEST(ThreadedDft, EqualsOpenCvsTransformAtOddAndEvenSizesOnAnyThreadCount) {
    std::mt19937 random(7);
    for (const auto& [w, h] : {std::pair{1, 1}, {5, 3}, {37, 50}, {64, 64}, {100, 17}, {256, 96}}) {
        cv::Mat field(h, w, CV_64F);
        std::normal_distribution<double> normal;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) field.at<double>(y, x) = normal(random);
        cv::Mat expected, back, expectedBack;
        cv::dft(field, expected, cv::DFT_COMPLEX_OUTPUT);
        cv::dft(expected, expectedBack, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
        const cv::Mat first = detail::forwardDft(field, 1);
        EXPECT_LE(largest(first - expected), 1e-9 * std::max(1.0, largest(expected))) << w << "x" << h;
        detail::inverseDft(first, back, 1);
        EXPECT_LE(largest(back - field), 1e-12 * std::max(1.0, largest(field))) << w << "x" << h;
        EXPECT_LE(largest(back - expectedBack), 1e-12) << w << "x" << h;
        for (int threads : {2, 3, 8}) {  // the same bytes whatever the thread count
            const cv::Mat spectrum = detail::forwardDft(field, threads);
            EXPECT_EQ(std::memcmp(spectrum.data, first.data, first.total() * first.elemSize()), 0) << threads;
            cv::Mat again;
            detail::inverseDft(spectrum, again, threads);
            EXPECT_EQ(std::memcmp(again.data, back.data, back.total() * back.elemSize()), 0) << threads;
        }
    }
}

TEST(ThreadedDft, RealInverseOfAHalfSpectrumInFloatEqualsOpenCvsFullInverse) {
    // A real field's full spectrum (cv::dft, double) is the reference; the half kx = 0 .. w/2 of it, in
    // float, must come back to the unscaled inverse to float rounding, with the same bytes on any threads.
    // Odd widths have no real last column (the tile's re-synthesis takes maps of any size).
    std::mt19937 random(5);
    std::normal_distribution<double> normal;
    for (const auto& [w, h] : {std::pair{2, 1}, {4, 4}, {8, 2}, {16, 64}, {64, 16}, {128, 128}, {3, 5}, {17, 16}, {99, 31}}) {
        cv::Mat field(h, w, CV_64F), full;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) field.at<double>(y, x) = normal(random);
        cv::dft(field, full, cv::DFT_COMPLEX_OUTPUT);
        auto inverse = [&](int threads) {
            std::vector<std::complex<float>> half(size_t(h) * (w / 2 + 1));
            for (int y = 0; y < h; ++y)
                for (int x = 0; x <= w / 2; ++x) {
                    const cv::Vec2d z = full.at<cv::Vec2d>(y, x);
                    half[size_t(y) * (w / 2 + 1) + x] = {float(z[0]), float(z[1])};
                }
            std::vector<float> out(size_t(w) * h, -1.0f);
            detail::inverseRealDftOfHalf(half.data(), w, h, threads,
                                         [&](int y, const float* row) { std::copy(row, row + w, out.begin() + size_t(y) * w); });
            return out;
        };
        const std::vector<float> one = inverse(1);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)  // no 1/(w h): the field times w h
                ASSERT_NEAR(one[size_t(y) * w + x], field.at<double>(y, x) * w * h, 1e-5 * w * h) << w << "x" << h;
        for (int threads : {2, 3}) EXPECT_EQ(inverse(threads), one) << w << "x" << h << " on " << threads;
    }
}

TEST(ThreadedDft, HalfSpectrumOfARealFieldInFloatEqualsOpenCvsFullTransform) {
    // cv::dft in double of the whole field is the reference: the float half must match it to float
    // rounding of the largest value, at odd and even sizes, with the same bytes on any thread count.
    std::mt19937 random(11);
    std::normal_distribution<double> normal;
    for (const auto& [w, h] : {std::pair{1, 1}, {2, 3}, {5, 4}, {16, 64}, {99, 31}, {128, 96}}) {
        cv::Mat field(h, w, CV_64F), full;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) field.at<double>(y, x) = float(normal(random));
        cv::dft(field, full, cv::DFT_COMPLEX_OUTPUT);
        auto half = [&](int threads) {
            return detail::forwardRealDftToHalf(w, h, threads, [&](int y, float* row) {
                for (int x = 0; x < w; ++x) row[x] = float(field.at<double>(y, x));
            });
        };
        const std::vector<std::complex<float>> one = half(1);
        ASSERT_EQ(one.size(), size_t(h) * (w / 2 + 1));
        const double tolerance = 1e-6 * std::max(1.0, largest(full));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x <= w / 2; ++x) {
                const cv::Vec2d z = full.at<cv::Vec2d>(y, x);
                const std::complex<float> got = one[size_t(y) * (w / 2 + 1) + x];
                ASSERT_NEAR(got.real(), z[0], tolerance) << w << "x" << h << " at " << x << "," << y;
                ASSERT_NEAR(got.imag(), z[1], tolerance) << w << "x" << h << " at " << x << "," << y;
            }
        for (int threads : {2, 3}) EXPECT_EQ(half(threads), one) << w << "x" << h << " on " << threads;
    }
}

TEST(ThreadedDft, FieldsSharingOneColumnPassEqualTheirOwnInverses) {
    // A field and its x derivative (factor i kx, 0 at the Nyquist column) from one column pass, against
    // cv::dft of the full spectrum times i kx; and an odd column factor (ky, as the sea's Dy pass uses)
    // whose kx = 0 column is imaginary until its row factor i makes it real.
    std::mt19937 random(9);
    std::normal_distribution<double> normal;
    const int w = 32, h = 16;
    cv::Mat field(h, w, CV_64F), full;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) field.at<double>(y, x) = normal(random);
    cv::dft(field, full, cv::DFT_COMPLEX_OUTPUT);
    auto signedBin = [](int q, int n) { return q < n / 2 ? q : q - n; };
    // The reference: cv::dft's inverse of the full spectrum times m(kx, ky), unscaled.
    auto reference = [&](const std::function<std::complex<double>(int kx, int ky)>& m) {
        cv::Mat product = full.clone(), out;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const bool nyquist = x == w / 2 || y == h / 2;
                const cv::Vec2d z = full.at<cv::Vec2d>(y, x);
                const std::complex<double> v = nyquist ? 0.0 : std::complex<double>(z[0], z[1]) * m(signedBin(x, w), signedBin(y, h));
                product.at<cv::Vec2d>(y, x) = {v.real(), v.imag()};
            }
        cv::dft(product, out, cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT);
        return out;
    };
    // The half spectrum times a column multiplier of ky (the Nyquist row and column left empty).
    auto half = [&](bool timesKy) {
        std::vector<std::complex<float>> out(size_t(h) * (w / 2 + 1));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w / 2; ++x) {
                const cv::Vec2d z = full.at<cv::Vec2d>(y, x);
                const double m = y == h / 2 ? 0.0 : timesKy ? signedBin(y, h) : 1.0;
                out[size_t(y) * (w / 2 + 1) + x] = {float(z[0] * m), float(z[1] * m)};
            }
        return out;
    };
    std::vector<std::complex<float>> ikx(w / 2 + 1), i(w / 2 + 1, {0.0f, 1.0f});
    for (int q = 0; q < w / 2; ++q) ikx[q] = {0.0f, float(q)};
    for (int threads : {1, 3}) {
        std::vector<float> plain(size_t(w) * h), dx(plain.size()), dy(plain.size());
        auto into = [&](std::vector<float>& v) {
            return [&v, w](int y, const float* row) { std::copy(row, row + w, v.begin() + size_t(y) * w); };
        };
        std::vector<std::complex<float>> a = half(false), b = half(true);
        detail::inverseRealDftOfHalf(a.data(), w, h, threads, {{{}, into(plain)}, {ikx, into(dx)}});
        detail::inverseRealDftOfHalf(b.data(), w, h, threads, {{i, into(dy)}});
        const cv::Mat p = reference([](int, int) { return 1.0; });
        const cv::Mat x = reference([](int kx, int) { return std::complex<double>(0.0, kx); });
        const cv::Mat y = reference([](int, int ky) { return std::complex<double>(0.0, ky); });
        for (int r = 0; r < h; ++r)
            for (int c = 0; c < w; ++c) {
                const size_t at = size_t(r) * w + c;
                ASSERT_NEAR(plain[at], p.at<double>(r, c), 1e-3) << threads;
                ASSERT_NEAR(dx[at], x.at<double>(r, c), 1e-2) << threads;
                ASSERT_NEAR(dy[at], y.at<double>(r, c), 1e-2) << threads;
            }
    }
}

TEST(ThreadedDft, HalfSpectrumGivenAsItGoesEqualsTheStoredOneWithTheLastFieldAsScratch) {
    // The overload with no spectrum of its own: the half spectrum read through a callback, the columns'
    // result kept in the storage of a field it writes (interleaved, three floats a texel, with a field
    // written beside it), must give the same bytes as the overload that transforms a stored spectrum.
    std::mt19937 random(3);
    std::normal_distribution<float> normal;
    for (const auto& [w, h] : {std::pair{2, 1}, {8, 2}, {16, 64}, {64, 16}, {34, 9}}) {
        const int columns = w / 2 + 1;
        std::vector<std::complex<float>> spectrum(size_t(h) * columns);
        for (auto& z : spectrum) z = {normal(random), normal(random)};
        // Real where a real field's spectrum is: the columns kx = 0 and w/2 of rows 0 and h/2.
        for (int r : {0, h / 2})
            for (int q : {0, w / 2}) spectrum[size_t(r) * columns + q].imag(0.0f);
        std::vector<std::complex<float>> ikx(columns);
        for (int q = 0; q < columns; ++q) ikx[q] = {0.0f, float(q)};
        auto into = [w](std::vector<float>& v, int stride, int channel) {
            return [&v, w, stride, channel](int y, const float* row) {
                for (int x = 0; x < w; ++x) v[(size_t(y) * w + x) * stride + channel] = row[x];
            };
        };
        std::vector<float> plain(size_t(w) * h), dx(plain.size());
        std::vector<std::complex<float>> copy = spectrum;
        detail::inverseRealDftOfHalf(copy.data(), w, h, 1, {{ikx, into(dx, 1, 0)}, {{}, into(plain, 1, 0)}});
        for (int threads : {1, 3}) {
            std::vector<float> image(size_t(w) * h * 3, 7.0f);  // channel 0 the scratch, then plain; 1: dx; 2 untouched
            std::vector<std::complex<float>> lastColumn(h);
            const detail::HalfSpectrumSource give = [&](int q0, int count, std::complex<float>* lines, size_t lineStride) {
                for (int r = 0; r < h; ++r)
                    for (int i = 0; i < count; ++i) lines[i * lineStride + r] = spectrum[size_t(r) * columns + q0 + i];
            };
            detail::inverseRealDftOfHalf(w, h, threads, give, {image.data(), 3, lastColumn.data()},
                                         {{ikx, into(image, 3, 1)}, {{}, into(image, 3, 0)}});
            for (size_t i = 0; i < plain.size(); ++i) {
                ASSERT_EQ(image[3 * i], plain[i]) << w << "x" << h << " on " << threads << " at " << i;
                ASSERT_EQ(image[3 * i + 1], dx[i]) << w << "x" << h << " on " << threads << " at " << i;
                ASSERT_EQ(image[3 * i + 2], 7.0f);
            }
        }
    }
}

TEST(CounterNormals, AreStandardNormalAndUncorrelatedAlongCellsRowsAndSeeds) {
    // 10^6 deviates: 500 000 pairs of a 4096-wide grid, as Ocean draws them (index = row * 4096 + column).
    // Every tolerance is 5 standard errors of its estimate over N values: mean 1/sqrt(N), variance
    // sqrt(2/N), fourth moment sqrt(96/N) (E x^8 - 9 = 96), a correlation 1/sqrt(N).
    constexpr uint64_t kWidth = 4096, kPairs = 500000;
    const uint64_t key = detail::normalStreamKey(1), other = detail::normalStreamKey(1 + detail::kSplitMixGamma);
    std::vector<double> first(kPairs), second(kPairs), otherSeed(kPairs);
    for (uint64_t i = 0; i < kPairs; ++i) {
        const detail::NormalPair g = detail::normalPair(key, i);
        first[i] = g.first, second[i] = g.second;
        otherSeed[i] = detail::normalPair(other, i).first;  // a cascade's seed, as cascadeBands spaces them
    }
    std::vector<double> all(first);
    all.insert(all.end(), second.begin(), second.end());
    const double n = double(all.size());
    auto mean = [](const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size()); };
    auto moment = [&](int power) {
        double sum = 0.0;
        for (double x : all) sum += std::pow(x, power);
        return sum / n;
    };
    // E[a b] over the pairs (a[i], b[i + shift]): a correlation, the deviates being standard.
    auto correlation = [](const std::vector<double>& a, const std::vector<double>& b, size_t shift) {
        double sum = 0.0;
        for (size_t i = 0; i + shift < a.size(); ++i) sum += a[i] * b[i + shift];
        return sum / double(a.size() - shift);
    };
    EXPECT_NEAR(mean(all), 0.0, 5 / std::sqrt(n));
    EXPECT_NEAR(moment(2), 1.0, 5 * std::sqrt(2 / n));
    EXPECT_NEAR(moment(3), 0.0, 5 * std::sqrt(15 / n));
    EXPECT_NEAR(moment(4), 3.0, 5 * std::sqrt(96 / n));
    const double half = 5 / std::sqrt(double(kPairs) - double(kWidth));
    EXPECT_NEAR(correlation(first, second, 0), 0.0, half);       // real and imaginary part of one cell
    EXPECT_NEAR(correlation(first, first, 1), 0.0, half);        // neighbouring cells of a row
    EXPECT_NEAR(correlation(second, first, 1), 0.0, half);
    EXPECT_NEAR(correlation(first, first, kWidth), 0.0, half);   // neighbouring rows
    EXPECT_NEAR(correlation(first, otherSeed, 0), 0.0, half);    // the same cell of another cascade
    EXPECT_NEAR(correlation(first, otherSeed, 1), 0.0, half);    // ... not a stream shifted by one
    // The tails: P(|x| > 3) = 0.0026998 for a standard normal, its standard error sqrt(p (1 - p) / N).
    const double p = 0.0026998;
    const double beyond = double(std::count_if(all.begin(), all.end(), [](double x) { return std::abs(x) > 3.0; })) / n;
    EXPECT_NEAR(beyond, p, 5 * std::sqrt(p * (1 - p) / n));
    // A pure function of (key, index): asked again, in another order, the same bits.
    EXPECT_EQ(detail::normalPair(key, 123456).first, first[123456]);
}

TEST(StableOrder, EqualsStdStableSortWithTiesNegativesAndSignedZeros) {
    std::mt19937 random(11);
    for (int trial = 0; trial < 40; ++trial) {
        // Some longer than the sort's 64 chunks x 2048 digits, so chunks hold many items of a digit, and
        // long enough to be sorted by buckets of the value range (at least 16 buckets of 4096 values).
        const size_t n = trial % 4 >= 2 ? 250000 + random() % 50000 : 1 + random() % 5000;
        std::vector<float> values(n);
        // Few distinct levels (ties), both signs, both zeros, tiny and huge magnitudes (the crowded case);
        // uniform values, some in steps of 1/64 (ties within buckets); normal values with a few huge
        // ones (a bucket holds most).
        const float levels[] = {-0.0f, 0.0f, -1.5f, 2.0f, 1e-30f, -1e-30f, 3e38f, -3e38f, 0.25f};
        std::normal_distribution<float> normal(0.0f, 1.0f);
        for (float& v : values)
            v = trial % 3 == 0   ? levels[random() % 9]
                : trial % 3 == 1 ? std::uniform_real_distribution<float>(-4.0f, 4.0f)(random) * (trial % 2 ? 64 : 1)
                : random() % 100000 == 0 ? 1e6f
                                        : normal(random);
        if (trial % 3 == 1 && trial % 2)
            for (float& v : values) v = std::round(v) / 64;
        std::vector<uint32_t> expected(n);
        std::iota(expected.begin(), expected.end(), 0u);
        std::stable_sort(expected.begin(), expected.end(), [&](uint32_t a, uint32_t b) { return values[a] < values[b]; });
        EXPECT_EQ(detail::stableOrder(values, 1), expected) << trial;
        EXPECT_EQ(detail::stableOrder(values, 3), expected) << trial;
        // The Gaussianiser (exact ranks below 2^20 values) takes each rank's quantile back to the rank's
        // value: between its neighbours in the sorted order (-0 as +0, which compares equal).
        const detail::Gaussianiser ranks(values, 2);
        ASSERT_TRUE(ranks.exact());
        for (size_t k = 0; k < n; k += 1 + n / 200) {
            const float back = ranks.back(detail::inverseNormalCdf((double(k) + 0.5) / double(n)));
            const float below = values[expected[k == 0 ? 0 : k - 1]], above = values[expected[std::min(n - 1, k + 1)]];
            ASSERT_TRUE(back >= below && back <= above) << trial << " " << k << ": " << back << " not in [" << below << ", " << above << "]";
        }
    }
}

TEST(Gaussianiser, BinnedRanksAreTheSortsToWithinTheirPartsOnLargeMaps) {
    // 2^21 values from several distributions, against the exact mid-rank quantiles of a sort: the binned
    // ranks (used from 2^20 values on) are off by little, ties exactly as the sort, and back returns a
    // value within two parts' widths of the one whose Gaussian it is given. A cluster crowded into one part
    // is sorted instead.
    std::mt19937 random(5);
    const size_t n = (size_t(1) << 21) + 12345;
    for (int kind = 0; kind < 6; ++kind) {
        std::vector<float> values(n);
        std::normal_distribution<float> normal(0.0f, 1.0f);
        std::exponential_distribution<float> exponential(3.0f);
        for (float& v : values) {
            switch (kind) {
                case 0: v = normal(random); break;
                case 1: v = std::uniform_real_distribution<float>(-1.0f, 3.0f)(random); break;
                case 2: v = exponential(random); break;  // skewed, a long tail
                case 3: v = random() % 5 == 0 ? 8.0f : normal(random); break;  // a fifth of them one value
                case 4: v = (random() % 2 ? 40.0f : 0.0f) + normal(random); break;  // two clusters far apart
                default: v = random() % 3 == 0 ? 0.5f + 1e-4f * normal(random) : 10 * normal(random); break;  // crowded
            }
        }
        std::vector<uint32_t> order(n);
        std::iota(order.begin(), order.end(), 0u);
        std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return values[a] < values[b]; });
        std::vector<double> reference(n);
        for (size_t start = 0; start < n;) {
            size_t stop = start + 1;
            while (stop < n && values[order[stop]] == values[order[start]]) ++stop;
            const double g = detail::inverseNormalCdf((0.5 * double(start + stop - 1) + 0.5) / double(n));
            for (size_t k = start; k < stop; ++k) reference[order[k]] = g;
            start = stop;
        }
        const detail::Gaussianiser ranks(values, 3);
        if (kind == 5) {
            EXPECT_TRUE(ranks.exact());
            continue;
        }
        ASSERT_FALSE(ranks.exact()) << kind;
        double worst = 0, squares = 0, worstBack = 0;
        const double width = (double(values[order[n - 1]]) - values[order[0]]) / detail::Gaussianiser::kRankBins;
        for (size_t i = 0; i < n; ++i) {
            const double error = std::abs(ranks.gaussian[i] - reference[i]);
            worst = std::max(worst, error);
            squares += error * error;
            if (kind == 3 && values[i] == 0.25f) {
                ASSERT_NEAR(ranks.gaussian[i], reference[i], 1e-9) << "a tie takes its mid-rank";
            }
            if (i % 64 == 0) {
                const double e = std::abs(double(ranks.back(reference[i])) - values[i]) / width;
                worstBack = std::max(worstBack, e);
            }
        }
        EXPECT_LT(std::sqrt(squares / double(n)), 1e-4) << kind;
        EXPECT_LT(worst, 5e-3) << kind;  // the far tails, where a rank's quantile moves fastest
        EXPECT_LT(worstBack, 2.0) << kind;
        if (kind == 4) {
            EXPECT_TRUE(detail::Gaussianiser(values, 1).gaussian == ranks.gaussian) << "the same on any thread count";
        }
    }
}

TEST(StripField, KeepsTheTexelsNearTheWrapLinesOnceEach) {
    // A 37 x 23 field kept within 5 columns of the left/right wrap line and 3 rows of the top/bottom one:
    // each kept texel reads back what its row gave (a texel in both strips from its row's copy), a write
    // to one reads back, and exactly the texels within reach are kept.
    const int w = 37, h = 23, reachX = 5, reachY = 3;
    detail::StripField strips(w, h, reachX, reachY);
    std::vector<double> full(size_t(w) * h);
    for (size_t i = 0; i < full.size(); ++i) full[i] = 0.25 * double(i) - 7;
    for (int y = 0; y < h; ++y) strips.setRow(y, &full[size_t(y) * w]);
    int kept = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool near = x < reachX || x >= w - reachX || y < reachY || y >= h - reachY;
            ASSERT_EQ(strips.keeps(x, y), near) << x << " " << y;
            if (!near) continue;
            ++kept;
            EXPECT_EQ(strips.at(x, y), full[size_t(y) * w + x]) << x << " " << y;
        }
    EXPECT_EQ(kept, w * h - (w - 2 * reachX) * (h - 2 * reachY));
    EXPECT_EQ(int(strips.columns().size()), 2 * reachX);
    strips.at(1, 1) = 99.5;  // in both strips
    const detail::StripField& view = strips;
    EXPECT_EQ(view.at(1, 1), 99.5);
    // A reach past the middle keeps everything.
    detail::StripField all(w, h, w, 0);
    for (int y = 0; y < h; ++y) all.setRow(y, &full[size_t(y) * w]);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) EXPECT_EQ(all.at(x, y), full[size_t(y) * w + x]);
}
