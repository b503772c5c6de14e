// `heightpack build` end to end: incremental rebuilds by content, deterministic trees whatever --jobs,
// a killed build leaving no partial file, bad manifests named by file:line, material.json and the
// depfile checked by independent readers (OpenImageIO, nlohmann::json).
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <thread>
#include <numbers>

#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
namespace fs = std::filesystem;

namespace {


// A periodic sea: whole numbers of waves across the tile, so every level tiles.
Image periodicMap(int size, double amplitude, int seed) {
    return makeImage(size, size, [=](int x, int y) {
        const double u = double(x) / size, v = double(y) / size;
        double h = 0.5;
        for (int k = 1; k <= 5; ++k)
            h += amplitude / k * std::sin(2 * std::numbers::pi * (k * u + ((k + seed) % 3) * v) + 0.7 * k + seed);
        return static_cast<float>(h);
    });
}

// A painting whose edges do not meet: a ramp left to right and an off-period wave.
Image paintedMap(int size) {
    return makeImage(size, size, [=](int x, int y) {
        return static_cast<float>(0.2 + 0.5 * x / size + 0.1 * std::sin(0.37 * y) * std::cos(0.23 * x));
    });
}

const char* kManifest = R"(format = 1
name = "sea"

[defaults]
filter = "kaiser"

[[displacement]]
name = "long"
source = "maps/a.png"
tile_size = 64.0
scroll = [0.01, 0.004]
amplitude = 1.5

[[displacement]]
name = "short"
source = "maps/b.png"
tile_size = 16.0
amplitude = 0.4

[normals]
name = "ripple_n"
source = "maps/r.png"
tile_size = 8.0
height = 0.05
filter = "kaiser"

[fresnel]
ior = 1.333
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

void writeText(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Every file under root (hidden ones too), relative path -> bytes.
std::map<std::string, std::string> tree(const fs::path& root) {
    std::map<std::string, std::string> files;
    std::error_code ec;
    for (const auto& e : fs::recursive_directory_iterator(root, ec))
        if (e.is_regular_file()) files[fs::relative(e.path(), root).string()] = readText(e.path().string());
    return files;
}

// Every file under root, relative path -> a hash of its bytes: short enough to print when it differs.
std::map<std::string, size_t> fingerprint(const fs::path& root) {
    std::map<std::string, size_t> files;
    for (const auto& [name, bytes] : tree(root)) files[name] = std::hash<std::string>{}(bytes);
    return files;
}

long long mtimeNs(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return -1;
    return st.st_mtim.tv_sec * 1000000000LL + st.st_mtim.tv_nsec;
}

// A project folder with four maps and the manifest above.
class BuildTest : public ::testing::Test {
protected:
    void SetUp() override {
        fs::create_directories(dir.path() / "maps");
        writeImage(dir.file("maps/a.png"), periodicMap(128, 0.08, 1), OIIO::TypeDesc::UINT16);
        writeImage(dir.file("maps/b.png"), periodicMap(64, 0.06, 2), OIIO::TypeDesc::UINT16);
        writeImage(dir.file("maps/r.png"), periodicMap(64, 0.1, 3), OIIO::TypeDesc::UINT8);
        writeImage(dir.file("maps/painted.png"), paintedMap(128), OIIO::TypeDesc::UINT8);
        writeText(manifest, kManifest);
    }

    ProcessResult build(std::vector<std::string> extra = {}) {
        std::vector<std::string> args = {"build", manifest, "-o", out};
        args.insert(args.end(), extra.begin(), extra.end());
        return heightpackRun(args);
    }
    // Builds with --json and returns the one material's report.
    nlohmann::json buildJson(std::vector<std::string> extra = {}) {
        extra.push_back("--json");
        const ProcessResult r = build(extra);
        EXPECT_EQ(r.code, 0) << r.err;
        const auto doc = nlohmann::json::parse(r.out, nullptr, false);
        EXPECT_FALSE(doc.is_discarded()) << r.out;
        return doc.is_discarded() ? nlohmann::json() : doc["materials"][0];
    }
    // Output -> status, from a report.
    static std::map<std::string, std::string> statuses(const nlohmann::json& material) {
        std::map<std::string, std::string> s;
        for (const auto& a : material["assets"]) s[a["output"]] = a["status"];
        return s;
    }

    ScratchDir dir;
    std::string manifest = dir.file("water.toml");
    std::string out = dir.file("out");
};

}  // namespace

TEST_F(BuildTest, SecondBuildDoesNothingAndSaysSo) {
    const auto first = buildJson();
    EXPECT_EQ(first["rebuilt"], 4);
    for (const auto& [output, status] : statuses(first)) EXPECT_EQ(status, "rebuilt") << output;
    const auto before = tree(out);
    const long long swellTime = mtimeNs(out + "/long.exr");

    const ProcessResult again = build();
    ASSERT_EQ(again.code, 0) << again.err;
    EXPECT_NE(again.out.find("nothing to do"), std::string::npos) << again.out;
    const auto second = buildJson();
    EXPECT_EQ(second["rebuilt"], 0);
    EXPECT_EQ(second["upToDate"], 4);
    EXPECT_FALSE(second["materialWritten"]);
    EXPECT_EQ(tree(out), before);
    EXPECT_EQ(mtimeNs(out + "/long.exr"), swellTime);  // not even rewritten with the same bytes
}

TEST_F(BuildTest, TouchingAMapWithoutChangingItRebuildsNothing) {
    buildJson();
    const auto later = fs::last_write_time(dir.file("maps/a.png")) + std::chrono::hours(1);
    fs::last_write_time(dir.file("maps/a.png"), later);
    fs::last_write_time(manifest, later);
    const auto report = buildJson();
    EXPECT_EQ(report["rebuilt"], 0) << report.dump(1);
}

TEST_F(BuildTest, ChangingOneMapRebuildsItsOutputOnly) {
    buildJson();
    const auto before = tree(out);
    writeImage(dir.file("maps/b.png"), periodicMap(64, 0.09, 2), OIIO::TypeDesc::UINT16);
    const auto report = buildJson();
    const std::map<std::string, std::string> expected = {
        {"long.exr", "up to date"}, {"short.exr", "rebuilt"}, {"ripple_n.exr", "up to date"}, {"fresnel.exr", "up to date"}};
    EXPECT_EQ(statuses(report), expected);
    const auto after = tree(out);
    EXPECT_NE(after.at("short.exr"), before.at("short.exr"));
    for (const char* same : {"long.exr", "ripple_n.exr", "fresnel.exr", "material.json"})
        EXPECT_EQ(after.at(same), before.at(same)) << same;
}

TEST_F(BuildTest, ChangingTheFilterRebuildsThePackedTexturesOnly) {
    buildJson();
    writeText(manifest, replaced(kManifest, "[defaults]\nfilter = \"kaiser\"", "[defaults]\nfilter = \"lanczos3\""));
    const auto report = buildJson();
    const std::map<std::string, std::string> expected = {
        {"long.exr", "rebuilt"}, {"short.exr", "rebuilt"}, {"ripple_n.exr", "up to date"}, {"fresnel.exr", "up to date"}};
    EXPECT_EQ(statuses(report), expected);
    // The rebuilt texture says so in its header, read by OpenImageIO.
    auto in = OIIO::ImageInput::open(out + "/long.exr");
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().get_string_attribute("heightpack:filter"), "lanczos3");
}

