#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "heightpack/core/mip.hpp"
#include "heightpack/core/pack.hpp"

#include "support/test_support.hpp"

using namespace heightpack;
using heightpack::test::randomImage;
using heightpack::test::referenceBilinear;
using heightpack::test::referenceWrap;

TEST(Pack, TwoByTwoExample) {
    Image h(2, 2);
    h.pixels = {1, 2,
                3, 4};
    const Image p = packNeighbour4(h, Wrap::Periodic);
    auto texel = [&](const Image& img, int x, int y) {
        return std::vector<float>{img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2), img.at(x, y, 3)};
    };
    EXPECT_EQ(texel(p, 0, 0), (std::vector<float>{1, 2, 3, 4}));
    EXPECT_EQ(texel(p, 1, 0), (std::vector<float>{2, 1, 4, 3}));
    EXPECT_EQ(texel(p, 0, 1), (std::vector<float>{3, 4, 1, 2}));
    EXPECT_EQ(texel(p, 1, 1), (std::vector<float>{4, 3, 2, 1}));
    const Image c = packNeighbour4(h, Wrap::Clamp);
    EXPECT_EQ(texel(c, 1, 0), (std::vector<float>{2, 2, 4, 4}));
    EXPECT_EQ(texel(c, 1, 1), (std::vector<float>{4, 4, 4, 4}));
}

TEST(Pack, ChannelsAreTheLevelShiftedByOneTexel) {
    const Image h = randomImage(64, 16, 11);
    for (bool periodic : {true, false}) {
        const Image p = packNeighbour4(h, periodic ? Wrap::Periodic : Wrap::Clamp);
        ASSERT_EQ(p.channels, 4);
        for (int y = 0; y < h.height; ++y) {
            for (int x = 0; x < h.width; ++x) {
                const int x1 = referenceWrap(x + 1, h.width, periodic), y1 = referenceWrap(y + 1, h.height, periodic);
                ASSERT_EQ(p.at(x, y, 0), h.at(x, y));
                ASSERT_EQ(p.at(x, y, 1), h.at(x1, y)) << x << "," << y;
                ASSERT_EQ(p.at(x, y, 2), h.at(x, y1)) << x << "," << y;
                ASSERT_EQ(p.at(x, y, 3), h.at(x1, y1)) << x << "," << y;
            }
        }
    }
}

TEST(Pack, ARunOfOneChannelIsThatChannelOfThePackedRow) {
    // Every run a writer can ask for (any start, any length, runs that end on the right edge) of every
    // channel of every row, both wraps, against the packed image: the same values, and nothing written past
    // the run.
    const Image h = randomImage(16, 8, 5);
    for (Wrap wrap : {Wrap::Periodic, Wrap::Clamp}) {
        const Image p = packNeighbour4(h, wrap);
        for (int y = 0; y < h.height; ++y)
            for (int channel = 0; channel < 4; ++channel)
                for (int x0 = 0; x0 < h.width; ++x0)
                    for (int count = 0; x0 + count <= h.width; ++count) {
                        std::vector<float> run(size_t(count) + 1, -7.0f);
                        packNeighbour4Run(h, wrap, y, x0, count, channel, run.data());
                        for (int i = 0; i < count; ++i)
                            ASSERT_EQ(run[i], p.at(x0 + i, y, channel)) << channel << " " << x0 << "+" << i << "," << y;
                        ASSERT_EQ(run[count], -7.0f);
                    }
    }
}

namespace {

// 10,000 coordinates: random ones inside and far outside [0,1], exact texel centres, exact texel edges,
// and the corners of the tile.
std::vector<std::pair<double, double>> testCoordinates(int width, int height, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> wide(-3.0, 4.0);
    std::uniform_int_distribution<int> ix(-width, 2 * width), iy(-height, 2 * height);
    std::vector<std::pair<double, double>> uv = {{0, 0}, {1, 1}, {0, 1}, {1, 0}, {-1, -1}, {2, 2}};
    while (uv.size() < 10000) {
        switch (uv.size() % 3) {
            case 0: uv.emplace_back(wide(rng), wide(rng)); break;
            case 1: uv.emplace_back((ix(rng) + 0.5) / width, (iy(rng) + 0.5) / height); break;
            default: uv.emplace_back(double(ix(rng)) / width, double(iy(rng)) / height); break;
        }
    }
    return uv;
}

}  // namespace

