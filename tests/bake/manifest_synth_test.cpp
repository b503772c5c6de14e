// Manifests that synthesise ([displacement.synth]): the table parses into the spectrum it says, bad
// tables are the manifest's errors (FILE:LINE, key), and a build keys the sea on its spectrum, so an
// unchanged manifest makes nothing and a changed wind remakes the map.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "heightpack/bake/build/build_job.hpp"
#include "heightpack/bake/build/cache_key.hpp"
#include "heightpack/bake/manifest.hpp"
#include "heightpack/core/sea/cascades.hpp"

#include "support/test_support.hpp"

namespace heightpack {
namespace {

namespace fs = std::filesystem;

// A 32 x 32 sea of three looping frames: small enough that a build takes milliseconds.
std::string seaManifest(const std::string& synthLines) {
    return "format = 1\nname = \"sea\"\n\n[[displacement]]\nname = \"swell\"\ntile_size = 64.0\n\n"
           "[displacement.synth]\n" + synthLines;  // the table is line 8, its keys from line 9
}
constexpr const char* kSea = "spectrum = \"jonswap\"\nwind = 12.0\nfetch = 50000.0\nsize = 32\nseed = 7\nloop = 8.0\nframes = 3\n";

Result<Manifest> parseText(const test::ScratchDir& dir, const std::string& text) {
    const std::string path = dir.file("m.toml");
    std::ofstream(path, std::ios::binary) << text;
    return parseManifest(path);
}

std::string bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(ManifestSynth, TheTableGivesTheSpectrumAndTheAssetsTileSize) {
    test::ScratchDir dir;
    auto m = parseText(dir, seaManifest(std::string(kSea) + "direction = 30.0\nspreading = \"cos2s\"\nspreading_s = 12.0\n"
                                                             "depth = 40.0\nswell = [2.5, 12.0, 250.0]\ngamma = 2.0\n"));
    ASSERT_TRUE(m) << m.error().path << ": " << m.error().what;
    const DisplacementAsset& d = m->displacement[0];
    ASSERT_TRUE(d.synth);
    const SpectrumOptions& s = d.synth->spectrum;
    EXPECT_EQ(s.model, SpectrumModel::Jonswap);
    EXPECT_EQ(s.windSpeed, 12.0);
    EXPECT_EQ(s.windDirection, 30.0);
    EXPECT_EQ(s.fetch, 50000.0);
    EXPECT_EQ(s.gamma, 2.0);
    EXPECT_EQ(s.spreading, Spreading::Cos2s);
    EXPECT_EQ(s.spreadingExponent, 12.0);
    EXPECT_EQ(s.depth, 40.0);
    EXPECT_EQ(s.swell.significantHeight, 2.5);
    EXPECT_EQ(s.swell.peakPeriod, 12.0);
    EXPECT_EQ(s.swell.direction, 250.0);
    EXPECT_EQ(s.tileSize, 64.0) << "the sea spans the asset's own tile";
    EXPECT_EQ(s.size, 32);
    EXPECT_EQ(s.seed, 7u);
    EXPECT_EQ(s.loopPeriod, 8.0);
    EXPECT_EQ(d.synth->frames, 3);
    EXPECT_TRUE(d.source.empty());
    EXPECT_FALSE(d.mustTile) << "a synthesised sea tiles by construction";
    ASSERT_EQ(d.frames.size(), 3u);
    EXPECT_EQ(d.frames[2], std::string(kSynthFolder) + "/swell.0002.exr") << "intermediates go inside the output";
    EXPECT_EQ(d.output, "swell.exr");
}

TEST(ManifestSynth, BadTablesAreBadInputNamingTheLineAndTheKey) {
    test::ScratchDir dir;
    test::writeImage(dir.file("a.png"), test::randomImage(8, 8, 1), OIIO::TypeDesc::UINT16);
    struct Case {
        std::string text;
        int line;
        std::string word;
    };
    const Case cases[] = {
        {seaManifest("wind = 12.0\nwindd = 3.0\n"), 10, "windd"},                    // unknown key
        {seaManifest("wind = \"12m/s\"\n"), 9, "wind"},                             // wrong type
        {seaManifest("wind = 0.0\n"), 9, "wind"},                                   // out of range
        {seaManifest("wind = 12.0\nsize = 48\n"), 10, "size"},                       // not a power of two
        {seaManifest("wind = 12.0\nframes = 4\n"), 10, "loop"},                      // frames without a loop
        {seaManifest("wind = 12.0\nspectrum = \"phillips\"\nfetch = 1000.0\n"), 11, "fetch"},
        {seaManifest("wind = 12.0\nspreading_s = 4.0\n"), 10, "spreading_s"},
        {seaManifest("wind = 12.0\nswell = [40.0, 12.0, 0.0]\n"), 10, "swell"},
        {seaManifest("direction = 10.0\n"), 8, "wind"},                             // required key missing
        {"format = 1\nname = \"sea\"\n[[displacement]]\nname = \"s\"\nsource = \"a.png\"\ntile_size = 4.0\n"
         "synth = { wind = 10.0 }\n", 5, "source"},                                 // both
        {"format = 1\nname = \"sea\"\n[[displacement]]\nname = \"s\"\ntile_size = 4.0\n", 3, "synth"},  // neither
        {seaManifest("wind = 12.0\nshift = 1\n"), 10, "shift"},                 // not true/false
        {seaManifest("wind = 12.0\ndisplacement = 1\n"), 10, "displacement"},   // nor under its old name
        {seaManifest("wind = 12.0\nshift = true\ndisplacement = true\n"), 11, "shift"},  // both names
        {seaManifest("wind = 12.0\ncascades = 5\n"), 10, "cascades"},           // more than synth bakes
        {seaManifest("wind = 12.0\ncascades = 0\n"), 10, "cascades"},
        {seaManifest("wind = 12.0\nsize = 16\ncascades = 2\n"), 11, "cascades"},  // bands too narrow
        // A cascade's name taken by an asset above; a name too long for its cascades'.
        {"format = 1\nname = \"sea\"\n[[displacement]]\nname = \"swell_c1\"\nsource = \"a.png\"\ntile_size = 4.0\n"
         "[[displacement]]\nname = \"swell\"\ntile_size = 64.0\nsynth = { wind = 10.0, size = 32, cascades = 2 }\n",
         8, "swell_c1"},
        {"format = 1\nname = \"sea\"\n[[displacement]]\nname = \"" + std::string(63, 'w') +
             "\"\ntile_size = 64.0\nsynth = { wind = 10.0, size = 32, cascades = 2 }\n",
         4, "cascades"},
        // Seven maps and a sea of two cascades: nine in the material.
        {"format = 1\nname = \"sea\"\n" + [] {
             std::string maps;
             for (int i = 0; i < 7; ++i)
                 maps += "[[displacement]]\nname = \"m" + std::to_string(i) + "\"\nsource = \"a.png\"\ntile_size = 4.0\n";
             return maps;
         }() + "[[displacement]]\nname = \"swell\"\ntile_size = 64.0\nsynth = { wind = 10.0, size = 32, cascades = 2 }\n",
         34, "cascades"},
    };
    for (const Case& c : cases) {
        auto m = parseText(dir, c.text);
        ASSERT_FALSE(m) << c.text;
        const Error& e = m.error();
        EXPECT_EQ(e.kind, ErrorKind::BadInput) << c.text;
        EXPECT_EQ(e.path, dir.file("m.toml") + ":" + std::to_string(c.line)) << e.what << "\n" << c.text;
        EXPECT_NE((e.what + " " + e.hint).find(c.word), std::string::npos) << e.what << " (" << e.hint << ")";
    }
}

// displacement = true, as manifests written before the word shift say it, asks for what shift = true does.
TEST(ManifestSynth, TheOldNameOfShiftStillReads) {
    test::ScratchDir dir;
    for (const auto& [lines, expected] : {std::pair{"", false}, {"shift = true\n", true}, {"displacement = true\n", true},
                                          {"shift = false\n", false}, {"displacement = false\n", false}}) {
        auto m = parseText(dir, seaManifest(std::string(kSea) + lines));
        ASSERT_TRUE(m) << lines << m.error().what;
        ASSERT_TRUE(m->displacement[0].synth);
        EXPECT_EQ(m->displacement[0].synth->shift, expected) << lines;
    }
}

// cascades = N splits the asset into N, each with the spectrum, tile size and names core's plan and
// synth --cascades give cascade c; shift = true rides along on each.
TEST(ManifestSynth, CascadesAreOneAssetEachAsCorePlansThem) {
    test::ScratchDir dir;
    auto m = parseText(dir, seaManifest(std::string(kSea) + "cascades = 3\nshift = true\n"));
    ASSERT_TRUE(m) << m.error().path << ": " << m.error().what;
    auto whole = parseText(dir, seaManifest(kSea));
    ASSERT_TRUE(whole);
    const SpectrumOptions sea = whole->displacement[0].synth->spectrum;
    const std::vector<CascadeBand> bands = cascadeBands(64.0, 32, 3, 7);
    ASSERT_EQ(m->displacement.size(), 3u);
    for (int c = 0; c < 3; ++c) {
        const DisplacementAsset& d = m->displacement[c];
        const std::string name = "swell_c" + std::to_string(c);
        ASSERT_TRUE(d.synth);
        EXPECT_EQ(d.layer.name, name);
        EXPECT_EQ(d.output, name + ".exr");
        EXPECT_EQ(d.frames.at(2), std::string(kSynthFolder) + "/" + name + ".0002.exr");
        EXPECT_EQ(d.layer.tileSize, bands[c].tileSize);
        EXPECT_EQ(d.synth->cascade, c);
        EXPECT_EQ(d.synth->cascades, 3);
        EXPECT_TRUE(d.synth->shift);
        EXPECT_EQ(keyText(d.synth->spectrum, ""), keyText(cascadeOptions(sea, bands[c]), "")) << "cascade " << c;
    }
}

// Builds the manifest into out with `jobs` jobs; returns how many outputs were remade.
int build(const test::ScratchDir& dir, const std::string& text, const std::string& out, int jobs) {
    auto m = parseText(dir, text);
    EXPECT_TRUE(m) << m.error().what;
    if (!m) return -1;
    BuildOptions options;
    options.outputDir = dir.file(out);
    options.version = "test";
    options.jobs = jobs;
    auto r = buildMaterial(*m, options);
    EXPECT_TRUE(r) << r.error().what;
    return r ? r->rebuilt() : -1;
}

TEST(ManifestSynth, TheSeaIsRemadeOnlyWhenItsSpectrumChanges) {
    test::ScratchDir dir;
    const std::string sea = seaManifest(kSea);
    ASSERT_EQ(build(dir, sea, "out", 1), 3) << "three frames";
    const std::string frame1 = bytes(dir.file("out/swell.0001.exr"));
    ASSERT_FALSE(frame1.empty());
    EXPECT_NE(frame1, bytes(dir.file("out/swell.0000.exr"))) << "the frames are the sea at different times";
    EXPECT_FALSE(fs::exists(dir.file(std::string("out/") + kSynthFolder))) << "intermediates and their folder go";
    const std::string json = bytes(dir.file("out/material.json"));
    EXPECT_NE(json.find("\"loopPeriod\": 8"), std::string::npos) << json;

    EXPECT_EQ(build(dir, sea, "out", 1), 0) << "an unchanged manifest makes nothing";
    EXPECT_EQ(build(dir, sea, "jobs2", 2), 3);
    for (const char* f : {"swell.0000.exr", "swell.0001.exr", "swell.0002.exr"})
        EXPECT_EQ(bytes(dir.file(std::string("out/") + f)), bytes(dir.file(std::string("jobs2/") + f))) << f << ": --jobs";

    std::string windier = sea;
    windier.replace(windier.find("wind = 12.0"), 11, "wind = 14.0");
    EXPECT_EQ(build(dir, windier, "out", 1), 3) << "a new wind is a new sea";
    EXPECT_NE(bytes(dir.file("out/swell.0001.exr")), frame1);
    EXPECT_EQ(build(dir, windier, "out", 1), 0);
}

// The new keys are in each map's key: an unchanged manifest makes nothing; displacement, the cascade
// count and a spectrum parameter each remake every map; a non-zero choppiness only rewrites material.json.
TEST(ManifestSynth, ShiftAndCascadesAreInTheKey) {
    test::ScratchDir dir;
    auto edited = [](std::string text, const std::string& from, const std::string& to) {
        return text.replace(text.find(from), from.size(), to);
    };
    std::string sea = seaManifest(std::string(kSea) + "cascades = 2\nshift = true\n");
    sea = edited(sea, "frames = 3", "frames = 1");  // one frame each: fast
    ASSERT_EQ(build(dir, sea, "out", 1), 2) << "two cascades";
    EXPECT_EQ(build(dir, sea, "out", 1), 0) << "an unchanged manifest makes nothing";
    const std::string choppy = bytes(dir.file("out/swell_c1.exr"));

    const std::string calmer = edited(sea, "tile_size = 64.0\n", "tile_size = 64.0\nchoppiness = 0.5\n");
    EXPECT_EQ(build(dir, calmer, "out", 1), 0) << "choppiness is the renderer's, not the texture's";
    EXPECT_NE(bytes(dir.file("out/material.json")).find("\"choppiness\": 0.5"), std::string::npos);

    const std::string flat = edited(sea, "shift = true", "shift = false");
    EXPECT_EQ(build(dir, flat, "out", 1), 2) << "heights alone are other textures";
    EXPECT_LT(bytes(dir.file("out/swell_c1.exr")).size(), choppy.size());
    EXPECT_EQ(build(dir, flat, "out", 1), 0);

    const std::string three = edited(flat, "cascades = 2", "cascades = 3");
    EXPECT_EQ(build(dir, three, "out", 1), 3) << "each cascade's place and band";
    EXPECT_EQ(build(dir, three, "out", 1), 0);

    const std::string gamma = three + "gamma = 2.0\n";
    EXPECT_EQ(build(dir, gamma, "out", 1), 3) << "a spectrum parameter";
    EXPECT_EQ(build(dir, gamma, "out", 1), 0);

    EXPECT_EQ(build(dir, sea, "out", 1), 2) << "back to two choppy cascades";
    EXPECT_EQ(bytes(dir.file("out/swell_c1.exr")), choppy) << "the same manifest makes the same bytes";
}

}  // namespace
}  // namespace heightpack
