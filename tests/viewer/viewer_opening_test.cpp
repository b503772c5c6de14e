// What a new user meets first (issue 35): opening the folder `heightpack build` wrote, naming a screenshot,
// and the flat tiled view in a window that is not square. Drawn with no display (EGL), read back.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "viewer_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

void expectOneErrorLine(const ViewRun& run, const std::string& start) {
    EXPECT_EQ(run.err.rfind("heightpack-view: error: " + start, 0), 0u) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
}

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

// `heightpack-view out/ocean`, the folder heightpack build wrote: it opens the folder's material.json and
// says so, drawing exactly what naming the material.json draws. A folder without one is bad input that
// says what the viewer looked for; a built folder among other maps is a usage error.
TEST(ViewerOpening, ABuiltFolderOpensItsMaterial) {
    ScratchDir dir;
    std::ofstream(dir.file("m.toml")) << "format = 1\nname = \"m\"\n[[displacement]]\nname = \"swell\"\nsource = \""
                                      << kExamples << "swell.png\"\ntile_size = 40.0\namplitude = 2.0\n";
    const ProcessResult built = runProcess({HEIGHTPACK_EXE, "build", dir.file("m.toml"), "-q", "-o", dir.file("out")});
    ASSERT_EQ(built.code, 0) << built.err;
    const std::vector<std::string> common = {"--size", "96x64", "--time", "1", "--camera", "0,0,6,20,-15"};
    auto viaFolder = common, viaFile = common;
    viaFolder.insert(viaFolder.begin(), dir.file("out"));
    viaFolder.insert(viaFolder.end(), {"--screenshot", dir.file("folder.png")});
    viaFile.insert(viaFile.begin(), dir.file("out/material.json"));
    viaFile.insert(viaFile.end(), {"--screenshot", dir.file("file.png")});
    const ViewRun folder = viewWithoutDisplay(viaFolder), file = viewWithoutDisplay(viaFile);
    ASSERT_EQ(folder.code, 0) << folder.err;
    ASSERT_EQ(file.code, 0) << file.err;
    EXPECT_NE(folder.err.find("heightpack-view: note: " + dir.file("out") + " is a folder; opening its " +
                              dir.file("out/material.json")),
              std::string::npos)
        << folder.err;
    EXPECT_EQ(readBytes(dir.file("folder.png")), readBytes(dir.file("file.png")));

    std::filesystem::create_directory(dir.file("empty"));
    const ViewRun empty = viewWithoutDisplay({dir.file("empty"), "--screenshot", dir.file("empty.png")});
    EXPECT_EQ(empty.code, 3) << empty.err;
    expectOneErrorLine(empty, dir.file("empty") + ": is a folder, not a map, and holds no material.json");
    const ViewRun mixed = viewWithoutDisplay({dir.file("out"), kExamples + "swell.png", "--screenshot", dir.file("mixed.png")});
    EXPECT_EQ(mixed.code, 2) << mixed.err;
    expectOneErrorLine(mixed, dir.file("out") + " is a built material's folder");
    EXPECT_FALSE(std::filesystem::exists(dir.file("empty.png")) || std::filesystem::exists(dir.file("mixed.png")));
}

// A screenshot's name must be one of the formats --help lists; each listed format writes the picture
// (the same pixels as the PNG), and any other is a usage error (2) before anything is drawn, one line
// naming the formats.
TEST(ViewerScreenshot, HelpListsTheFormatsThatAreWrittenAndOthersAreAUsageError) {
    ScratchDir dir;
    const ViewRun help = viewWithoutDisplay({"--help"});
    ASSERT_EQ(help.code, 0);
    EXPECT_NE(help.out.find(".png, .tif, .tiff or .exr"), std::string::npos) << help.out;
    const std::vector<std::string> common = {kExamples + "swell.png", "--size", "48x32", "--view", "height",
                                             "--camera", "0,0,30,0,-60", "--screenshot"};
    auto args = common;
    args.push_back(dir.file("shot.png"));
    ASSERT_EQ(viewWithoutDisplay(args).code, 0);
    const Picture png = readPicture(dir.file("shot.png"));
    for (const std::string ext : {".tif", ".tiff", ".exr"}) {
        args = common;
        args.push_back(dir.file("shot" + ext));
        const ViewRun run = viewWithoutDisplay(args);
        ASSERT_EQ(run.code, 0) << ext << ": " << run.err;
        // 8 bits a channel; an EXR holds them as half, which keeps every 8-bit level within half a level.
        const Difference d = compare(png, readPicture(dir.file("shot" + ext)), 0);
        EXPECT_EQ(d.max, 0) << ext;
    }
    for (const std::string name : {"shot.jpg", "shot.webp", "shot"}) {
        args = common;
        args.push_back(dir.file(name));
        const ViewRun run = viewWithoutDisplay(args);
        EXPECT_EQ(run.code, 2) << name << ": " << run.err;
        expectOneErrorLine(run, dir.file(name) + ": is no screenshot format: the viewer writes .png, .tif, .tiff or .exr");
        EXPECT_FALSE(std::filesystem::exists(dir.file(name)));
    }
}

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