TEST_F(BuildTest, ChangingAnAmplitudeRewritesOnlyMaterialJson) {
    buildJson();
    writeText(manifest, replaced(kManifest, "amplitude = 1.5", "amplitude = 2.25"));
    const auto report = buildJson();
    EXPECT_EQ(report["rebuilt"], 0);
    EXPECT_TRUE(report["materialWritten"]);
    const auto material = nlohmann::json::parse(readText(out + "/material.json"));
    EXPECT_EQ(material["displacement"][0]["amplitude"], 2.25);
}

TEST_F(BuildTest, DeletedOrDamagedOutputsAreRebuiltToTheSameBytes) {
    buildJson();
    const auto before = tree(out);
    fs::remove(out + "/long.exr");
    std::string damaged = before.at("short.exr");
    damaged[damaged.size() / 2] ^= 0x55;
    writeText(out + "/short.exr", damaged);
    const auto report = buildJson();
    const std::map<std::string, std::string> expected = {
        {"long.exr", "rebuilt"}, {"short.exr", "rebuilt"}, {"ripple_n.exr", "up to date"}, {"fresnel.exr", "up to date"}};
    EXPECT_EQ(statuses(report), expected);
    EXPECT_EQ(tree(out), before);
}

TEST_F(BuildTest, JobsOneAndTwoGiveByteIdenticalTrees) {
    const std::string one = dir.file("one"), two = dir.file("two");
    ASSERT_EQ(heightpackRun({"build", manifest, "-o", one, "--jobs", "1", "--threads", "1"}).code, 0);
    ASSERT_EQ(heightpackRun({"build", manifest, "-o", two, "--jobs", "2", "--threads", "3"}).code, 0);
    const auto a = tree(one), b = tree(two);
    EXPECT_EQ(a.size(), 6u);  // four textures, material.json, the build state
    EXPECT_EQ(a, b);
}

TEST_F(BuildTest, MaterialJsonDescribesWhatWasWritten) {
    buildJson();
    const auto m = nlohmann::json::parse(readText(out + "/material.json"));
    EXPECT_EQ(m["schema"], "heightpack-material");
    EXPECT_EQ(m["version"], 1);
    EXPECT_EQ(m["name"], "sea");
    ASSERT_EQ(m["displacement"].size(), 2u);
    const auto& d = m["displacement"][0];
    EXPECT_EQ(d["tileSize"], 64.0);
    EXPECT_EQ(d["scroll"], nlohmann::json::array({0.01, 0.004}));
    EXPECT_EQ(d["amplitude"], 1.5);
    EXPECT_EQ(d["layout"], "neighbour4");
    // Sizes and level counts as OpenImageIO reads them from the files.
    for (const auto* layer : {&m["displacement"][0], &m["displacement"][1], &m["normals"], &m["fresnel"]}) {
        const auto& t = (*layer)["texture"];
        auto in = OIIO::ImageInput::open(out + "/" + t["file"].get<std::string>());
        ASSERT_TRUE(in) << t.dump();
        EXPECT_EQ(t["width"], in->spec().width);
        EXPECT_EQ(t["height"], in->spec().height);
        int levels = 0;
        while (in->seek_subimage(0, levels)) ++levels;
        EXPECT_EQ(t["levels"], levels);
    }
    EXPECT_EQ(m["normals"]["octaves"].size(), 1u);  // none given: one at the map's own tile size
    EXPECT_EQ(m["normals"]["octaves"][0]["tileSize"], 8.0);
    EXPECT_EQ(m["fresnel"]["ior"], 1.333);
}

TEST_F(BuildTest, JsonReportGivesHashesChecksAndTimes) {
    const auto r = buildJson();
    ASSERT_EQ(r["assets"].size(), 4u);
    std::map<std::string, nlohmann::json> byName;
    for (const auto& a : r["assets"]) byName[a["name"]] = a;
    EXPECT_EQ(byName["long"]["inputHash"].get<std::string>().size(), 32u);
    EXPECT_NE(byName["long"]["inputHash"], byName["short"]["inputHash"]);
    EXPECT_TRUE(byName["fresnel"]["inputHash"].is_null());
    EXPECT_TRUE(byName["long"]["check"]["ran"]);
    EXPECT_TRUE(byName["long"]["check"]["tiles"]);
    EXPECT_LT(byName["long"]["check"]["worst"]["leftRight"]["value"].get<double>(), 2.0);
    EXPECT_TRUE(byName["fresnel"]["check"].is_null());
    EXPECT_GE(byName["long"]["seconds"].get<double>(), 0.0);
    // The same map under another name hashes the same: the hash is of the bytes.
    fs::copy_file(dir.file("maps/a.png"), dir.file("maps/a_copy.png"));
    writeText(manifest, replaced(kManifest, "maps/b.png", "maps/a_copy.png"));
    const auto again = buildJson();
    EXPECT_EQ(again["assets"][0]["inputHash"], again["assets"][1]["inputHash"]);
    // An up-to-date output's check passed in the build that made it and is not run again.
    EXPECT_FALSE(again["assets"][0]["check"]["ran"]);
    EXPECT_TRUE(again["assets"][0]["check"]["passedEarlier"]);
}

