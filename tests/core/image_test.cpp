#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>

#include "heightpack/core/image.hpp"

using namespace heightpack;

TEST(Image, WrapIndexPeriodicTakesEveryIntegerOntoTheTile) {
    EXPECT_EQ(wrapIndex(-1, 4, Wrap::Periodic), 3);
    EXPECT_EQ(wrapIndex(-4, 4, Wrap::Periodic), 0);
    EXPECT_EQ(wrapIndex(-5, 4, Wrap::Periodic), 3);
    EXPECT_EQ(wrapIndex(4, 4, Wrap::Periodic), 0);
    EXPECT_EQ(wrapIndex(9, 4, Wrap::Periodic), 1);
    EXPECT_EQ(wrapIndex(0, 1, Wrap::Periodic), 0);
    EXPECT_EQ(wrapIndex(-7, 1, Wrap::Periodic), 0);
}

TEST(Image, WrapIndexClampRepeatsTheEdge) {
    EXPECT_EQ(wrapIndex(-1, 4, Wrap::Clamp), 0);
    EXPECT_EQ(wrapIndex(-100, 4, Wrap::Clamp), 0);
    EXPECT_EQ(wrapIndex(3, 4, Wrap::Clamp), 3);
    EXPECT_EQ(wrapIndex(4, 4, Wrap::Clamp), 3);
}

TEST(Image, InterleavesChannelsRowMajor) {
    Image image(3, 2, 2);
    image.at(2, 1, 1) = 5.0f;
    EXPECT_EQ(image.pixels[(1 * 3 + 2) * 2 + 1], 5.0f);
    EXPECT_EQ(image.row(1)[2 * 2 + 1], 5.0f);
    EXPECT_EQ(image.wrapped(-1, 3, Wrap::Periodic, 1), 5.0f);
    EXPECT_EQ(image.wrapped(7, 9, Wrap::Clamp, 1), 5.0f);
}

TEST(Image, SampleRangeIsTheLeastAndGreatestSampleOnAnyThreadCount) {
    // Against std::minmax_element, on images whose extremes sit anywhere (first, last, one chunk's middle),
    // with negatives, one channel and four, and sizes below and above the chunk count.
    std::mt19937 random(3);
    for (const auto& [w, h, c] : {std::tuple{1, 1, 1}, {7, 3, 1}, {64, 33, 4}, {257, 129, 1}}) {
        Image image(w, h, c);
        std::uniform_real_distribution<float> u(-3.0f, 2.0f);
        for (float& v : image.pixels) v = u(random);
        for (size_t at : {size_t(0), image.pixels.size() - 1, image.pixels.size() / 3}) {
            Image probe = image;
            probe.pixels[at] = 9.0f;
            probe.pixels[(at + 1) % probe.pixels.size()] = -9.0f;
            const auto [low, high] = std::minmax_element(probe.pixels.begin(), probe.pixels.end());
            for (int threads : {1, 2, 5}) {
                const SampleRange r = sampleRange(probe, threads);
                EXPECT_EQ(r.low, *low) << w << "x" << h << "x" << c << " at " << at << " on " << threads;
                EXPECT_EQ(r.high, *high) << w << "x" << h << "x" << c << " at " << at << " on " << threads;
            }
        }
    }
}
