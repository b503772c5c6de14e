// material.json and manifests for choppy maps (issue 15): a texture holding Dx, Dy says so with its
// choppiness; every material.json written before (no such fields) reads as it did and keeps its bytes.
#include <gtest/gtest.h>

#include <fstream>
#include <optional>
#include <string>

#include "heightpack/bake/manifest.hpp"
#include "heightpack/bake/material.hpp"

#include "support/test_support.hpp"

namespace heightpack {
namespace {

MaterialDescription twoLayers() {
    MaterialDescription d;
    d.name = "sea";
    d.generator = "heightpack 9.8.7";
    d.manifest = "sea.toml";
    DisplacementLayer a;
    a.name = "swell";
    a.texture = {"swell.exr", 64, 64, 7, 1, std::nullopt};
    d.displacement.push_back(a);
    a.name = "chop";
    a.shift = true;
    a.choppiness = 0.7;  // not exactly representable: must read back to the same double
    d.displacement.push_back(a);
    return d;
}

Result<MaterialDescription> readBack(const test::ScratchDir& dir, const std::string& text) {
    std::ofstream(dir.file("material.json"), std::ios::binary) << text;
    return readMaterial(dir.file("material.json"));
}

TEST(ChoppyMaterial, RecordsShiftAndChoppinessOnlyWhereTheTextureHoldsThem) {
    test::ScratchDir dir;
    const std::string json = materialJson(twoLayers());
    const size_t chop = json.find("\"chop\"");
    ASSERT_NE(chop, std::string::npos);
    // The heights-only layer is written as it always was; the choppy one after its amplitude.
    EXPECT_EQ(json.find("\"shift\""), json.find("\"shift\": true"));
    EXPECT_GT(json.find("\"shift\""), chop);
    EXPECT_EQ(json.find("horizontalDisplacement"), std::string::npos);
    EXPECT_GT(json.find("\"choppiness\": 0.7"), chop);
    auto back = readBack(dir, json);
    ASSERT_TRUE(back) << back.error().what;
    EXPECT_FALSE(back->displacement[0].shift);
    EXPECT_TRUE(back->displacement[1].shift);
    EXPECT_EQ(back->displacement[1].choppiness, 0.7);
    EXPECT_EQ(materialJson(*back), json);
    // A wrong type is a damaged file, named.
    std::string bad = json;
    bad.replace(bad.find("\"shift\": true"), 13, "\"shift\": 1.0");
    auto refused = readBack(dir, bad);
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().what.find("shift"), std::string::npos) << refused.error().what;
}

// A material.json as heightpack wrote it before the sideways motion was called shift (typed out here, not
// made by materialJson): its horizontalDisplacement still reads as shift, and a wrong type is still named.
TEST(ChoppyMaterial, ReadsTheOldWordForShift) {
    test::ScratchDir dir;
    const auto written = [](const std::string& chopFlag) {
        return std::string(R"({"schema":"heightpack-material","version":1,"name":"sea","displacement":[)"
                           R"({"name":"swell","texture":{"file":"swell.exr","width":64,"height":64,"levels":7},)"
                           R"("layout":"neighbour4","wrap":"periodic","filter":"kaiser","heightScale":1.0,)"
                           R"("heightOffset":0.0,"tileSize":64.0,"scroll":[0.0,0.0],"amplitude":1.0},)"
                           R"({"name":"chop","texture":{"file":"chop.exr","width":64,"height":64,"levels":7},)"
                           R"("layout":"neighbour4","wrap":"periodic","filter":"kaiser","heightScale":1.0,)"
                           R"("heightOffset":0.0,"tileSize":16.0,"scroll":[0.0,0.0],"amplitude":1.0,)"
                           R"("horizontalDisplacement":)") +
               chopFlag + R"(,"choppiness":0.7}]})";
    };
    for (const char* flag : {"true", "false"}) {
        auto old = readBack(dir, written(flag));
        ASSERT_TRUE(old) << old.error().what;
        ASSERT_EQ(old->displacement.size(), 2u);
        EXPECT_FALSE(old->displacement[0].shift);
        EXPECT_EQ(old->displacement[1].shift, std::string(flag) == "true") << flag;
        EXPECT_EQ(old->displacement[1].choppiness, 0.7);
    }
    auto refused = readBack(dir, written("1.0"));
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().what.find("horizontalDisplacement"), std::string::npos) << refused.error().what;
}

TEST(ChoppyMaterial, ManifestChoppinessDefaultsToOneAndStaysInRange) {
    test::ScratchDir dir;
    std::ofstream(dir.file("map.png"), std::ios::binary) << "not read while parsing";
    auto manifest = [&](const std::string& extra) {
        std::ofstream(dir.file("m.toml")) << "format = 1\nname = \"m\"\n[[displacement]]\nname = \"a\"\n"
                                             "source = \"map.png\"\ntile_size = 8.0\n"
                                          << extra;
        return parseManifest(dir.file("m.toml"));
    };
    auto plain = manifest("");
    ASSERT_TRUE(plain) << plain.error().what;
    EXPECT_EQ(plain->displacement[0].layer.choppiness, 1.0);
    auto set = manifest("choppiness = 0.25\n");
    ASSERT_TRUE(set) << set.error().what;
    EXPECT_EQ(set->displacement[0].layer.choppiness, 0.25);
    for (const char* wrong : {"choppiness = -1\n", "choppiness = 11\n", "choppiness = \"much\"\n"}) {
        auto refused = manifest(wrong);
        ASSERT_FALSE(refused) << wrong;
        EXPECT_NE(refused.error().what.find("choppiness"), std::string::npos) << refused.error().what;
        EXPECT_NE(refused.error().path.find("m.toml:7"), std::string::npos) << refused.error().path;
    }
}

}  // namespace
}  // namespace heightpack
