// heightpack-view given a texture from pack with one header value damaged (issue 38): bad input, exit 3,
// one line naming the file and the key, and nothing drawn; the undamaged file draws.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "support/damaged_header.hpp"
#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"
#include "viewer_support.hpp"

using namespace heightpack::test;

TEST(ViewerDamagedHeader, RefusesEachDamagedKeyNamingTheFileAndTheKeyAndDrawsNothing) {
    ScratchDir dir;
    ASSERT_EQ(heightpackRun({"synth", "--wind", "10", "--tile-size", "64m", "--size", "32", "--frames", "2", "--loop", "12s",
                             "-o", dir.file("seq.exr"), "-q"}).code, 0);
    for (const char* ext : {".exr", ".ktx2", ".dds"})
        ASSERT_EQ(heightpackRun({"pack", dir.file("seq.0000.exr"), "--scale", "0.25", "-o", dir.file(std::string("good") + ext), "-q"}).code, 0);
    const ViewRun good = viewWithoutDisplay({dir.file("good.ktx2"), "--screenshot", dir.file("good.png")});
    ASSERT_EQ(good.code, 0) << good.err;
    ASSERT_TRUE(std::filesystem::exists(dir.file("good.png")));
    int cases = 0;
    for (const HeaderDamage& damage : headerDamages()) {
        SCOPED_TRACE(damage.name());
        const std::string path = damagedCopy(dir, damage, cases++);
        const std::string shot = dir.file("shot" + std::to_string(cases) + ".png");
        const ViewRun r = viewWithoutDisplay({path, "--screenshot", shot});
        EXPECT_EQ(r.code, 3) << r.err;
        EXPECT_EQ(r.err.rfind("heightpack-view: error: " + path, 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_NE(r.err.find(damage.key), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(shot));
    }
}

// A block stream cut short (issue 39): BC4 heights in KTX2 and DDS whose last level ends mid-block are bad
// input, one line naming the file, and nothing drawn.
TEST(ViewerDamagedHeader, RefusesABlockStreamCutShortAndDrawsNothing) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(64, 64, smoothWave), OIIO::TypeDesc::UINT16);
    for (const char* ext : {".ktx2", ".dds"}) {
        SCOPED_TRACE(ext);
        const std::string whole = dir.file(std::string("bc4") + ext), cut = dir.file(std::string("cut") + ext);
        ASSERT_EQ(heightpackRun({"pack", dir.file("map.png"), "--layout", "plain", "--pixel-type", "bc4", "-o", whole, "-q"}).code, 0);
        std::vector<unsigned char> bytes = readBytes(whole);
        bytes.resize(bytes.size() - 13);
        writeBytes(cut, bytes);
        const std::string shot = dir.file(std::string("shot") + ext + ".png");
        const ViewRun r = viewWithoutDisplay({cut, "--screenshot", shot});
        EXPECT_EQ(r.code, 3) << r.err;
        EXPECT_EQ(r.err.rfind("heightpack-view: error: " + cut, 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_FALSE(std::filesystem::exists(shot));
    }
}
