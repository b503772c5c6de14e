// What a new user meets first (issue 35): the flat tiled view in a window that is not square. Drawn with
// no display (EGL), read back.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "viewer_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// The smallest shift p (at least `from` pixels) at which the picture repeats along x (or y): the mean
// absolute difference between each lit pixel and the one p further on, over the pairs where both are lit,
// is at most `tolerance` grey levels. 0 when it never does.
int repeatPeriod(const Picture& p, bool alongX, int from, double tolerance) {
    const int length = alongX ? p.width : p.height;
    for (int shift = from; shift < length; ++shift) {
        double sum = 0.0;
        long pairs = 0;
        for (int y = 0; y + (alongX ? 0 : shift) < p.height; ++y)
            for (int x = 0; x + (alongX ? shift : 0) < p.width; ++x) {
                const int a = p.at(x, y), b = alongX ? p.at(x + shift, y) : p.at(x, y + shift);
                if (a == 0 || b == 0) continue;  // the black beside the tiles
                sum += std::abs(a - b);
                ++pairs;
            }
        if (pairs > 1000 && sum / pairs <= tolerance) return shift;
    }
    return 0;
}

// The columns (or rows) that hold any lit pixel: the width (or height) of the tiles' block.
int litExtent(const Picture& p, bool alongX) {
    int first = -1, last = -1;
    for (int i = 0; i < (alongX ? p.width : p.height); ++i) {
        bool lit = false;
        for (int j = 0; j < (alongX ? p.height : p.width) && !lit; ++j) lit = (alongX ? p.at(i, j) : p.at(j, i)) != 0;
        if (lit) last = i, first = first < 0 ? i : first;
    }
    return first < 0 ? 0 : last - first + 1;
}

}  // namespace

// Issue 35, item 9: --tiled NxM keeps each tile the map's shape, whatever the window's. The period at
// which the picture repeats, measured along x and y from its pixels, is one tile: equal for a square map
// in a wide window, twice as long across as down for a 2:1 map in a square one; the block is as large as
// the window allows.
TEST(ViewerTiled, TilesKeepTheMapsShapeInAWindowOfAnotherShape) {
    ScratchDir dir;
    // Noise repeats only at the tile's period (the map is a tile: periodic).
    writeImage(dir.file("square.png"), randomImage(64, 64, 3, 0.1f, 1.0f), OIIO::TypeDesc::UINT8);
    writeImage(dir.file("wide.png"), randomImage(64, 32, 4, 0.1f, 1.0f), OIIO::TypeDesc::UINT8);
    struct Case {
        std::string map, size;
        int tileX, tileY;  // pixels a tile spans: the 3 x 3 block fitted into the window with square texels
    };
    for (const Case& c : {Case{"square.png", "480x240", 80, 80}, Case{"wide.png", "300x300", 100, 50}}) {
        SCOPED_TRACE(c.map + " in " + c.size);
        const ViewRun run = viewWithoutDisplay({dir.file(c.map), "--tiled", "3x3", "--size", c.size, "--screenshot",
                                                dir.file("tiled.png")});
        ASSERT_EQ(run.code, 0) << run.err;
        const Picture p = readPicture(dir.file("tiled.png"));
        const int periodX = repeatPeriod(p, true, 8, 0.5), periodY = repeatPeriod(p, false, 8, 0.5);
        EXPECT_EQ(periodX, c.tileX);
        EXPECT_EQ(periodY, c.tileY);
        EXPECT_EQ(litExtent(p, true), 3 * c.tileX);
        EXPECT_EQ(litExtent(p, false), 3 * c.tileY);
        std::printf("%s in %s: repeats every %d x %d pixels, tiles over %d x %d\n", c.map.c_str(), c.size.c_str(), periodX,
                    periodY, litExtent(p, true), litExtent(p, false));
    }
}
