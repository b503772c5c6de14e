// heightpack-view under Xvfb with Mesa's software GL: screenshots read back and compared, so a wrong
// lookup, pass or camera shows up as wrong pixels.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "viewer_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// The first row from the top that is not the black background, in column x.
int horizonRow(const Picture& p, int x) {
    for (int y = 0; y < p.height; ++y)
        if (p.at(x, y, 0) > 8 || p.at(x, y, 1) > 8 || p.at(x, y, 2) > 8) return y;
    return p.height;
}

}  // namespace

TEST(Viewer, PackedLookupEqualsHardwareBilinearOfThePlainMap) {
    // Looking straight down, the height shown as grey: the packed path and GL_LINEAR on the R32F map.
    ScratchDir dir;
    const std::vector<std::string> common = {kExamples + "swell.png", "--view", "height", "--size", "320x240",
                                             "--time", "3", "--camera", "0,0,40,0,-89.9", "--amplitude", "4",
                                             "--tile-size", "64"};
    for (const auto& [packed, reference] : {std::pair<std::string, std::string>{"bilinear", "reference-bilinear"},
                                            {"trilinear", "reference-trilinear"}}) {
        auto a = common, b = common;
        a.insert(a.end(), {"--lookup", packed});
        b.insert(b.end(), {"--lookup", reference});
        const Picture pa = screenshot(dir, packed + ".png", a), pb = screenshot(dir, reference + ".png", b);
        const Difference d = compare(pa, pb, 2);
        EXPECT_LE(d.max, 4) << packed;
        EXPECT_LT(d.fractionOver, 0.01) << packed;
    }
    // From high above the far water uses coarse levels: trilinear against its reference there too.
    auto high = common;
    high[8] = "0,0,400,0,-30";
    auto a = high, b = high;
    a.insert(a.end(), {"--lookup", "trilinear"});
    b.insert(b.end(), {"--lookup", "reference-trilinear"});
    const Difference far = compare(screenshot(dir, "far_a.png", a), screenshot(dir, "far_b.png", b), 2);
    EXPECT_LE(far.max, 6);
    EXPECT_LT(far.fractionOver, 0.01);
    // And the picture is not blank: the waves vary the grey.
    const Picture p = readPicture(dir.file("bilinear.png"));
    int lo = 255, hi = 0;
    for (size_t i = 0; i < p.rgb.size(); i += 3) lo = std::min<int>(lo, p.rgb[i]), hi = std::max<int>(hi, p.rgb[i]);
    EXPECT_GT(hi - lo, 60);
}

TEST(Viewer, FrustumBranchAndTwoPassesDoNotChangeThePicture) {
    ScratchDir dir;
    const std::vector<std::string> common = {kExamples + "swell.png", kExamples + "choppy.png", "--size", "320x180",
                                             "--time", "7", "--camera", "5,-3,6,40,-12"};
    const Picture base = screenshot(dir, "base.png", common);
    auto noBranch = common;
    noBranch.push_back("--no-frustum-branch");
    const Difference branch = compare(base, screenshot(dir, "nobranch.png", noBranch), 2);
    EXPECT_LE(branch.max, 3);
    auto twoPass = common;
    twoPass.push_back("--two-pass");
    const Difference passes = compare(base, screenshot(dir, "twopass.png", twoPass), 4);
    EXPECT_LT(passes.fractionOver, 0.005);
}

TEST(Viewer, FlatWaterPutsTheHorizonWhereTheCameraSaysAndWavesBreakIt) {
    ScratchDir dir;
    writeImage(dir.file("flat.png"), makeImage(64, 64, [](int, int) { return 0.5f; }), OIIO::TypeDesc::UINT8);
    // 60 degree vertical field of view, 400 rows, looking 10 degrees down: the horizon is
    // 200 * tan(10 deg) / tan(30 deg) = 61.1 rows above the middle.
    const double expected = 200.0 - 200.0 * std::tan(10 * M_PI / 180) / std::tan(30 * M_PI / 180);
    const Picture flat = screenshot(dir, "flat_shot.png", {dir.file("flat.png"), "--view", "height", "--size",
                                                            "400x400", "--camera", "0,0,2,0,-10"});
    for (int x = 0; x < flat.width; x += 13) EXPECT_NEAR(horizonRow(flat, x), expected, 1.5) << "column " << x;
    const Picture waves = screenshot(dir, "waves_shot.png", {kExamples + "painted_not_tileable.png", "--view", "height",
                                                              "--size", "400x400", "--camera", "0,0,2,0,-10",
                                                              "--amplitude", "6", "--tile-size", "40"});
    int lowest = waves.height, highest = 0;
    for (int x = 0; x < waves.width; ++x) {
        lowest = std::min(lowest, horizonRow(waves, x));
        highest = std::max(highest, horizonRow(waves, x));
    }
    EXPECT_GT(highest - lowest, 3) << "a displaced sea has a ragged skyline";
}

