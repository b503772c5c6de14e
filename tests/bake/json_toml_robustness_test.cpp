// material.json and manifests that are damaged in every way fuzzing found (and their neighbours): a
// value of another type, a number out of range, odd TOML. Each must be a BadInput naming the file,
// never an exception, an assert or undefined behaviour (the sanitizer build checks the last).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "heightpack/bake/manifest.hpp"
#include "heightpack/bake/material.hpp"

#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// A material.json as heightpack build writes it, with every optional part.
const char* kMaterial = R"({
  "schema": "heightpack-material", "version": 1, "name": "ocean", "generator": "heightpack 0.1.0",
  "manifest": "ocean.toml",
  "displacement": [{
    "name": "swell", "texture": {"file": "swell.exr", "width": 512, "height": 512, "levels": 10, "frames": 4},
    "layout": "neighbour4", "wrap": "periodic", "filter": "kaiser", "heightScale": 1.0, "heightOffset": 0.0,
    "tileSize": 64.0, "scroll": [0.01, 0.004], "amplitude": 1.5, "loopPeriod": 8.0}],
  "normals": {"name": "ripple_n", "texture": {"file": "ripple_n.exr", "width": 256, "height": 256, "levels": 9},
    "convention": "opengl", "alpha": "none", "tileSize": 8.0, "heightRange": 0.05,
    "octaves": [{"tileSize": 8.0, "scroll": [0.02, 0.01], "strength": 1.0}]},
  "fresnel": {"name": "fresnel", "texture": {"file": "fresnel.exr", "width": 256, "height": 1, "levels": 1},
    "ior": 1.333, "model": "exact", "index": "nv"},
  "foam": {"name": "foam", "texture": {"file": "foam.exr", "width": 64, "height": 64, "levels": 7},
    "h0": 1.2, "hmax": 2.2, "tileSize": 4.0}
})";

void writeText(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

// readMaterial on text: never throws; an error is BadInput naming the file.
Result<MaterialDescription> readMaterialText(const ScratchDir& dir, const std::string& text) {
    const std::string path = dir.file("material.json");
    writeText(path, text);
    std::optional<Result<MaterialDescription>> r;
    EXPECT_NO_THROW(r.emplace(readMaterial(path))) << text;
    if (!r) return badInput(path, "threw");
    if (!*r) {
        EXPECT_EQ(r->error().kind, ErrorKind::BadInput) << text;
        EXPECT_EQ(r->error().path, path);
    }
    return std::move(*r);
}

// kMaterial with one change.
std::string materialWith(const std::function<void(nlohmann::json&)>& change) {
    nlohmann::json doc = nlohmann::json::parse(kMaterial);
    change(doc);
    return doc.dump();
}

}  // namespace

TEST(MaterialRobustness, TheFullMaterialReads) {
    ScratchDir dir;
    auto m = readMaterialText(dir, kMaterial);
    ASSERT_TRUE(m) << m.error().what;
    EXPECT_EQ(m->generator, "heightpack 0.1.0");
    EXPECT_EQ(m->displacement.at(0).texture.frames, 4);
}

// Fuzzing: `"generator": 1` made nlohmann::json throw type_error through readMaterial, which ended the
// viewer (it reads material.json through readMaterial).
TEST(MaterialRobustness, ANumberWhereAStringBelongsIsBadInputNamingTheKey) {
    ScratchDir dir;
    for (const char* key : {"generator", "manifest", "name", "schema"}) {
        auto m = readMaterialText(dir, materialWith([&](nlohmann::json& d) { d[key] = 1; }));
        ASSERT_FALSE(m) << key;
        EXPECT_NE(m.error().what.find(key), std::string::npos) << m.error().what;
    }
}

// Fuzzing: 1e20 and 1e10 were converted to int (undefined behaviour) before being judged.
TEST(MaterialRobustness, NumbersOutOfRangeAreRefusedBeforeAnyConversion) {
    ScratchDir dir;
    auto version = readMaterialText(dir, materialWith([](nlohmann::json& d) { d["version"] = 1e20; }));
    ASSERT_FALSE(version);
    EXPECT_NE(version.error().what.find("version 1e+20"), std::string::npos) << version.error().what;

    const std::vector<std::pair<std::string, nlohmann::json>> sizes = {
        {"width", 1e10}, {"height", -1e10}, {"levels", 1e300}, {"frames", 2147483648.0}, {"width", 2.5}, {"levels", 0}};
    for (const auto& [key, value] : sizes) {
        auto m = readMaterialText(dir, materialWith([&](nlohmann::json& d) { d["displacement"][0]["texture"][key] = value; }));
        ASSERT_FALSE(m) << key << " " << value;
        EXPECT_NE(m.error().what.find("texture." + key + " (a whole number"), std::string::npos) << m.error().what;
    }
}