TEST_F(BuildTest, AMapThatMustTileAndDoesNotFailsTheBuildNamingIt) {
    buildJson();
    const auto before = tree(out);
    writeText(manifest, replaced(kManifest, "maps/b.png", "maps/painted.png"));
    const ProcessResult r = build();
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find(manifest + ":14: displacement 'short' (" ), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("left/right edges"), std::string::npos) << r.err;
    EXPECT_EQ(tree(out), before);
    // Marked as not tiling, the same map builds.
    writeText(manifest, replaced(replaced(kManifest, "maps/b.png", "maps/painted.png"), "amplitude = 0.4",
                                 "amplitude = 0.4\ntileable = false"));
    const auto report = buildJson();
    EXPECT_EQ(report["assets"][1]["status"], "rebuilt");
    EXPECT_TRUE(report["assets"][1]["check"].is_null());
}

TEST_F(BuildTest, CheckOnlyValidatesAndWritesNothing) {
    const ProcessResult ok = heightpackRun({"build", manifest, "--check-only"});
    EXPECT_EQ(ok.code, 0) << ok.err;
    EXPECT_NE(ok.out.find("manifest valid"), std::string::npos) << ok.out;
    EXPECT_FALSE(fs::exists(out));
    writeText(manifest, replaced(kManifest, "maps/a.png", "maps/painted.png"));
    const ProcessResult bad = heightpackRun({"build", manifest, "--check-only", "-o", out});
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.err.find("displacement 'long'"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(out));
}

TEST_F(BuildTest, DepfileNamesTheStampTheManifestAndEverySource) {
    const std::string depfile = dir.file("sea.d"), stamp = dir.file("sea.stamp");
    ASSERT_EQ(build({"--depfile", depfile, "--stamp", stamp}).code, 0);
    EXPECT_TRUE(fs::exists(stamp));
    const std::string text = readText(depfile);
    EXPECT_EQ(text.rfind(stamp + ":", 0), 0u) << text;
    for (const char* file : {"water.toml", "maps/a.png", "maps/b.png", "maps/r.png"})
        EXPECT_NE(text.find(fs::absolute(dir.file(file)).string()), std::string::npos) << file << "\n" << text;
    EXPECT_EQ(text.find("painted"), std::string::npos);  // not read, not a dependency
}

TEST_F(BuildTest, SequenceSourcesBuildFrameByFrame) {
    for (int f = 0; f < 3; ++f) {
        char name[64];
        std::snprintf(name, sizeof name, "maps/sea.%04d.png", f);
        writeImage(dir.file(name), periodicMap(64, 0.05 + 0.01 * f, f), OIIO::TypeDesc::UINT16);
    }
    writeText(manifest, replaced(kManifest, "maps/b.png", "maps/sea.png"));
    const auto report = buildJson();
    EXPECT_EQ(report["rebuilt"], 6);
    for (const char* frame : {"short.0000.exr", "short.0001.exr", "short.0002.exr"}) EXPECT_TRUE(fs::exists(out + "/" + frame));
    const auto m = nlohmann::json::parse(readText(out + "/material.json"));
    EXPECT_EQ(m["displacement"][1]["texture"]["file"], "short.exr");
    EXPECT_EQ(m["displacement"][1]["texture"]["frames"], 3);
}

