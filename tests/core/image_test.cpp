#include <gtest/gtest.h>

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