TEST(Viewer, TiledViewShowsTheSeamsOfANonTileableMapOnly) {
    ScratchDir dir;
    auto jumpRatio = [&](const std::string& map) {
        const Picture p = screenshot(dir, "tiled.png", {map, "--tiled", "3x3", "--size", "600x600"});
        // Mean step between neighbouring columns at the tile lines (x = 200, 400) against everywhere.
        double lines = 0, all = 0;
        int lineCount = 0, allCount = 0;
        for (int y = 0; y < p.height; ++y) {
            for (int x = 1; x < p.width; ++x) {
                const double step = std::abs(p.at(x, y) - p.at(x - 1, y));
                all += step;
                ++allCount;
                if (x == 200 || x == 400) lines += step, ++lineCount;
            }
        }
        return (lines / lineCount) / (all / allCount);
    };
    EXPECT_GT(jumpRatio(kExamples + "painted_not_tileable.png"), 5.0);
    EXPECT_LT(jumpRatio(kExamples + "swell.png"), 2.0);
}

TEST(Viewer, BadInputGivesTheDocumentedErrorAndNoWindow) {
    ScratchDir dir;
    writeBytes(dir.file("broken.exr"), {'n', 'o', 'p', 'e'});
    for (const std::string& input : {dir.file("missing.exr"), dir.file("broken.exr")}) {
        const ViewRun run = view({input, "--screenshot", dir.file("shot.png")});
        EXPECT_EQ(run.code, 3) << run.err;
        EXPECT_EQ(run.err.rfind("heightpack-view: error: " + input, 0), 0u) << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    }
    const ViewRun badNormals = view({kExamples + "swell.png", "--normals", dir.file("missing_n.exr"), "--screenshot",
                                     dir.file("shot.png")});
    EXPECT_EQ(badNormals.code, 3);
    EXPECT_EQ(view({kExamples + "swell.png", "--size", "huge"}).code, 2);
    EXPECT_EQ(dir.listing(), (std::vector<std::string>{"broken.exr"}));  // no screenshot written
}

