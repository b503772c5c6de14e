// The quilting (core/tile_quilt.hpp) against independent computations: its FFT search equals the brute-force
// sum of squared differences and finds a planted copy; its cut is the brute-force cheapest path; a crop of
// an exactly periodic cell pattern (a map no Gaussian field describes) comes out tiling and looking right;
// texels beyond the strips are the map's (exactly, or less a harmonic field); the same bytes on any number
// of threads; small and non-square maps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "heightpack/bake/check_job.hpp"
#include "heightpack/core/tile/look.hpp"
#include "heightpack/core/tile/quilt.hpp"
#include "heightpack/core/tile/tileable.hpp"

#include "tile/quilt_kernels.hpp"

using namespace heightpack;

namespace {

// A cell pattern that tiles exactly with period `period`: the distance to the second-nearest of `cells`
// random sites on the torus less the distance to the nearest (0 on the cell walls, rising to a peak inside
// each cell, with a sharp crease on every wall), each cell scaled by its own height.
Image periodicCells(int period, int cells, int width, int height, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> place(0, period), scale(0.5, 1.0);
    std::vector<double> sx(cells), sy(cells), sh(cells);
    for (int i = 0; i < cells; ++i) sx[i] = place(random), sy[i] = place(random), sh[i] = scale(random);
    Image map(width, height, 1);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double d1 = std::numeric_limits<double>::infinity(), d2 = d1;
            int nearest = 0;
            for (int i = 0; i < cells; ++i) {
                double dx = std::abs(x + 0.5 - sx[i]), dy = std::abs(y + 0.5 - sy[i]);
                dx = std::min(std::fmod(dx, period), period - std::fmod(dx, period));
                dy = std::min(std::fmod(dy, period), period - std::fmod(dy, period));
                const double d = std::hypot(dx, dy);
                if (d < d1) d2 = d1, d1 = d, nearest = i;
                else if (d < d2) d2 = d;
            }
            map.at(x, y) = static_cast<float>(sh[nearest] * (d2 - d1) / period);
        }
    return map;
}

detail::Field randomField(int w, int h, std::mt19937& random) {
    std::normal_distribution<double> normal;
    detail::Field f(w, h);
    for (double& x : f.v) x = normal(random);
    return f;
}

// Whether (x, y) lies in the strip of `band` texels centred on a wrap line (as tile/quilt.hpp places it).
bool inStrip(int i, int size, int band) {
    const int first = size - band / 2;
    return i >= first || i < band - band / 2;
}

TEST(QuiltSearch, MaskedSquaredErrorsEqualTheBruteForceSums) {
    std::mt19937 random(3);
    for (const auto& [w, h] : {std::pair{12, 10}, {7, 16}}) {
        const detail::Field target = randomField(w, h, random), source = randomField(w, h, random);
        detail::Field mask(w, h);
        for (size_t i = 0; i < mask.v.size(); ++i) mask.v[i] = (random() % 3 == 0) ? 1.0 : 0.0;
        const detail::Field errors = detail::maskedSquaredErrors(target, mask, source, 2);
        for (int dy = 0; dy < h; ++dy)
            for (int dx = 0; dx < w; ++dx) {
                double expected = 0;
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x) {
                        const double d = target.at(x, y) - source.at((x + dx) % w, (y + dy) % h);
                        expected += mask.at(x, y) * d * d;
                    }
                EXPECT_NEAR(errors.at(dx, dy), expected, 1e-9 * std::max(1.0, expected)) << dx << "," << dy;
            }
    }
}

