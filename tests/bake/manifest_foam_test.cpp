// Foam from a manifest (issue 25): [displacement.synth] foam = true parses into the synth's foam options,
// bad foam keys are the manifest's errors, the foam is in each frame's key (its options and the
// choppiness it is worked out for), and the loop is computed once per build and shared by its frames,
// in one build's threads and across a plan's separate `--only` runs (through the intermediates folder).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <vector>

#include "heightpack/bake/build/build_job.hpp"
#include "heightpack/bake/manifest.hpp"

#include "support/test_support.hpp"

namespace heightpack::manifest_foam_test {
namespace {

namespace fs = std::filesystem;

// A 32 x 32 sea of three looping frames: the asset's own keys from line 6, then the synth table, whose
// keys given here start at line 14 when the asset adds none.
std::string foamManifest(const std::string& assetLines, const std::string& synthLines) {
    return "format = 1\nname = \"sea\"\n[[displacement]]\nname = \"swell\"\ntile_size = 64.0\n" + assetLines +
           "[displacement.synth]\nspectrum = \"jonswap\"\nwind = 14.0\nsize = 32\nseed = 7\nloop = 6.0\nframes = 3\n"
           "shift = true\n" +
           synthLines;
}
const std::string kFoam = "foam = true\n";

Result<Manifest> parseFoamManifest(const test::ScratchDir& dir, const std::string& text) {
    const std::string path = dir.file("m.toml");
    std::ofstream(path, std::ios::binary) << text;
    return parseManifest(path);
}

using test::readBytes;

TEST(ManifestFoam, TheTableGivesTheFoamOptionsAndTheAssetsChoppiness) {
    test::ScratchDir dir;
    auto m = parseFoamManifest(dir, foamManifest("choppiness = 1.3\n", kFoam + "foam_threshold = 0.7\nfoam_decay = 1.5\nfoam_build_up = 6.0\n"));
    ASSERT_TRUE(m) << m.error().path << ": " << m.error().what;
    const SynthSource& sea = *m->displacement[0].synth;
    EXPECT_TRUE(sea.foam);
    EXPECT_EQ(sea.foamOptions.threshold, 0.7);
    EXPECT_EQ(sea.foamOptions.decay, 1.5);
    EXPECT_EQ(sea.foamOptions.buildUp, 6.0);
    EXPECT_EQ(sea.choppiness, 1.3) << "the foam is where the surface the viewer draws folds";

    auto plain = parseFoamManifest(dir, foamManifest("", kFoam));
    ASSERT_TRUE(plain);
    const FoamOptions defaults;  // synth's --foam-* defaults
    EXPECT_EQ(plain->displacement[0].synth->foamOptions.threshold, defaults.threshold);
    EXPECT_EQ(plain->displacement[0].synth->foamOptions.decay, defaults.decay);
    EXPECT_EQ(plain->displacement[0].synth->foamOptions.buildUp, defaults.buildUp);
    EXPECT_EQ(plain->displacement[0].synth->choppiness, 1.0);
    EXPECT_FALSE(parseFoamManifest(dir, foamManifest("", ""))->displacement[0].synth->foam) << "no foam unless asked";
}

TEST(ManifestFoam, BadFoamKeysNameTheLineAndTheKey) {
    test::ScratchDir dir;
    const struct {
        std::string text;
        int line;
        std::string key;
    } cases[] = {
        {foamManifest("", "foam = 1\n"), 14, "synth.foam'"},                            // not true/false
        {foamManifest("", "foam_threshold = 0.7\n"), 14, "foam_threshold"},             // tuning without foam
        {foamManifest("", "foam = false\nfoam_decay = 3.0\n"), 15, "foam_decay"},
        {foamManifest("", kFoam + "foam_threshold = 2.5\n"), 15, "foam_threshold"},     // synth's ranges
        {foamManifest("", kFoam + "foam_decay = 0.0\n"), 15, "foam_decay"},
        {foamManifest("", kFoam + "foam_build_up = -1.0\n"), 15, "foam_build_up"},
        {foamManifest("choppiness = 0.0\n", kFoam), 6, "choppiness"},                  // nothing folds
        {foamManifest("foam = false\n", kFoam), 6, "].foam'"},                          // made, then dropped
    };
    for (const auto& c : cases) {
        auto m = parseFoamManifest(dir, c.text);
        ASSERT_FALSE(m) << c.text;
        EXPECT_EQ(m.error().kind, ErrorKind::BadInput);
        EXPECT_EQ(m.error().path, dir.file("m.toml") + ":" + std::to_string(c.line)) << m.error().what << "\n" << c.text;
        EXPECT_NE(m.error().what.find(c.key), std::string::npos) << m.error().what;
    }
}

// A build of text into out; counts the outputs remade and how many times a foam loop was computed (a
// step that computes one reports stage "foam" at 0 once).
struct Built {
    int rebuilt = -1, loopsComputed = 0;
};
Built buildFoamy(const test::ScratchDir& dir, const std::string& text, const std::string& out, int jobs = 1,
            const std::string& only = {}) {
    Built result;
    auto m = parseFoamManifest(dir, text);
    EXPECT_TRUE(m) << m.error().what;
    if (!m) return result;
    BuildOptions options;
    options.outputDir = dir.file(out);
    options.version = "test";
    options.jobs = jobs;
    options.only = only;
    std::mutex mutex;
    options.onEvent = [&](const BuildEvent& e) {
        std::lock_guard<std::mutex> lock(mutex);
        result.loopsComputed += e.stage == "foam" && e.fraction == 0.0;
    };
    auto r = buildMaterial(*m, options);
    EXPECT_TRUE(r) << r.error().path << ": " << r.error().what;
    if (r) result.rebuilt = r->rebuilt();
    return result;
}

// Each setting that shapes the foam remakes every frame; an unchanged manifest makes nothing.
TEST(ManifestFoam, TheFoamIsInTheKey) {
    test::ScratchDir dir;
    const std::string foamy = foamManifest("choppiness = 1.2\n", kFoam + "foam_threshold = 0.8\n");
    ASSERT_EQ(buildFoamy(dir, foamy, "out").rebuilt, 3);
    EXPECT_EQ(buildFoamy(dir, foamy, "out").rebuilt, 0) << "an unchanged manifest makes nothing";
    const std::vector<unsigned char> first = readBytes(dir.file("out/swell.0001.exr"));
    auto edited = [](std::string text, const std::string& from, const std::string& to) {
        return text.replace(text.find(from), from.size(), to);
    };
    const std::string changes[] = {
        edited(foamy, "foam_threshold = 0.8", "foam_threshold = 0.6"),
        foamy + "foam_decay = 3.0\n",
        foamy + "foam_build_up = 2.0\n",
        edited(foamy, "choppiness = 1.2", "choppiness = 1.5"),  // with foam, choppiness shapes the texture
        edited(foamy, "foam = true\nfoam_threshold = 0.8\n", ""),  // no foam at all
    };
    for (const std::string& changed : changes) {
        EXPECT_EQ(buildFoamy(dir, changed, "out").rebuilt, 3) << changed;
        EXPECT_NE(readBytes(dir.file("out/swell.0001.exr")), first) << changed;
        EXPECT_EQ(buildFoamy(dir, changed, "out").rebuilt, 0) << changed;
    }
    EXPECT_EQ(buildFoamy(dir, foamy, "out").rebuilt, 3);
    EXPECT_EQ(readBytes(dir.file("out/swell.0001.exr")), first) << "the same manifest makes the same bytes";
    EXPECT_FALSE(fs::exists(dir.file("out/.heightpack-synth"))) << "the loop goes with the intermediates";
}

// One loop per build, whatever --jobs; in a plan, the first action computes it and leaves it in the
// intermediates, the next ones read it (a damaged one is computed again), and the last action removes it.
// Every way makes the same bytes.
TEST(ManifestFoam, TheLoopIsComputedOnceAndShared) {
    test::ScratchDir dir;
    const std::string foamy = foamManifest("", kFoam + "foam_threshold = 0.8\n");
    EXPECT_EQ(buildFoamy(dir, foamy, "one", 1).loopsComputed, 1);
    EXPECT_EQ(buildFoamy(dir, foamy, "three", 3).loopsComputed, 1);
    EXPECT_EQ(buildFoamy(dir, foamy, "three", 3).loopsComputed, 0) << "nothing to make: no loop either";

    const std::string loop = dir.file("plan/.heightpack-synth/swell.foam");
    EXPECT_EQ(buildFoamy(dir, foamy, "plan", 1, "swell.0002.exr").loopsComputed, 1);
    ASSERT_TRUE(fs::exists(loop));
    EXPECT_EQ(buildFoamy(dir, foamy, "plan", 1, "swell.0000.exr").loopsComputed, 0) << "read from the intermediates";
    std::vector<unsigned char> damaged = readBytes(loop);
    damaged[damaged.size() - 5] ^= 0x40;  // in frame 2's floats, the last frame's
    test::writeBytes(loop, damaged);
    EXPECT_EQ(buildFoamy(dir, foamy, "plan", 1, "swell.0001.exr").loopsComputed, 0) << "frame 1's bytes are whole";
    EXPECT_EQ(buildFoamy(dir, foamy, "plan", 1, "swell.0002.exr").loopsComputed, 1) << "frame 2's are not: computed again";
    EXPECT_EQ(buildFoamy(dir, foamy, "plan", 1, "material.json").loopsComputed, 0);
    EXPECT_FALSE(fs::exists(dir.file("plan/.heightpack-synth"))) << "the last action removes the loop and its lock";
    for (const char* f : {"swell.0000.exr", "swell.0001.exr", "swell.0002.exr"}) {
        const std::vector<unsigned char> reference = readBytes(dir.file(std::string("one/") + f));
        EXPECT_EQ(readBytes(dir.file(std::string("three/") + f)), reference) << f << ": --jobs";
        EXPECT_EQ(readBytes(dir.file(std::string("plan/") + f)), reference) << f << ": one action at a time";
    }
}

}  // namespace
}  // namespace heightpack::manifest_foam_test