// Each exit code of `heightpack-view --help` that a test can provoke, with its one error line.
TEST(Viewer, ExitCodesAreTheDocumentedOnes) {
    ScratchDir dir;
    auto oneErrorLine = [](const ViewRun& run, const std::string& start) {
        EXPECT_EQ(run.err.rfind("heightpack-view: error: " + start, 0), 0u) << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    };
    const ViewRun help = view({"--help"});
    EXPECT_EQ(help.code, 0);
    for (const char* line : {"  2   usage error", "  3   bad input", "  4   cannot write the screenshot",
                             "  5   no usable OpenGL", "  70  internal"})
        EXPECT_NE(help.out.find(line), std::string::npos) << line << "\n" << help.out;

    // Usage and input errors come before any window: run without a display, so xvfb-run's own failures
    // (it exits 1 to 6 when its server does not start or clean up) cannot stand in for the viewer's codes.
    const auto headless = viewerEnvironment({"DISPLAY", "WAYLAND_DISPLAY"});
    const ViewRun badFlag = runProcess({HEIGHTPACK_VIEW_EXE, kExamples + "swell.png", "--no-such-flag"}, headless);
    EXPECT_EQ(badFlag.code, 2) << badFlag.err;
    EXPECT_NE(badFlag.err.find("heightpack-view --help"), std::string::npos) << badFlag.err;
    // Four maps displace the grid (synth --cascades 4's tiles), and a number per map at most.
    const ViewRun fiveMaps = runProcess({HEIGHTPACK_VIEW_EXE, kExamples + "swell.png", kExamples + "swell.png",
                                         kExamples + "swell.png", kExamples + "swell.png", kExamples + "swell.png"},
                                        headless);
    EXPECT_EQ(fiveMaps.code, 2) << fiveMaps.err;
    oneErrorLine(fiveMaps, "at most 4 height maps displace the grid; 5 were given");
    const ViewRun fiveSizes =
        runProcess({HEIGHTPACK_VIEW_EXE, kExamples + "swell.png", "--tile-size", "64,16,4,1,0.5"}, headless);
    EXPECT_EQ(fiveSizes.code, 2) << fiveSizes.err;
    oneErrorLine(fiveSizes, "--tile-size must be one to four positive lengths");

    writeBytes(dir.file("material.json"), {'{', 'n', 'o'});
    const ViewRun badMaterial =
        runProcess({HEIGHTPACK_VIEW_EXE, dir.file("material.json"), "--screenshot", dir.file("shot.png")}, headless);
    EXPECT_EQ(badMaterial.code, 3) << badMaterial.err;
    oneErrorLine(badMaterial, dir.file("material.json"));

    const std::string unwritable = dir.file("no_such_folder/shot.png");
    // Writing the screenshot needs a frame drawn: under xvfb-run, tried again if xvfb-run itself failed.
    ViewRun cannotWrite;
    for (int attempt = 0; attempt < 3; ++attempt) {
        cannotWrite = view({kExamples + "swell.png", "--screenshot", unwritable, "--size", "64x64"});
        if (cannotWrite.err.find("xvfb-run") == std::string::npos) break;
    }
    EXPECT_EQ(cannotWrite.code, 4) << cannotWrite.err;
    oneErrorLine(cannotWrite, unwritable);

    // No display at all (not under xvfb-run): a window cannot open, so there is no OpenGL to draw with.
    const ViewRun noDisplay = runProcess({HEIGHTPACK_VIEW_EXE, kExamples + "swell.png", "--frames", "1"}, headless);
    EXPECT_EQ(noDisplay.code, 5) << noDisplay.err;
    EXPECT_NE(noDisplay.err.find("heightpack-view: error: cannot start GLFW (is there a display?"), std::string::npos)
        << noDisplay.err;
    // A screenshot without a display draws through EGL; with no EGL vendor either (glvnd finds none where
    // this names no file), nothing can draw.
    auto noEgl = headless;
    noEgl.push_back("__EGL_VENDOR_LIBRARY_FILENAMES=" + dir.file("no_vendor.json"));
    const ViewRun noOpenGl =
        runProcess({HEIGHTPACK_VIEW_EXE, kExamples + "swell.png", "--screenshot", dir.file("shot.png")}, noEgl);
    EXPECT_EQ(noOpenGl.code, 5) << noOpenGl.err;
    oneErrorLine(noOpenGl, "cannot draw without a display: EGL offers neither");
    const ViewRun windowless = runProcess({HEIGHTPACK_VIEW_EXE, kExamples + "swell.png", "--headless"}, headless);
    EXPECT_EQ(windowless.code, 2) << windowless.err;
    oneErrorLine(windowless, "--headless draws only --screenshot, --grid-heights or --bench");
    EXPECT_EQ(dir.listing(), (std::vector<std::string>{"material.json"}));  // no screenshot written
}

TEST(Viewer, BenchReportsGpuTimePerPass) {
    const ViewRun run = view({kExamples + "swell.png", "--bench", "3", "--json", "--two-pass", "--grid", "64",
                              "--segments", "128", "--size", "160x90"});
    ASSERT_EQ(run.code, 0) << run.err;
    const auto j = nlohmann::json::parse(run.out);
    EXPECT_EQ(j["frames"], 3);
    EXPECT_EQ(j["vertices"], 64 * 128);
    EXPECT_GT(j["waterMs"].get<double>(), 0.0);
    EXPECT_GT(j["combineMs"].get<double>(), 0.0);
    EXPECT_TRUE(j["lookups"].empty()) << "only the lookup asked for, unless --compare-lookups";
    // As text: the passes drawn and no others (no combine pass without --two-pass, no tiled view), and the
    // other lookups only when asked to compare them (not run here: each lookup compiles its own shaders,
    // 5-10 s apiece on Mesa's software renderer).
    const ViewRun text = view({kExamples + "swell.png", "--bench", "2", "--grid", "32", "--segments", "64", "--size", "160x90"});
    ASSERT_EQ(text.code, 0) << text.err;
    EXPECT_NE(text.out.find("water pass"), std::string::npos) << text.out;
    EXPECT_EQ(text.out.find("combine pass"), std::string::npos) << text.out;
    EXPECT_EQ(text.out.find("tiled view"), std::string::npos) << text.out;
    EXPECT_EQ(text.out.find("  lookup "), std::string::npos) << text.out;
    const ViewRun alone = view({kExamples + "swell.png", "--compare-lookups", "--size", "160x90"});
    EXPECT_EQ(alone.code, 2) << alone.err;
}