TEST_F(BuildTest, SeveralManifestsBuildIntoOneFolderEach) {
    const std::string second = dir.file("lagoon.toml");
    writeText(second, replaced(kManifest, "name = \"sea\"", "name = \"lagoon\""));
    const ProcessResult r = heightpackRun({"build", manifest, second, "-o", out, "--jobs", "2"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(out + "/sea/material.json"));
    EXPECT_TRUE(fs::exists(out + "/lagoon/material.json"));
    EXPECT_EQ(readText(out + "/sea/long.exr"), readText(out + "/lagoon/long.exr"));
    // A map that must tile and does not, in either material, stops both: every material is checked
    // before any is written.
    const auto before = tree(out);
    writeText(second, replaced(replaced(kManifest, "name = \"sea\"", "name = \"lagoon\""), "maps/b.png",
                               "maps/painted.png"));
    writeImage(dir.file("maps/a.png"), periodicMap(128, 0.07, 1), OIIO::TypeDesc::UINT16);  // sea would rebuild
    const ProcessResult failing = heightpackRun({"build", manifest, second, "-o", out});
    EXPECT_EQ(failing.code, 1) << failing.err;
    EXPECT_NE(failing.err.find(second + ":14: displacement 'short'"), std::string::npos) << failing.err;
    EXPECT_NE(failing.out.find("sea: nothing written"), std::string::npos) << failing.out;
    EXPECT_EQ(tree(out), before);
    // Two materials of one name would overwrite each other.
    const ProcessResult clash = heightpackRun({"build", manifest, manifest, "-o", out});
    EXPECT_EQ(clash.code, 3);
}

// A manifest user is told the manifest key that fixes an input, never a command-line flag.
TEST_F(BuildTest, HintsNameManifestKeysNotFlags) {
    writeImage(dir.file("maps/odd.png"), periodicMap(100, 0.08, 4), OIIO::TypeDesc::UINT16);
    writeText(manifest, replaced(kManifest, "maps/a.png", "maps/odd.png"));
    const ProcessResult odd = build();
    EXPECT_EQ(odd.code, 3) << odd.err;
    EXPECT_NE(odd.err.find("set resize = true to resample it to 128x128"), std::string::npos) << odd.err;
    EXPECT_NE(odd.err.find("asset 'long'"), std::string::npos) << odd.err;
    EXPECT_EQ(odd.err.find("--resize"), std::string::npos) << odd.err;

    // The normal map's remedy too: a manifest cannot ask for an 8-bit PNG, so only resize is offered.
    writeText(manifest, replaced(kManifest, "maps/r.png", "maps/odd.png"));
    const ProcessResult normals = build();
    EXPECT_EQ(normals.code, 3) << normals.err;
    EXPECT_NE(normals.err.find("set resize = true to resample it to 128x128"), std::string::npos) << normals.err;
    EXPECT_EQ(normals.err.find("--"), std::string::npos) << normals.err;

    const Image grey = periodicMap(64, 0.06, 5);
    std::vector<float> rgb;
    for (float v : grey.pixels) rgb.insert(rgb.end(), {v, 0.5f * v, 0.25f});
    writeImage(dir.file("maps/colour.png"), 64, 64, 3, rgb, OIIO::TypeDesc::UINT8);
    writeText(manifest, replaced(kManifest, "maps/b.png", "maps/colour.png"));
    const ProcessResult colour = build();
    EXPECT_EQ(colour.code, 3) << colour.err;
    EXPECT_NE(colour.err.find("choose the height channel with channel = \"r\", \"g\", \"b\", \"a\", \"luma\" or a "
                              "channel's name"),
              std::string::npos)
        << colour.err;
    EXPECT_EQ(colour.err.find("--channel"), std::string::npos) << colour.err;

    // The command line keeps its flags for the same inputs.
    const ProcessResult packed = heightpackRun({"pack", dir.file("maps/odd.png"), "-o", dir.file("odd.exr")});
    EXPECT_EQ(packed.code, 3);
    EXPECT_NE(packed.err.find("(pass --resize pow2 to resample it to 128x128)"), std::string::npos) << packed.err;
}

// Each bad manifest: an error on one line naming file:line and the key, the documented exit code, and
// the previous build's outputs untouched.
TEST_F(BuildTest, BadManifestsNameFileLineAndKeepThePreviousOutputs) {
    buildJson();
    const auto before = tree(out);
    struct Case {
        const char* what;
        std::string text;
        std::string marker;  // the error's line is the line holding this text
        int code;
        std::string mentions;
    };
    const std::string base = kManifest;
    const std::vector<Case> cases = {
        {"syntax error", replaced(base, "[[displacement]]\nname = \"short\"", "[[displacement]\nname = \"short\""),
         "[[displacement]\n", 3, "TOML syntax error"},
        {"unknown top-level key", replaced(base, "name = \"sea\"", "name = \"sea\"\ncolour = \"blue\""), "colour", 3,
         "unknown key 'colour'"},
        {"misspelt key", replaced(base, "tile_size = 64.0", "tile_sise = 64.0"), "tile_sise", 3,
         "did you mean 'tile_size'"},
        {"negative tile size", replaced(base, "tile_size = 64.0", "tile_size = -64.0"), "tile_size = -64.0", 3,
         "displacement[0].tile_size"},
        {"missing map", replaced(base, "maps/a.png", "maps/missing.png"), "maps/missing.png", 3, "does not exist"},
        {"map not tileable", replaced(base, "maps/a.png", "maps/painted.png"), "[[displacement]]\nname = \"long\"", 1,
         "does not tile"},
        {"duplicate output", replaced(base, "name = \"short\"", "name = \"short\"\noutput = \"long.exr\""),
         "[[displacement]]\nname = \"short\"", 3, "'long.exr'"},
        {"output escaping via ..", replaced(base, "name = \"short\"", "name = \"short\"\noutput = \"../short.exr\""),
         "../short.exr", 3, "displacement[1].output"},
        {"absolute output", replaced(base, "name = \"short\"", "name = \"short\"\noutput = \"/tmp/short.exr\""),
         "/tmp/short.exr", 3, "displacement[1].output"},
        {"output not an exr", replaced(base, "name = \"short\"", "name = \"short\"\noutput = \"short.png\""),
         "short.png", 3, ".exr"},
        {"wrong type", replaced(base, "amplitude = 0.4", "amplitude = \"0.4\""), "amplitude = \"0.4\"", 3,
         "must be a number"},
        {"missing required key", replaced(base, "height = 0.05\n", ""), "[normals]", 3, "missing key 'normals.height'"},
        {"unknown wrap", replaced(base, "[defaults]\n", "[defaults]\nwrap = \"mirror\"\n"), "mirror", 3,
         "defaults.wrap"},
        {"newer format", replaced(base, "format = 1", "format = 2"), "format = 2", 3, "format"},
        {"no height maps", "format = 1\nname = \"sea\"\n", "format = 1", 3, "missing key 'displacement'"},
        // Misspelt, the tables are named rather than the key they leave missing.
        {"height maps under another name",
         replaced(replaced(base, "[[displacement]]\nname = \"long\"", "[[unused]]\nname = \"long\""),
                  "[[displacement]]\nname = \"short\"", "[[unused]]\nname = \"short\""),
         "[[unused]]\nname = \"long\"", 3, "unknown key 'unused'"},
        {"foam hmax below h0", base + "\n[foam]\nh0 = 2.0\nhmax = 1.0\n", "hmax = 1.0", 3, "foam.hmax"},
        {"Fresnel ramp too small", replaced(base, "ior = 1.333", "ior = 1.333\nsize = 1"), "size = 1\n", 3, "fresnel.size"},
        {"scroll with three numbers", replaced(base, "scroll = [0.01, 0.004]", "scroll = [0.01, 0.004, 0.0]"),
         "scroll = [", 3, "displacement[0].scroll"},
        {"duplicate name", replaced(base, "name = \"short\"", "name = \"long\""), "name = \"long\"\nsource = \"maps/b",
         3, "already the name"},
        {"bad channel", replaced(base, "name = \"short\"", "name = \"short\"\nchannel = \"x\""), "channel", 3,
         "displacement[1].channel"},
        {"normal height zero", replaced(base, "height = 0.05", "height = 0"), "height = 0", 3, "normals.height"},
        {"ior below one", replaced(base, "ior = 1.333", "ior = 0.5"), "ior = 0.5", 3, "fresnel.ior"},
        {"octaves not tables", replaced(base, "filter = \"kaiser\"\n\n[fresnel]", "filter = \"kaiser\"\noctave = 3\n\n[fresnel]"),
         "octave = 3", 3, "normals.octave"},
    };
    ASSERT_GE(cases.size(), 15u);
    for (const Case& c : cases) {
        SCOPED_TRACE(c.what);
        writeText(manifest, c.text);
        const size_t at = c.text.find(c.marker);
        ASSERT_NE(at, std::string::npos) << c.marker;
        const int line = 1 + static_cast<int>(std::count(c.text.begin(), c.text.begin() + at, '\n'));
        const ProcessResult r = build();
        EXPECT_EQ(r.code, c.code) << r.err;
        EXPECT_EQ(r.err.rfind("heightpack: error: " + manifest + ":" + std::to_string(line) + ": ", 0), 0u) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_NE(r.err.find(c.mentions), std::string::npos) << r.err;
        EXPECT_EQ(tree(out), before);
    }
}

// Interrupts a build of six large maps the moment its first texture appears, with SIGKILL (which
// cannot be caught: what it leaves must already be whole) or SIGINT (whose handler removes the
// temporary files). Either way every texture there is complete, and the next build finishes the job,
// clears what the interrupted one left, and gives what an uninterrupted build gives.
class InterruptedBuildTest : public BuildTest, public ::testing::WithParamInterface<int> {};

TEST_P(InterruptedBuildTest, LeavesNoPartialOutputAndTheNextBuildCompletesIt) {
    const int signal = GetParam();
    std::string text = "format = 1\nname = \"big\"\n";
    for (int i = 0; i < 6; ++i) {
        const std::string map = "maps/big" + std::to_string(i) + ".png";
        writeImage(dir.file(map), periodicMap(1024, 0.05 + 0.01 * i, i), OIIO::TypeDesc::UINT16);
        text += "[[displacement]]\nname = \"big" + std::to_string(i) + "\"\nsource = \"" + map + "\"\ntile_size = 32\n";
    }
    writeText(manifest, text);

    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        const int devnull = ::open("/dev/null", O_WRONLY);
        ::dup2(devnull, 1);
        ::dup2(devnull, 2);
        ::execl(HEIGHTPACK_EXE, HEIGHTPACK_EXE, "build", manifest.c_str(), "-o", out.c_str(), "--jobs", "1",
                "--threads", "1", static_cast<char*>(nullptr));
        ::_exit(127);
    }
    auto firstOutput = [&] {
        std::error_code ec;
        for (const auto& e : fs::directory_iterator(out, ec))
            if (e.path().extension() == ".exr" && e.path().filename().string()[0] != '.') return true;
        return false;
    };
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    int status = 0;
    bool exited = false;
    while (!firstOutput() && std::chrono::steady_clock::now() < deadline) {
        if (::waitpid(child, &status, WNOHANG) == child) {
            exited = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ::kill(child, signal);
    if (!exited) ::waitpid(child, &status, 0);
    ASSERT_FALSE(exited) << "the build finished before it could be interrupted";
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(WTERMSIG(status), signal);

    // Every texture there is whole: OpenImageIO reads every level of it.
    int complete = 0;
    bool temporaries = false;
    for (const auto& e : fs::directory_iterator(out)) {
        const std::string name = e.path().filename().string();
        temporaries = temporaries || name.find(".hptmp-") != std::string::npos;
        if (name[0] == '.' || e.path().extension() != ".exr") continue;
        auto in = OIIO::ImageInput::open(e.path().string());
        ASSERT_TRUE(in) << name;
        for (int level = 0; in->seek_subimage(0, level); ++level) {
            std::vector<float> pixels(size_t(in->spec().width) * in->spec().height * 4);
            EXPECT_TRUE(in->read_image(0, level, 0, 4, OIIO::TypeDesc::FLOAT, pixels.data())) << name << " " << level;
        }
        ++complete;
    }
    EXPECT_GE(complete, 1);
    EXPECT_LT(complete, 6);
    EXPECT_FALSE(fs::exists(out + "/material.json"));
    if (signal == SIGINT) {
        EXPECT_FALSE(temporaries) << "SIGINT's handler removes the temporary file being written";
    }

    // Outputs recorded in the build state are kept; one renamed into place just before the signal, and
    // not yet recorded, is made again.
    const auto report = buildJson({"--jobs", "2"});
    EXPECT_GE(report["rebuilt"].get<int>(), 6 - complete);
    EXPECT_LE(report["rebuilt"].get<int>(), 7 - complete);
    for (const auto& e : fs::directory_iterator(out))
        EXPECT_EQ(e.path().filename().string().find(".hptmp-"), std::string::npos) << e.path();
    const std::string clean = dir.file("clean");
    ASSERT_EQ(heightpackRun({"build", manifest, "-o", clean}).code, 0);
    EXPECT_EQ(tree(out), tree(clean));
}

INSTANTIATE_TEST_SUITE_P(Signals, InterruptedBuildTest, ::testing::Values(SIGKILL, SIGINT),
                         [](const ::testing::TestParamInfo<int>& info) {
                             return std::string(info.param == SIGKILL ? "SIGKILL" : "SIGINT");
                         });

TEST_F(BuildTest, ADamagedSourceIsBadInputNamingItAndItsManifestLine) {
    buildJson();
    const auto before = tree(out);
    const std::string png = readText(dir.file("maps/b.png"));
    writeText(dir.file("maps/b.png"), png.substr(0, png.size() / 2));
    const ProcessResult r = build();
    EXPECT_EQ(r.code, 3);
    EXPECT_EQ(r.err.rfind("heightpack: error: " + dir.file("maps/b.png") + ": ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("asset 'short' of " + manifest + ":14"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(tree(out), before);
}

TEST_F(BuildTest, DepfileEscapesSpacesForMakeAndNinja) {
    fs::copy_file(dir.file("maps/a.png"), dir.file("maps/a b.png"));
    writeText(manifest, replaced(kManifest, "maps/a.png", "maps/a b.png"));
    const std::string depfile = dir.file("sea.d");
    ASSERT_EQ(build({"--depfile", depfile, "--stamp", dir.file("stamp")}).code, 0);
    EXPECT_NE(readText(depfile).find("maps/a\\ b.png"), std::string::npos) << readText(depfile);
}

TEST_F(BuildTest, AnOutputThatWouldOverwriteASourceIsRefused) {
    // A source EXR built into its own folder: the packed texture would replace the map it is made from.
    const std::string exr = dir.file("maps/a.exr");
    ASSERT_EQ(heightpackRun({"tile", dir.file("maps/a.png"), "--depth", "float", "-q", "-o", exr}).code, 0);
    std::string text = replaced(replaced(kManifest, "maps/a.png", "a.exr"), "name = \"long\"", "name = \"a\"");
    for (size_t at; (at = text.find("maps/")) != std::string::npos;) text.erase(at, 5);
    writeText(dir.file("maps/m.toml"), text);
    const std::string before = readText(exr);
    const ProcessResult r = heightpackRun({"build", dir.file("maps/m.toml"), "-o", dir.file("maps")});
    EXPECT_EQ(r.code, 4) << r.err;
    EXPECT_NE(r.err.find("is also a source"), std::string::npos) << r.err;
    EXPECT_EQ(readText(exr), before);
}

TEST_F(BuildTest, FoamTexturesSubfoldersAndTheThresholdWork) {
    std::string text = replaced(kManifest, "name = \"long\"", "name = \"long\"\noutput = \"textures/long.exr\"");
    text = replaced(text, "name = \"sea\"", "name = \"sea\"\nthreshold = 100000.0");  // lets the painting pass
    text = replaced(text, "maps/b.png", "maps/painted.png");
    text += "\n[foam]\nh0 = 0.5\nhmax = 0.9\ntile_size = 3.0\nsource = \"maps/r.png\"\nfilter = \"box\"\n";
    writeText(manifest, text);
    const auto report = buildJson();
    EXPECT_EQ(report["rebuilt"], 5) << report.dump(1);
    EXPECT_TRUE(fs::exists(out + "/textures/long.exr"));

    const auto m = nlohmann::json::parse(readText(out + "/material.json"));
    EXPECT_EQ(m["displacement"][0]["texture"]["file"], "textures/long.exr");
    EXPECT_EQ(m["foam"]["h0"], 0.5);
    EXPECT_EQ(m["foam"]["hmax"], 0.9);
    EXPECT_EQ(m["foam"]["tileSize"], 3.0);
    ASSERT_EQ(m["foam"]["texture"]["file"], "foam.exr");
    // The foam texture is a plain one-channel mip chain of the map, as OpenImageIO reads it.
    auto in = OIIO::ImageInput::open(out + "/foam.exr");
    ASSERT_TRUE(in);
    EXPECT_EQ(in->spec().nchannels, 1);
    EXPECT_EQ(in->spec().get_string_attribute("heightpack:layout"), "plain");
    EXPECT_EQ(in->spec().get_string_attribute("heightpack:filter"), "box");
    int levels = 0;
    while (in->seek_subimage(0, levels)) ++levels;
    EXPECT_EQ(levels, 7);  // 64x64 down to 1x1
    EXPECT_EQ(m["foam"]["texture"]["levels"], levels);
    std::vector<float> level0(64 * 64);
    ASSERT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, level0.data()));
    auto map = OIIO::ImageInput::open(dir.file("maps/r.png"));
    ASSERT_TRUE(map);
    std::vector<float> painted(64 * 64);
    ASSERT_TRUE(map->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, painted.data()));
    EXPECT_EQ(level0, painted);
}

// A build that cannot write its depfile or its stamp writes nothing at all: every path is judged first.
TEST_F(BuildTest, AnUnwritableDepfileOrStampStopsTheBuildBeforeAnythingIsWritten) {
    writeText(dir.file("a-file"), "not a folder\n");
    for (const std::vector<std::string>& extra :
         {std::vector<std::string>{"--depfile", dir.file("missing/sea.d")},
          std::vector<std::string>{"--stamp", dir.file("missing/sea.stamp")},
          std::vector<std::string>{"--depfile", dir.file("a-file/sea.d"), "--stamp", dir.file("sea.stamp")},
          std::vector<std::string>{"--depfile", dir.file("sea.d"), "--stamp", dir.file("water.toml")}}) {
        const auto before = fingerprint(dir.path());
        const ProcessResult r = build(extra);
        EXPECT_EQ(r.code, 4) << extra[1] << "\n" << r.err;
        EXPECT_NE(r.err.find(extra.back() == dir.file("water.toml") ? "water.toml" : extra[1]), std::string::npos) << r.err;
        EXPECT_EQ(fingerprint(dir.path()), before) << extra[1];  // no texture, no material.json, no state, no depfile
        EXPECT_FALSE(fs::exists(out)) << extra[1];
    }
}

// Inside the output folder the build makes the folders, for the depfile and the stamp too; both are
// written whole (no temporary file left) and replace what was there.
TEST_F(BuildTest, DepfileAndStampInTheOutputFolderAreWrittenAtomically) {
    const std::string depfile = out + "/deps/sea.d", stamp = out + "/sea.stamp";
    ASSERT_EQ(build({"--depfile", depfile, "--stamp", stamp}).code, 0);
    EXPECT_EQ(readText(stamp), "heightpack build stamp\n");
    EXPECT_EQ(readText(depfile).rfind(stamp + ":", 0), 0u);
    writeText(stamp, "an older, longer stamp that must not survive in part\n");
    ASSERT_EQ(build({"--depfile", depfile, "--stamp", stamp}).code, 0);
    EXPECT_EQ(readText(stamp), "heightpack build stamp\n");
    for (const auto& [name, bytes] : tree(out)) EXPECT_EQ(name.find(".hptmp-"), std::string::npos) << name;
}

// The docs promise that a damaged state file only means a full rebuild: whatever it holds.
TEST_F(BuildTest, ADamagedStateFileMeansAFullRebuildNeverAnError) {
    buildJson();
    const auto before = fingerprint(out);
    const std::string statePath = out + "/.heightpack-build.json";
    const std::string good = readText(statePath);
    const auto state = nlohmann::json::parse(good);
    const std::string output = state["outputs"].begin().key();
    auto with = [&](const std::function<void(nlohmann::json&)>& change) {
        nlohmann::json s = state;
        change(s);
        return s.dump();
    };
    const std::vector<std::pair<std::string, std::string>> damaged = {
        {"key a number", with([&](nlohmann::json& s) { s["outputs"][output]["key"] = 1; })},
        {"hash null", with([&](nlohmann::json& s) { s["outputs"][output]["hash"] = nullptr; })},
        {"checked an array", with([&](nlohmann::json& s) { s["outputs"][output]["checked"] = {1, 2}; })},
        {"entry a string", with([&](nlohmann::json& s) { s["outputs"][output] = "x"; })},
        {"format a string", with([&](nlohmann::json& s) { s["format"] = "1"; })},
        {"format huge", with([&](nlohmann::json& s) { s["format"] = 1e20; })},
        {"format huge integer", replaced(good, "\"format\": 1", "\"format\": 18446744073709551615")},
        {"format another", with([&](nlohmann::json& s) { s["format"] = 2; })},
        {"outputs an array", with([&](nlohmann::json& s) { s["outputs"] = {1}; })},
        {"a top-level array", "[1, 2, 3]"},
        {"truncated", good.substr(0, good.size() / 2)},
        {"not JSON", "\x89PNG garbage\n"},
        {"empty", ""},
    };
    for (const auto& [what, text] : damaged) {
        writeText(statePath, text);
        const ProcessResult r = build({"--json"});
        ASSERT_EQ(r.code, 0) << what << ": " << r.err;
        const auto report = nlohmann::json::parse(r.out, nullptr, false);
        ASSERT_FALSE(report.is_discarded()) << what;
        for (const auto& [name, status] : statuses(report["materials"][0])) EXPECT_EQ(status, "rebuilt") << what << " " << name;
        EXPECT_EQ(fingerprint(out), before) << what;  // the same bytes, and the state written afresh
    }
}

// Output paths are judged before writing, but a relative output folder that does not exist yet is
// still made (the README's demo does this), with the depfile and the stamp inside it.
TEST_F(BuildTest, ARelativeOutputFolderThatDoesNotExistYetIsMade) {
    const ProcessResult r = runProcess({"sh", "-c", "cd \"$0\" && \"$1\" build water.toml -o new/out --depfile new/out/sea.d "
                                                    "--stamp new/out/sea.stamp", dir.path().string(), HEIGHTPACK_EXE});
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* file : {"new/out/long.exr", "new/out/material.json", "new/out/sea.d", "new/out/sea.stamp"})
        EXPECT_TRUE(fs::is_regular_file(dir.file(file))) << file;
}