TEST(QuiltSearch, FindsACopyPlantedAtAKnownShift) {
    // Two overlap columns beside a wrap line, as the left/right strip has them; their content planted
    // again (with the column between) at a known shift: that shift alone matches with error 0.
    std::mt19937 random(5);
    const int w = 64, h = 48, dx0 = 23, dy0 = 0;
    detail::Field map = randomField(w, h, random), target(w, h), mask(w, h);
    for (int y = 0; y < h; ++y)
        for (int x : {w - 3, w - 2, 1, 2}) {
            target.at(x, y) = map.at(x, y);
            mask.at(x, y) = 1.0;
            map.at((x + dx0) % w, (y + dy0) % h) = map.at(x, y);
        }
    const detail::Field errors = detail::maskedSquaredErrors(target, mask, map, 1);
    const size_t best = size_t(std::min_element(errors.v.begin(), errors.v.end()) - errors.v.begin());
    EXPECT_EQ(int(best % w), dx0);
    EXPECT_EQ(int(best / w), dy0);
    EXPECT_NEAR(errors.v[best], 0.0, 1e-9);
}

TEST(QuiltCut, IsTheCheapestPathOfTheBruteForce) {
    std::mt19937 random(11);
    std::uniform_real_distribution<double> uniform(0, 1);
    for (int width = 1; width <= 4; ++width)
        for (int length = 1; length <= 6; ++length)
            for (int trial = 0; trial < 5; ++trial) {
                std::vector<double> cost(size_t(width) * length);
                for (double& c : cost) c = uniform(random);
                const std::vector<int> path = detail::minimalCut(cost, width, length);
                ASSERT_EQ(int(path.size()), length);
                double total = 0;
                for (int line = 0; line < length; ++line) {
                    ASSERT_TRUE(path[line] >= 0 && path[line] < width);
                    if (line > 0) {
                        ASSERT_LE(std::abs(path[line] - path[line - 1]), 1);
                    }
                    total += cost[size_t(line) * width + path[line]];
                }
                // Every path, by recursion over the lines.
                double best = std::numeric_limits<double>::infinity();
                std::function<void(int, int, double)> walk = [&](int line, int place, double sum) {
                    sum += cost[size_t(line) * width + place];
                    if (line == length - 1) return void(best = std::min(best, sum));
                    for (int next : {place - 1, place, place + 1}) {
                        if (next >= 0 && next < width) walk(line + 1, next, sum);
                    }
                };
                for (int start = 0; start < width; ++start) {
                    walk(0, start, 0.0);
                }
                EXPECT_NEAR(total, best, 1e-12) << width << "x" << length;
            }
}

TEST(Quilt, ACropOfPeriodicCellsTilesAndLooksRight) {
    // 160x128 of a pattern of period 192: both wrap lines cut cells apart.
    const Image crop = periodicCells(192, 60, 160, 128, 1);
    ASSERT_FALSE(levelTiles(measureSeams(crop)));
    const QuiltResult r = quiltTile(crop);
    ASSERT_EQ(r.map.width, 160);
    ASSERT_EQ(r.map.height, 128);
    EXPECT_TRUE(measureSeamChain(r.map, MipOptions{}, kDefaultSeamThreshold, SeamOptions{}).tiles());
    const TileLook look = measureTileLook(r.map, {&crop, 0, std::nullopt});
    EXPECT_TRUE(look.passes()) << look.frame << " " << look.blobs << " " << look.echo;
    // No line at a strip's border either: the step across each border column is like the steps beside it.
    auto step = [&](int x) {
        double sum = 0;
        for (int y = 0; y < r.map.height; ++y) sum += std::abs(r.map.at((x + 1) % 160, y) - r.map.at(x, y));
        return sum;
    };
    const int border = 160 - r.bandX / 2 - 1;  // the last column before the strip
    EXPECT_LT(step(border), 2 * std::max(step(border - 2), step(border + 2))) << step(border);
}