TEST(Viewer, PlaysASequenceFrameByFrame) {
    // synth writes frames, pack packs them as a numbered sequence; at t = f * loop / frames the viewer
    // shows frame f, exactly as if that frame's file were opened alone (same t, so the same scroll).
    ScratchDir dir;
    ASSERT_EQ(runProcess({HEIGHTPACK_EXE, "synth", "--wind", "8m/s", "--tile-size", "64m", "--size", "64", "--frames",
                          "4", "--loop", "8s", "-q", "-o", dir.file("seq.exr")})
                  .code,
              0);
    ASSERT_EQ(runProcess({HEIGHTPACK_EXE, "pack", dir.file("seq.exr"), "-q", "-o", dir.file("packed.exr")}).code, 0);
    const std::vector<std::string> common = {"--view", "height", "--size", "160x120", "--camera", "0,0,60,0,-89.9",
                                             "--tile-size", "64", "--amplitude", "1"};
    for (const auto& [frame, time] : {std::pair<const char*, const char*>{"0000", "0"}, {"0002", "4"}}) {
        auto sequence = common, single = common;
        sequence.insert(sequence.begin(), dir.file("packed.exr"));
        sequence.insert(sequence.end(), {"--time", time});
        single.insert(single.begin(), dir.file(std::string("packed.") + frame + ".exr"));
        single.insert(single.end(), {"--time", time});
        const Difference d = compare(screenshot(dir, "seq.png", sequence), screenshot(dir, "one.png", single), 0);
        EXPECT_EQ(d.max, 0) << "frame " << frame;
    }
    // Between frames the picture is neither frame: the viewer blends.
    auto between = common;
    between.insert(between.begin(), dir.file("packed.exr"));
    between.insert(between.end(), {"--time", "1"});
    auto first = common;
    first.insert(first.begin(), dir.file("packed.0000.exr"));
    first.insert(first.end(), {"--time", "1"});
    EXPECT_GT(compare(screenshot(dir, "between.png", between), screenshot(dir, "first.png", first), 2).max, 2);
}

