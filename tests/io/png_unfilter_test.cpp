// PNG's row filters undone by the fast decoder's unfilter (libpack/io/png_unfilter.hpp) against the
// specification's definition (section 9), written out here byte by byte: groups of Paeth rows run side by
// side in vector lanes, other rows one by one, on any number of threads, and every result must be the
// definition's.
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <vector>

#include "png_unfilter.hpp"

using namespace heightpack;

namespace {

// The definition: Recon(x) = Filt(x) + predictor of a (left), b (up), c (up-left), bytes outside the
// image are 0; Paeth picks the one of a, b, c closest to a + b - c, ties to a, then b.
std::vector<unsigned char> definedUnfilter(const std::vector<unsigned char>& filtered, int height, size_t rowBytes, int bpp) {
    std::vector<unsigned char> out(size_t(height) * rowBytes);
    for (int y = 0; y < height; ++y) {
        const int type = filtered[size_t(y) * (rowBytes + 1)];
        for (size_t i = 0; i < rowBytes; ++i) {
            const int x = filtered[size_t(y) * (rowBytes + 1) + 1 + i];
            const int a = i >= size_t(bpp) ? out[size_t(y) * rowBytes + i - bpp] : 0;
            const int b = y > 0 ? out[size_t(y - 1) * rowBytes + i] : 0;
            const int c = y > 0 && i >= size_t(bpp) ? out[size_t(y - 1) * rowBytes + i - bpp] : 0;
            const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
            const int paeth = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
            const int predicted[5] = {0, a, b, (a + b) / 2, paeth};
            out[size_t(y) * rowBytes + i] = static_cast<unsigned char>(x + predicted[type]);
        }
    }
    return out;
}

}  // namespace

TEST(PngUnfilter, EqualsTheSpecificationsDefinitionForEveryFilterMixAndThreadCount) {
    std::mt19937 random(7);
    std::uniform_int_distribution<int> byte(0, 255), filter(0, 4);
    int cases = 0;
    for (int bpp : {1, 2, 4})
        for (int pixels : {1, 2, 3, 7, 9, 300, 2100})
            for (int height : {1, 2, 3, 5, 8, 9, 33})
                for (int pattern = 0; pattern < 4; ++pattern) {
                    // All Paeth; all Paeth but one row; a random mix; Paeth with smooth bytes (small filtered
                    // values, as a smooth map gives, where Paeth's ties are common).
                    const size_t rowBytes = size_t(pixels) * bpp;
                    std::vector<unsigned char> filtered(size_t(height) * (rowBytes + 1));
                    for (int y = 0; y < height; ++y) {
                        unsigned char* row = filtered.data() + size_t(y) * (rowBytes + 1);
                        row[0] = static_cast<unsigned char>(pattern == 2 ? filter(random) : pattern == 1 && y == height / 2 ? 1 : 4);
                        for (size_t i = 0; i < rowBytes; ++i)
                            row[1 + i] = static_cast<unsigned char>(pattern == 3 ? byte(random) % 3 : byte(random));
                    }
                    const std::vector<unsigned char> expected = definedUnfilter(filtered, height, rowBytes, bpp);
                    for (int threads : {1, 2, 3}) {
                        std::vector<unsigned char> rows = filtered;
                        ASSERT_TRUE(detail::unfilter(rows.data(), height, rowBytes, bpp, threads));
                        for (int y = 0; y < height; ++y)
                            for (size_t i = 0; i < rowBytes; ++i)
                                ASSERT_EQ(rows[size_t(y) * (rowBytes + 1) + 1 + i], expected[size_t(y) * rowBytes + i])
                                    << "bpp " << bpp << ", " << pixels << " x " << height << ", pattern " << pattern << ", "
                                    << threads << " threads, row " << y << " byte " << i;
                    }
                    ++cases;
                }
    EXPECT_EQ(cases, 3 * 7 * 7 * 4);
}

TEST(PngUnfilter, RefusesFilterTypesPastFourAndChangesNothing) {
    std::vector<unsigned char> rows = {4, 10, 20, 5, 30, 40, 1, 50, 60};
    const std::vector<unsigned char> before = rows;
    EXPECT_FALSE(detail::unfilter(rows.data(), 3, 2, 1, 2));
    EXPECT_EQ(rows, before);
}
