// info --engine (issue 25): a WARNING line, with a format the engine does load, for each engine named
// that will not load the file as stored; the verdicts in JSON; an unknown engine is a usage error. The
// verdicts themselves are tested per format in tests/bake/engine_support_test.cpp.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

TEST(InfoEngines, WarnsForEachEngineThatWillNotLoadTheFile) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT16);
    ASSERT_EQ(heightpackRun({"pack", dir.file("map.png"), "--layout", "plain", "--pixel-type", "uint16", "-q", "-o",
                             dir.file("plain16.ktx2")}).code, 0);
    const ProcessResult text = heightpackRun({"info", dir.file("plain16.ktx2"), "--engine", "three,godot", "--engine", "babylon"});
    ASSERT_EQ(text.code, 0) << text.err;
    EXPECT_NE(text.out.find("WARNING three: refuses"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("it loads KTX2 R half or float"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("WARNING godot: partial"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("WARNING babylon: refuses"), std::string::npos) << text.out;

    const ProcessResult json = heightpackRun({"info", dir.file("map.png"), "--engine", "unreal", "--json"});
    ASSERT_EQ(json.code, 0) << json.err;
    const auto j = nlohmann::json::parse(json.out);
    ASSERT_EQ(j["engines"].size(), 1u);
    EXPECT_EQ(j["engines"][0]["engine"], "unreal");
    EXPECT_EQ(j["engines"][0]["support"], "loads");  // a 16-bit grey PNG: imported as G16
    EXPECT_EQ(text.out.find("WARNING unreal"), std::string::npos);

    const ProcessResult bad = heightpackRun({"info", dir.file("map.png"), "--engine", "cryengine"});
    EXPECT_EQ(bad.code, 2);
    EXPECT_NE(bad.err.find("three,babylon,unreal,unity,godot"), std::string::npos) << bad.err;
}