// A manifest that synthesises its sea: built once, then nothing to do, then a changed wind remakes the
// map with other bytes; a bad synth key is the manifest's error (FILE:LINE, exit 3) and writes nothing.
TEST_F(BuildTest, ASynthesisedSeaRebuildsWhenItsSpectrumChanges) {
    const std::string sea = "format = 1\nname = \"sea\"\n[[displacement]]\nname = \"swell\"\ntile_size = 64.0\n"
                            "[displacement.synth]\nwind = 12.0\nsize = 32\nseed = 3\n";
    writeText(manifest, sea);
    const auto first = buildJson();
    EXPECT_EQ(first["rebuilt"], 1) << first.dump(1);
    const std::string before = readText(out + "/swell.exr");
    ASSERT_FALSE(before.empty());
    const ProcessResult again = build();
    ASSERT_EQ(again.code, 0) << again.err;
    EXPECT_NE(again.out.find("nothing to do"), std::string::npos) << again.out;

    writeText(manifest, replaced(sea, "wind = 12.0", "wind = 15.0"));
    EXPECT_EQ(buildJson()["rebuilt"], 1);
    EXPECT_NE(readText(out + "/swell.exr"), before) << "a stronger wind is another sea";

    writeText(manifest, replaced(sea, "seed = 3", "seed = 3\nfetch_km = 20"));
    const ProcessResult bad = build();
    EXPECT_EQ(bad.code, 3);
    EXPECT_NE(bad.err.find(manifest + ":10:"), std::string::npos) << bad.err;
    EXPECT_NE(bad.err.find("'displacement[0].synth.fetch_km'"), std::string::npos) << bad.err;
}