// A float the viewer holds must fit a float: 1e300 or an overflowing 1e400 (read as infinity) cannot.
TEST(MaterialRobustness, NonFiniteAndHugeNumbersAreRefused) {
    ScratchDir dir;
    for (const char* text : {"1e400", "-1e400", "1e300"}) {
        const std::string json = materialWith([](nlohmann::json& d) { d["displacement"][0]["tileSize"] = 123456.0; });
        const size_t at = json.find("123456");
        ASSERT_NE(at, std::string::npos);
        std::string damaged = json;
        damaged.replace(at, json.find_first_of(",}", at) - at, text);
        auto m = readMaterialText(dir, damaged);
        EXPECT_FALSE(m) << text;
    }
    EXPECT_FALSE(readMaterialText(dir, materialWith([](nlohmann::json& d) { d["foam"]["h0"] = 1e35; })));
}

// Every value in the file, replaced by one of each other type: read or refused, never thrown.
TEST(MaterialRobustness, EveryValueOfAnotherTypeIsReadOrRefusedNeverThrown) {
    ScratchDir dir;
    const nlohmann::json doc = nlohmann::json::parse(kMaterial);
    const std::vector<nlohmann::json> others = {1, -1, 1e20, 0.5, "x", "", nullptr, true,
                                                nlohmann::json::array(), nlohmann::json::object()};
    int cases = 0;
    const nlohmann::json leaves = doc.flatten();  // "/displacement/0/name" -> value, ...
    for (const auto& item : leaves.items()) {
        // The leaf and every level above it.
        for (nlohmann::json::json_pointer at(item.key()); !at.empty(); at = at.parent_pointer())
            for (const nlohmann::json& other : others) {
                nlohmann::json damaged = doc;
                damaged[at] = other;
                (void)readMaterialText(dir, damaged.dump());
                ++cases;
            }
    }
    EXPECT_GT(cases, 500);
}

TEST(MaterialRobustness, TruncatedAndNonJsonFilesAreRefused) {
    ScratchDir dir;
    const std::string text = kMaterial;
    for (size_t n = 0; n < text.size() - 2; n += 7) EXPECT_FALSE(readMaterialText(dir, text.substr(0, n))) << n;
    EXPECT_FALSE(readMaterialText(dir, "[1, 2]"));
    EXPECT_FALSE(readMaterialText(dir, "\x89PNG\r\n"));
}

namespace {

// parseManifest on text beside one real map: never throws or asserts; an error is BadInput.
Result<Manifest> parseManifestText(const ScratchDir& dir, const std::string& text) {
    const std::string path = dir.file("water.toml");
    writeText(path, text);
    std::optional<Result<Manifest>> r;
    EXPECT_NO_THROW(r.emplace(parseManifest(path))) << text;
    if (!r) return badInput(path, "threw");
    if (!*r) {
        EXPECT_EQ(r->error().kind, ErrorKind::BadInput) << text << "\n" << r->error().what;
        EXPECT_EQ(r->error().path.rfind(path, 0), 0u) << r->error().path;
    }
    return std::move(*r);
}

}  // namespace

// Fuzzing: `[#]` reached a failing assert inside toml++'s parser (a debug build aborted; a release build
// built by clang turned the check into an assumption, undefined behaviour). Odd tables next to it.
TEST(ManifestRobustness, OddTomlIsBadInputNeverAnAssert) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(4, 4, [](int x, int y) { return float(x + y) / 8; }), OIIO::TypeDesc::UINT8);
    const std::string valid = "format = 1\nname = \"sea\"\n[[displacement]]\nname = \"a\"\nsource = \"map.png\"\ntile_size = 4\n";
    ASSERT_TRUE(parseManifestText(dir, valid));
    std::string deep = "a = ";
    for (int i = 0; i < 2000; ++i) deep += "[";
    const std::vector<std::string> cases = {
        "[#]", "[ #]", "[[#]]", "[=]", "[.]", "[a.]", "[\"\"]", "[a]\n[a]", "a.b = 1\n[a]", "[a]\nb = 1\n[a.b]",
        "[[a]]\n[a]", "x = 1979-05-27T07:32:00Z", "format = 1e400", "format = nan", "format = inf",
        "format = 9223372036854775807", "format = -9223372036854775808", "format = 99999999999999999999",
        "format = 1\nname = 1", "format = 1\nname = \"sea\"\ndisplacement = 1",
        "format = 1\nname = \"sea\"\ndisplacement = [1, 2]", "format = 1\nname = \"sea\"\n[displacement]",
        "format = 1\nname = \"sea\"\n[[displacement]]\n[displacement.x]",
        valid + "scroll = [1e400, 0]", valid + "scroll = \"x\"", valid + "amplitude = 1979-05-27",
        valid + "[normals]\nsource = \"map.png\"\ntile_size = 1\nheight = 1\noctave = 5",
        valid + "[normals]\nsource = \"map.png\"\ntile_size = 1\nheight = 1\n[normals.octave]",
        valid + "[fresnel]\nsize = 1e3", valid + "[fresnel]\nsize = 99999999999999999",
        valid + "[foam]\nh0 = \"1\"\nhmax = 2", valid + "[defaults]\nresize = 1",
        deep, "\xef\xbb\xbf[#]", std::string("a = \"\0\"", 7), "\xff\xfe", "a = '''\n[#]",
    };
    for (const std::string& text : cases) EXPECT_FALSE(parseManifestText(dir, text)) << text.substr(0, 80);
}