TEST(Quilt, BeyondTheStripsTheMapChangesByAHarmonicFieldAlone) {
    // Moisan's smooth field of the large scales and the healing's correction: both have their Laplacian on
    // the strips (the map's edges, the cut paths), so beyond them the change is harmonic, and not zero.
    const Image crop = periodicCells(160, 40, 120, 100, 2);
    const auto [lo, hi] = std::minmax_element(crop.pixels.begin(), crop.pixels.end());
    const double range = *hi - *lo;
    // Texels the easing into range may touch: within 2% of the range of an extreme.
    auto middle = [&](float v) { return v > *lo + 0.02 * range && v < *hi - 0.02 * range; };
    const QuiltResult r = quiltTile(crop);
    ASSERT_GT(r.bandX, 0);
    auto beyond = [&](int x, int y) { return !inStrip(x, crop.width, r.bandX) && !inStrip(y, crop.height, r.bandY); };
    auto change = [&](int x, int y) { return double(r.map.at(x, y)) - crop.at(x, y); };
    double largest = 0, worstLaplacian = 0;
    int judged = 0;
    for (int y = 1; y < crop.height - 1; ++y)
        for (int x = 1; x < crop.width - 1; ++x) {
            bool all = true;
            for (const auto& [px, py] : {std::pair{x, y}, {x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}})
                all = all && beyond(px, py) && middle(crop.at(px, py)) && middle(r.map.at(px, py));
            if (!all) continue;
            ++judged;
            largest = std::max(largest, std::abs(change(x, y)));
            const double laplacian = change(x - 1, y) + change(x + 1, y) + change(x, y - 1) + change(x, y + 1) - 4 * change(x, y);
            worstLaplacian = std::max(worstLaplacian, std::abs(laplacian));
        }
    EXPECT_GT(judged, crop.width * crop.height / 2);
    EXPECT_GT(largest, 1e-3 * range);
    EXPECT_LT(worstLaplacian, 1e-5 * range);
    // While in the strips the map was replaced: a large change somewhere on the wrap lines.
    double onWrap = 0;
    for (int y = 0; y < crop.height; ++y) onWrap = std::max(onWrap, std::abs(change(0, y)));
    EXPECT_GT(onWrap, 0.05 * range);
}

TEST(Quilt, TheSameBytesOnAnyNumberOfThreadsAndAnotherMatchGivesOthers) {
    const Image crop = periodicCells(128, 30, 96, 80, 3);
    QuiltOptions one, two, next;
    one.threads = 1;
    two.threads = 2;
    next.match = 1;
    const QuiltResult a = quiltTile(crop, one), b = quiltTile(crop, two), c = quiltTile(crop, next);
    EXPECT_EQ(a.map.pixels, b.map.pixels);
    EXPECT_TRUE(a.sourceX[0] != c.sourceX[0] || a.sourceX[1] != c.sourceX[1]);
    EXPECT_NE(a.map.pixels, c.map.pixels);
}

TEST(Quilt, SmallAndNonSquareMapsKeepTheirSizeAndTile) {
    for (const auto& [w, h] : {std::pair{16, 16}, {16, 40}, {72, 24}, {33, 17}}) {
        const Image crop = periodicCells(96, 25, w, h, 4);
        const QuiltResult r = quiltTile(crop);
        ASSERT_EQ(r.map.width, w);
        ASSERT_EQ(r.map.height, h);
        EXPECT_EQ(r.bandX, std::max(8, int(std::lround(w / 8.0))));
        EXPECT_TRUE(std::all_of(r.map.pixels.begin(), r.map.pixels.end(), [](float v) { return std::isfinite(v); }));
        // The wrap steps are like the steps inside: at most the largest step inside.
        double inside = 0, wrap = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double step = std::abs(r.map.at((x + 1) % w, y) - r.map.at(x, y));
                (x == w - 1 ? wrap : inside) = std::max(x == w - 1 ? wrap : inside, step);
            }
        EXPECT_LE(wrap, inside) << w << "x" << h;
    }
    // Below 16 texels: Moisan's periodic component.
    const Image tiny = periodicCells(32, 4, 12, 12, 5);
    EXPECT_EQ(quiltTile(tiny).map.pixels, periodicComponent(tiny, PeriodicContinuity::Heights).pixels);
}

}  // namespace
