// A texture from pack with one header value damaged (issue 38): info and check refuse it as bad input
// (exit 3), in one line that names the file and the key, for every key of the family and every container;
// the same file undamaged reads.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/damaged_header.hpp"
#include "support/heightpack_process.hpp"

using namespace heightpack::test;

namespace {

// pack's outputs in each container, from a synth sequence's first frame (so they record a loop period).
void makeTextures(const ScratchDir& dir) {
    ASSERT_EQ(heightpackRun({"synth", "--wind", "10", "--tile-size", "64m", "--size", "32", "--frames", "2", "--loop", "12s",
                             "-o", dir.file("seq.exr"), "-q"}).code, 0);
    for (const char* ext : {".exr", ".ktx2", ".dds"}) {
        const ProcessResult r = heightpackRun({"pack", dir.file("seq.0000.exr"), "--scale", "0.25", "-o", dir.file(std::string("good") + ext), "-q"});
        ASSERT_EQ(r.code, 0) << r.err;
    }
}

}  // namespace

TEST(DamagedHeader, InfoAndCheckRefuseEachDamagedKeyNamingTheFileAndTheKey) {
    ScratchDir dir;
    makeTextures(dir);
    for (const char* ext : {".exr", ".ktx2", ".dds"}) {
        for (const char* command : {"info", "check"}) {
            const ProcessResult good = heightpackRun({command, dir.file(std::string("good") + ext)});
            EXPECT_TRUE(good.code == 0 || good.code == 1) << command << " " << ext << ": " << good.err;
        }
    }
    int cases = 0;
    for (const HeaderDamage& damage : headerDamages()) {
        SCOPED_TRACE(damage.name());
        const std::string path = damagedCopy(dir, damage, cases++);
        for (const char* command : {"info", "check"}) {
            SCOPED_TRACE(command);
            const ProcessResult r = heightpackRun({command, path});
            EXPECT_EQ(r.code, 3) << r.err << r.out;
            expectOneLineError(r, path);
            EXPECT_NE(r.err.find(damage.key), std::string::npos) << r.err;
        }
        const ProcessResult json = heightpackRun({"info", path, "--json"});
        EXPECT_EQ(json.code, 3) << json.out;
    }
    EXPECT_GE(cases, 30);
}