// The build as a Ninja plan (issue 26, item 1): run by Ninja at -j 1 and -j 4, it makes the same bytes as
// `heightpack build` (the state file and material.json too, so a later build finds everything up to
// date); a second run does nothing; changing one map reruns its action and the last one only. The
// manifest adds a synthesised sea of three frames, three actions that share an intermediate folder.
TEST_F(BuildTest, TheNinjaPlanMakesTheSameBytesAndRerunsOnlyWhatChanged) {
    writeText(manifest, std::string(kManifest) +
                            "\n[[displacement]]\nname = \"swell\"\ntile_size = 32.0\n"
                            "synth = { wind = 9.0, size = 32, seed = 2, loop = 4.0, frames = 3 }\n");
    ASSERT_EQ(build().code, 0);  // the reference, into out
    const ProcessResult plan = heightpackRun({"build", manifest, "-o", dir.file("planned"), "--plan", "ninja"});
    ASSERT_EQ(plan.code, 0) << plan.err;
    writeText(dir.file("plan.ninja"), plan.out);
    const ProcessResult json = heightpackRun({"build", manifest, "-o", dir.file("planned"), "--plan", "json"});
    ASSERT_EQ(json.code, 0) << json.err;
    const auto actions = nlohmann::json::parse(json.out)["actions"];
    ASSERT_EQ(actions.size(), 4u + 3u + 1u);  // four outputs, three frames, material.json
    EXPECT_EQ(actions.back()["outputs"][0], dir.file("planned") + "/material.json");
    EXPECT_EQ(actions.back()["inputs"].size(), 2u + 3u + 7u);  // the program, the manifest, every map, every output
    EXPECT_EQ(actions[0]["inputs"][2], dir.file("maps/a.png"));

    auto ninja = [&](const std::string& plan, const std::string& jobs) {
        return runProcess({"ninja", "-C", dir.path().string(), "-f", plan, "-j", jobs});
    };
    // The plan's paths are as given (absolute here), so it runs from any folder; -j 1 from another plan.
    const ProcessResult serial = heightpackRun({"build", manifest, "-o", dir.file("serial"), "--plan", "ninja"});
    writeText(dir.file("serial.ninja"), serial.out);
    const ProcessResult one = ninja("serial.ninja", "1"), four = ninja("plan.ninja", "4");
    ASSERT_EQ(one.code, 0) << one.out << one.err;
    ASSERT_EQ(four.code, 0) << four.out << four.err;
    EXPECT_EQ(fingerprint(dir.file("planned")), fingerprint(out));
    EXPECT_EQ(fingerprint(dir.file("serial")), fingerprint(out));
    EXPECT_FALSE(fs::exists(dir.file("planned/.heightpack-synth")));  // the frames' intermediates are gone

    const ProcessResult again = ninja("plan.ninja", "4");
    EXPECT_NE(again.out.find("no work to do"), std::string::npos) << again.out;
    const ProcessResult upToDate = heightpackRun({"build", manifest, "-o", dir.file("planned")});
    EXPECT_NE(upToDate.out.find("nothing to do"), std::string::npos) << upToDate.out;

    writeImage(dir.file("maps/b.png"), periodicMap(64, 0.09, 2), OIIO::TypeDesc::UINT16);
    const ProcessResult changed = ninja("plan.ninja", "4");
    ASSERT_EQ(changed.code, 0) << changed.out;
    EXPECT_NE(changed.out.find("[1/2] bake sea: short.exr"), std::string::npos) << changed.out;
    EXPECT_NE(changed.out.find("[2/2] describe sea: material.json"), std::string::npos) << changed.out;
    ASSERT_EQ(build().code, 0);
    EXPECT_EQ(fingerprint(dir.file("planned")), fingerprint(out));

    // An output the manifest does not make, or --plan with what it does not go with: usage errors.
    const ProcessResult unknown = heightpackRun({"build", manifest, "-o", dir.file("planned"), "--only", "nope.exr"});
    EXPECT_EQ(unknown.code, 2) << unknown.err;
    EXPECT_NE(unknown.err.find("nope.exr"), std::string::npos) << unknown.err;
    EXPECT_EQ(heightpackRun({"build", manifest, "-o", out, "--plan", "ninja", "--check-only"}).code, 2);
}