TEST(Pack, PackedBilinearEqualsBilinearOfThePlainLevelEverywhere) {
    const Image h = randomImage(64, 32, 5);
    for (bool periodic : {true, false}) {
        const Wrap wrap = periodic ? Wrap::Periodic : Wrap::Clamp;
        MipOptions o;
        o.wrap = wrap;
        const auto chain = generateMipChain(h, o);
        const auto packed = packMipChain(chain, wrap);
        for (size_t level = 0; level < chain.size(); ++level) {
            for (const auto& [u, v] : testCoordinates(chain[level].width, chain[level].height, 100 + level)) {
                const double expected = referenceBilinear(chain[level], u, v, periodic);
                ASSERT_NEAR(samplePackedBilinear(packed[level], u, v, wrap), expected, 1e-6)
                    << wrapName(wrap) << " level " << level << " uv " << u << "," << v;
            }
        }
    }
}

TEST(Pack, TrilinearBlendsAdjacentLevelsOnlyInsideTheBand) {
    const Image h = randomImage(32, 32, 9);
    const auto chain = generateMipChain(h, Filter::Kaiser);
    const auto packed = packMipChain(chain, Wrap::Periodic);
    const TrilinearBands bands;  // 0.3 / 0.7, Listing 18-3
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> uv(-1.0, 2.0), lod(-0.5, 6.0);
    for (int k = 0; k < 10000; ++k) {
        const double u = uv(rng), v = uv(rng), l = lod(rng);
        const double clamped = std::clamp(l, 0.0, double(chain.size() - 1));
        const int level = std::min(int(clamped), int(chain.size()) - 1);
        const double fr = clamped - level;
        const double fine = referenceBilinear(chain[level], u, v, true);
        double expected = fine;
        if (level + 1 < int(chain.size()) && fr >= 0.3) {
            const double coarse = referenceBilinear(chain[level + 1], u, v, true);
            const double t = std::min(1.0, (fr - 0.3) / 0.4);
            expected = fine + (coarse - fine) * t;
        }
        ASSERT_NEAR(samplePackedTrilinear(packed, u, v, l, Wrap::Periodic, bands), expected, 1e-6)
            << "uv " << u << "," << v << " lod " << l;
    }
}

TEST(Pack, TrilinearIsContinuousAcrossTheSnappedBands) {
    const auto packed = packMipChain(generateMipChain(randomImage(32, 32, 13), Filter::Kaiser), Wrap::Periodic);
    const TrilinearBands bands{0.25, 0.8};
    for (double edge : {1.25, 1.8, 2.25, 2.8}) {
        const float below = samplePackedTrilinear(packed, 0.37, 0.61, edge - 1e-7, Wrap::Periodic, bands);
        const float above = samplePackedTrilinear(packed, 0.37, 0.61, edge + 1e-7, Wrap::Periodic, bands);
        EXPECT_NEAR(below, above, 1e-5) << "lod " << edge;
    }
    // Outside the band only one level counts: the result equals that level's bilinear exactly.
    EXPECT_EQ(samplePackedTrilinear(packed, 0.37, 0.61, 2.1, Wrap::Periodic, bands),
              samplePackedBilinear(packed[2], 0.37, 0.61, Wrap::Periodic));
    EXPECT_EQ(samplePackedTrilinear(packed, 0.37, 0.61, 2.9, Wrap::Periodic, bands),
              samplePackedBilinear(packed[3], 0.37, 0.61, Wrap::Periodic));
}
