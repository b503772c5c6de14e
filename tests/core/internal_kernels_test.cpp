// The core floor's internal kernels against independent computations: the threaded 2-D DFTs
// (libpack/core/dft.hpp) against OpenCV's own single-threaded cv::dft, and the radix sort behind the rank
// Gaussianisation (libpack/core/gaussianise.hpp) against std::stable_sort.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

#include "dft.hpp"
#include "gaussianise.hpp"

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

TEST(StableOrder, EqualsStdStableSortWithTiesNegativesAndSignedZeros) {
    std::mt19937 random(11);
    for (int trial = 0; trial < 40; ++trial) {
        // Some longer than the sort's 64 chunks x 2048 buckets, so chunks hold many items of a bucket.
        const size_t n = 1 + random() % (trial % 8 == 7 ? 300000 : 5000);
        std::vector<float> values(n);
        // Few distinct levels (ties), both signs, both zeros, tiny and huge magnitudes.
        const float levels[] = {-0.0f, 0.0f, -1.5f, 2.0f, 1e-30f, -1e-30f, 3e38f, -3e38f, 0.25f};
        for (float& v : values)
            v = trial % 2 ? levels[random() % 9] : std::uniform_real_distribution<float>(-4.0f, 4.0f)(random);
        std::vector<uint32_t> expected(n);
        std::iota(expected.begin(), expected.end(), 0u);
        std::stable_sort(expected.begin(), expected.end(), [&](uint32_t a, uint32_t b) { return values[a] < values[b]; });
        EXPECT_EQ(detail::stableOrder(values, 1), expected) << trial;
        EXPECT_EQ(detail::stableOrder(values, 3), expected) << trial;
    }
}