// --plan bazel names every file by a label of the package in the folder the plan is made in (issue 37):
// a path outside it, or absolute, is a usage error of one line, before anything is printed. The plan
// itself is run by Bazel in tests/cli/bazel_plan_test.cpp (label bazel).
TEST_F(BuildTest, TheBazelPlanRefusesPathsOutsideItsPackage) {
    const ProcessResult absolute = build({"--plan", "bazel"});
    EXPECT_EQ(absolute.code, 2) << absolute.err;
    expectOneLineError(absolute, manifest);
    auto inFolder = [&](const std::string& line) {
        return runProcess({"bash", "-c", "cd \"$1\" && \"$0\" " + line, HEIGHTPACK_EXE, dir.path().string()});
    };
    const ProcessResult escaping = inFolder("build water.toml -o ../out --plan bazel");
    EXPECT_EQ(escaping.code, 2) << escaping.err;
    expectOneLineError(escaping, "../out/");
    const ProcessResult plan = inFolder("build ./water.toml -o out/sea --plan bazel");
    ASSERT_EQ(plan.code, 0) << plan.err;
    size_t rules = 0;
    for (size_t at = plan.out.find("genrule("); at != std::string::npos; at = plan.out.find("genrule(", at + 1)) ++rules;
    EXPECT_EQ(rules, 4u + 1u) << plan.out;  // four outputs and material.json
    EXPECT_NE(plan.out.find("outs = [\"out/sea/long.exr\"]"), std::string::npos) << plan.out;
    EXPECT_NE(plan.out.find("\"maps/a.png\""), std::string::npos) << plan.out;

    const ProcessResult workspace = heightpackRun({"build", "--plan", "bazel-workspace"});
    EXPECT_EQ(workspace.code, 0) << workspace.err;
    EXPECT_NE(workspace.out.find("new_local_repository("), std::string::npos) << workspace.out;
    EXPECT_NE(workspace.out.find("\"" + fs::path(HEIGHTPACK_EXE).parent_path().string() + "\""), std::string::npos)
        << workspace.out;
    EXPECT_EQ(heightpackRun({"build", manifest, "--plan", "bazel-workspace"}).code, 2);
    EXPECT_EQ(heightpackRun({"build", "-o", out}).code, 2);  // no manifest
    EXPECT_EQ(inFolder("build water.toml -o out --plan bazel --cache cache").code, 2);  // Bazel has its own
}