TEST(Viewer, OpensABuiltMaterialWithItsParameters) {
    // heightpack build writes the textures and material.json; the viewer opening material.json must show
    // what it shows given the same textures and the material's tile sizes and amplitudes by hand.
    ScratchDir dir;
    std::ofstream(dir.file("m.toml")) << "format = 1\nname = \"m\"\n"
                                      << "[[displacement]]\nname = \"swell\"\nsource = \"" << kExamples << "swell.png\"\n"
                                      << "tile_size = 40.0\nscroll = [0.010, 0.004]\namplitude = 2.0\n"
                                      << "[[displacement]]\nname = \"choppy\"\nsource = \"" << kExamples << "choppy.png\"\n"
                                      << "tile_size = 10.0\nscroll = [-0.006, 0.011]\namplitude = 0.3\n"
                                      << "[normals]\nsource = \"" << kExamples << "ripple.png\"\ntile_size = 8.0\nheight = 0.05\n"
                                      << "[[normals.octave]]\ntile_size = 8.0\nscroll = [0.02, 0.01]\n"
                                      << "[[normals.octave]]\ntile_size = 8.0\nscroll = [-0.015, 0.02]\n"
                                      << "[[normals.octave]]\ntile_size = 2.0\nscroll = [0.05, -0.03]\nstrength = 0.5\n"
                                      << "[[normals.octave]]\ntile_size = 2.0\nscroll = [-0.04, -0.05]\nstrength = 0.5\n"
                                      << "[fresnel]\nior = 1.333\n";
    const ProcessResult built = runProcess({HEIGHTPACK_EXE, "build", dir.file("m.toml"), "-q", "-o", dir.file("m")});
    ASSERT_EQ(built.code, 0) << built.err;
    const std::vector<std::string> shot = {"--size", "320x180", "--time", "12.5", "--camera", "0,0,8,30,-10"};
    auto material = shot, byHand = shot, defaults = shot;
    material.insert(material.begin(), dir.file("m/material.json"));
    const std::vector<std::string> files = {dir.file("m/swell.exr"), dir.file("m/choppy.exr"), "--normals",
                                            dir.file("m/normals.exr"), "--fresnel", dir.file("m/fresnel.exr")};
    byHand.insert(byHand.begin(), files.begin(), files.end());
    defaults.insert(defaults.begin(), files.begin(), files.end());
    byHand.insert(byHand.end(), {"--tile-size", "40,10", "--amplitude", "2,0.3"});
    const Picture fromMaterial = screenshot(dir, "material.png", material);
    EXPECT_EQ(compare(fromMaterial, screenshot(dir, "by_hand.png", byHand), 0).max, 0);
    // The material's parameters were used: the viewer's own defaults give another picture.
    EXPECT_GT(compare(fromMaterial, screenshot(dir, "defaults.png", defaults), 2).fractionOver, 0.05);
}

namespace {

// Mean of the three channels over the rows below `top`: the water, below the horizon.
double meanBelow(const Picture& p, int top) {
    double sum = 0.0;
    for (int y = top; y < p.height; ++y)
        for (int x = 0; x < p.width; ++x) sum += p.at(x, y, 0) + p.at(x, y, 1) + p.at(x, y, 2);
    return sum / (3.0 * p.width * std::max(1, p.height - top));
}

}  // namespace

TEST(Viewer, NormalMapsAndFoamTexturesChangeThePicture) {
    // A texture the shader cannot sample (incomplete mip chain) reads as zero and silently drops out of
    // the lighting; these pictures must show both the normal map and the foam texture.
    ScratchDir dir;
    ASSERT_EQ(runProcess({HEIGHTPACK_EXE, "normal", kExamples + "ripple.png", "--tile-size", "8m", "--height", "0.5m",
                          "-q", "-o", dir.file("ripple_n.exr")})
                  .code,
              0);
    const std::vector<std::string> shot = {"--size", "240x135", "--time", "3", "--camera", "0,0,6,30,-15"};
    auto plain = shot, detailed = shot;
    plain.insert(plain.begin(), kExamples + "swell.png");
    detailed.insert(detailed.begin(), {kExamples + "swell.png", "--normals", dir.file("ripple_n.exr")});
    EXPECT_GT(compare(screenshot(dir, "plain.png", plain), screenshot(dir, "normals.png", detailed), 4).fractionOver, 0.1);

    // Foam everywhere (H0 far below the water) against none (far above): the foam texture whitens the sea.
    for (const char* range : {"h0 = -100.0\nhmax = -99.0\n", "h0 = 100.0\nhmax = 101.0\n"}) {
        std::ofstream(dir.file("m.toml")) << "format = 1\nname = \"m\"\n[[displacement]]\nname = \"swell\"\nsource = \""
                                          << kExamples << "swell.png\"\ntile_size = 40.0\n[foam]\n"
                                          << range << "source = \"" << kExamples << "ripple.png\"\n";
        ASSERT_EQ(runProcess({HEIGHTPACK_EXE, "build", dir.file("m.toml"), "-q", "-o", dir.file(range[5] == '-' ? "all" : "none")}).code, 0);
    }
    auto all = shot, none = shot;
    all.insert(all.begin(), dir.file("all/material.json"));
    none.insert(none.begin(), dir.file("none/material.json"));
    const Picture foam = screenshot(dir, "all.png", all), water = screenshot(dir, "none.png", none);
    EXPECT_GT(meanBelow(foam, foam.height / 2), meanBelow(water, water.height / 2) + 40.0);
}