// In Bazel's sandbox an action sees only what it declares (issue 37): each frame of a painted sequence
// declares every frame (which are there decides the outputs' names), each frame of a sea with foam the
// loop's own action's output, and material.json every map once and every output.
TEST_F(BuildTest, TheBazelPlanDeclaresEveryFileEachActionReads) {
    for (int f = 0; f < 3; ++f)
        writeImage(dir.file("maps/seq.000" + std::to_string(f) + ".png"), periodicMap(32, 0.05, f), OIIO::TypeDesc::UINT8);
    writeText(manifest, "format = 1\nname = \"sea\"\n[[displacement]]\nname = \"seq\"\nsource = \"maps/seq.png\"\n"
                        "tile_size = 32.0\n[[displacement]]\nname = \"foamy\"\ntile_size = 64.0\n"
                        "synth = { wind = 9.0, size = 16, seed = 2, loop = 4.0, frames = 2, foam = true }\n"
                        "[normals]\nname = \"n\"\nsource = \"maps/seq.0001.png\"\ntile_size = 8.0\nheight = 0.05\n");
    const ProcessResult plan = runProcess({"bash", "-c", "cd \"$1\" && \"$0\" build water.toml -o out --plan bazel",
                                           HEIGHTPACK_EXE, dir.path().string()});
    ASSERT_EQ(plan.code, 0) << plan.err;
    // Each rule's outs and srcs, by the rule's first output.
    std::map<std::string, std::pair<std::string, std::string>> rules;  // first output -> srcs, outs text
    for (size_t at = plan.out.find("genrule("); at != std::string::npos;) {
        const size_t next = plan.out.find("genrule(", at + 1);
        const std::string rule = plan.out.substr(at, next == std::string::npos ? std::string::npos : next - at);
        const size_t srcs = rule.find("srcs = "), outs = rule.find("outs = "), tools = rule.find("tools = ");
        const std::string outsText = rule.substr(outs, tools - outs);
        const size_t quote = outsText.find('"');
        rules[outsText.substr(quote + 1, outsText.find('"', quote + 1) - quote - 1)] = {rule.substr(srcs, outs - srcs), outsText};
        at = next;
    }
    ASSERT_EQ(rules.size(), 1u + 3u + 2u + 1u + 1u) << plan.out;  // the loop, 3 + 2 frames, normals, material.json
    auto declares = [&](const std::string& output, const std::string& file) {
        return rules[output].first.find("\"" + file + "\"") != std::string::npos;
    };
    ASSERT_TRUE(rules.count("out/.heightpack-synth/foamy.foam")) << plan.out;
    for (const char* frame : {"out/seq.0000.exr", "out/seq.0001.exr", "out/seq.0002.exr"})
        for (const char* map : {"maps/seq.0000.png", "maps/seq.0001.png", "maps/seq.0002.png"})
            EXPECT_TRUE(declares(frame, map)) << frame << " " << map;
    for (const char* frame : {"out/foamy.0000.exr", "out/foamy.0001.exr"}) {
        EXPECT_TRUE(declares(frame, "out/.heightpack-synth/foamy.foam")) << frame;
        EXPECT_FALSE(declares(frame, "maps/seq.0000.png")) << frame;
    }
    EXPECT_TRUE(declares("out/n.exr", "maps/seq.0001.png"));
    EXPECT_FALSE(declares("out/n.exr", "maps/seq.0000.png"));
    const std::string& last = rules["out/material.json"].first;
    for (const char* file : {"maps/seq.0000.png", "maps/seq.0001.png", "maps/seq.0002.png", "out/seq.0002.exr",
                             "out/foamy.0001.exr", "out/n.exr"}) {
        const std::string quoted = std::string("\"") + file + "\"";
        EXPECT_NE(last.find(quoted), std::string::npos) << file;
        EXPECT_EQ(last.find(quoted), last.rfind(quoted)) << file << " once";
    }
    EXPECT_NE(rules["out/material.json"].second.find("\"out/.heightpack-build.json\""), std::string::npos);
}