TEST(Viewer, InteractiveWindowRunsWithItsPanel) {
    // The window an artist uses: the frame loop, input polling, the ImGui panel and the reload check,
    // for a few frames, on a built material. An ImGui stack mismatch in the panel aborted here once.
    ScratchDir dir;
    std::ofstream(dir.file("m.toml")) << "format = 1\nname = \"m\"\n[[displacement]]\nname = \"swell\"\nsource = \""
                                      << kExamples << "swell.png\"\ntile_size = 40.0\n";
    ASSERT_EQ(runProcess({HEIGHTPACK_EXE, "build", dir.file("m.toml"), "-q", "-o", dir.file("m")}).code, 0);
    const ViewRun run = view({dir.file("m/material.json"), "--frames", "8", "--size", "480x270"});
    EXPECT_EQ(run.code, 0) << run.err;
    EXPECT_EQ(run.err.find("Assertion"), std::string::npos) << run.err;
}

TEST(Viewer, ChannelChoosesTheHeightOfAColourMapAndErrorsNameTheViewer) {
    ScratchDir dir;
    // The height in green; red and blue hold something else.
    std::vector<float> rgb;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) rgb.insert(rgb.end(), {0.0f, float(0.5 + 0.4 * std::sin(x * 0.3)), 1.0f});
    writeImage(dir.file("colour.png"), 64, 64, 3, rgb, OIIO::TypeDesc::UINT8);
    const ViewRun refused = view({dir.file("colour.png"), "--screenshot", dir.file("shot.png")});
    EXPECT_EQ(refused.code, 3);
    EXPECT_EQ(refused.err.rfind("heightpack-view: error: ", 0), 0u) << refused.err;
    EXPECT_NE(refused.err.find("--channel"), std::string::npos) << refused.err;  // the hint names an option it has
    const ViewRun usage = view({dir.file("colour.png"), "--size", "huge"});
    EXPECT_EQ(usage.err.rfind("heightpack-view: error: ", 0), 0u) << usage.err;
    const ViewRun chosen = view({dir.file("colour.png"), "--channel", "g", "--screenshot", dir.file("shot.png")});
    EXPECT_EQ(chosen.code, 0) << chosen.err;
}

TEST(Viewer, ExplosionFollowsTheChapterAndIsSmoothAtItsCentre) {
    // Looking straight down at an explosion on flat water, height as grey: the grey at distance r from the
    // centre is the chapter's I(r) = I0 sin(k r + w t) exp(-b t) / r^2 with r smoothed as sqrt(r^2 + 1),
    // computed here. Clamping r at 1 m, as before, made a flat disc of one grey with a kink at its rim.
    ScratchDir dir;
    const double k = 1.2, w = -6.0, b = 0.35, t = 0.5, i0 = 1.0, camera = 6.0;
    auto height = [&](double r) {
        const double s2 = r * r + 1.0, s = std::sqrt(s2);
        return i0 * std::sin(k * s + w * t) * std::exp(-b * t) / s2;
    };
    const int size = 401;
    const Picture p = screenshot(dir, "explosion.png",
                                 {kExamples + "swell.png", "--amplitude", "0", "--view", "height", "--size", "401x401",
                                  "--time", "0.5", "--explosion", "0,0,0,1", "--camera", "0,0,6,0,-89.99"});
    ASSERT_EQ(p.width, size);
    // Pixel p from the centre sees the water at r = p * tan(30 deg) / 200 * (camera - h(r)).
    const double perPixel = std::tan(30.0 * 3.14159265358979 / 180.0) / ((size - 1) / 2.0);
    // From 8 px: the radial grid leaves a hole of radius r0 (10 cm, 6 px here) under the camera.
    for (int offset : {8, 12, 20, 30, 40, 60, 80}) {
        double r = offset * perPixel * camera;
        for (int i = 0; i < 20; ++i) r = offset * perPixel * (camera - height(r));
        const double expected = 255.0 * (0.1 + 0.8 * (height(r) + 2.0) / 4.0);
        for (const auto& [x, y] : std::vector<std::pair<int, int>>{{200 + offset, 200}, {200 - offset, 200}, {200, 200 + offset}}) {
            EXPECT_NEAR(p.at(x, y), expected, 2.5) << "at " << offset << " px, r = " << r << " m";
        }
    }
}
