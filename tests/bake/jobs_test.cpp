// The per-map jobs and the multi-material build, called as a library on small generated maps; what they
// write is read back and compared with independent computations (neighbours found by brute force, the
// slope of a plane, Schlick's formula), never with saved outputs.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "heightpack/bake/build/build_materials.hpp"
#include "heightpack/bake/fresnel_job.hpp"
#include "heightpack/bake/normal_job.hpp"
#include "heightpack/bake/pack_job.hpp"
#include "heightpack/bake/synth_job.hpp"
#include "heightpack/bake/tile_job.hpp"
#include "heightpack/io/info.hpp"

#include "support/test_support.hpp"

namespace heightpack {
namespace {

int channelIndex(const TextureFile& t, const std::string& name) {
    for (size_t c = 0; c < t.channelNames.size(); ++c)
        if (t.channelNames[c] == name) return static_cast<int>(c);
    ADD_FAILURE() << "no channel " << name;
    return 0;
}

// Texel (i, j) of level 0 holds H(i,j), H(i+1,j), H(i,j+1), H(i+1,j+1) of the painted map, indices
// wrapped or clamped, each stored as offset + scale * value.
TEST(PackJob, LevelZeroHoldsEveryTexelsFourNeighbours) {
    test::ScratchDir dir;
    const int w = 16, h = 8;
    const Image painted = test::randomImage(w, h, 7);
    test::writeImage(dir.file("in.exr"), painted, OIIO::TypeDesc::FLOAT);
    for (Wrap wrap : {Wrap::Periodic, Wrap::Clamp}) {
        PackOptions o;
        o.mip.wrap = wrap;
        o.scale = 2.0f;
        o.offset = -0.25f;
        auto r = packHeightMap(dir.file("in.exr"), dir.file("out.exr"), o);
        ASSERT_TRUE(r) << r.error().what;
        auto t = readTextureFile(dir.file("out.exr"));
        ASSERT_TRUE(t) << t.error().what;
        ASSERT_EQ(t->levels.size(), 5u) << "16x8 has levels 16, 8, 4, 2, 1 wide";
        EXPECT_EQ(t->levels.back().width, 1);
        EXPECT_EQ(t->levels.back().height, 1);
        const Image& level = t->levels[0];
        ASSERT_EQ(level.width, w);
        ASSERT_EQ(level.height, h);
        auto next = [&](int i, int n) { return wrap == Wrap::Periodic ? (i + 1) % n : std::min(i + 1, n - 1); };
        auto stored = [&](int x, int y) { return -0.25f + 2.0f * painted.at(x, y); };
        const int R = channelIndex(*t, "R"), G = channelIndex(*t, "G"), B = channelIndex(*t, "B"), A = channelIndex(*t, "A");
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                EXPECT_FLOAT_EQ(level.at(x, y, R), stored(x, y));
                EXPECT_FLOAT_EQ(level.at(x, y, G), stored(next(x, w), y)) << x << "," << y;
                EXPECT_FLOAT_EQ(level.at(x, y, B), stored(x, next(y, h))) << x << "," << y;
                EXPECT_FLOAT_EQ(level.at(x, y, A), stored(next(x, w), next(y, h))) << x << "," << y;
            }
        // Every coarser level is packed from its own heights (its R channel) the same way.
        for (size_t l = 1; l < t->levels.size(); ++l) {
            const Image& c = t->levels[l];
            for (int y = 0; y < c.height; ++y)
                for (int x = 0; x < c.width; ++x) {
                    EXPECT_EQ(c.at(x, y, G), c.at(next(x, c.width), y, R)) << "level " << l;
                    EXPECT_EQ(c.at(x, y, A), c.at(next(x, c.width), next(y, c.height), R)) << "level " << l;
                }
        }
    }
}

TEST(PackJob, APlainChainHoldsTheHeightsAlone) {
    test::ScratchDir dir;
    const Image painted = test::randomImage(8, 8, 3);
    test::writeImage(dir.file("in.exr"), painted, OIIO::TypeDesc::FLOAT);
    PackOptions o;
    o.layout = Layout::Plain;
    ASSERT_TRUE(packHeightMap(dir.file("in.exr"), dir.file("plain.exr"), o));
    auto t = readTextureFile(dir.file("plain.exr"));
    ASSERT_TRUE(t);
    ASSERT_EQ(t->levels[0].channels, 1);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) EXPECT_FLOAT_EQ(t->levels[0].at(x, y), painted.at(x, y));
}

// A plane rising along +x by s metres per metre has the unit normal (-s, 0, 1) / sqrt(1 + s^2).
TEST(PackJob, OptionsThatCannotGoTogetherAreJudgedByTheLibraryBeforeTheInputIsRead) {
    // The input does not exist: an options error must come first, as InconsistentOptions (a usage error
    // in every shell), naming the output the user gave and the remedy for the shell to word.
    test::ScratchDir dir;
    const std::string missing = dir.file("missing.png");
    struct Case {
        const char* name;
        std::function<void(PackOptions&)> set;
        std::string output, named;
        Fix fix;
    };
    const std::vector<Case> cases = {
        {"a plain twin of a plain layout",
         [&](PackOptions& o) { o.layout = Layout::Plain; o.plainOutput = dir.file("p.exr"); }, dir.file("o.exr"),
         dir.file("p.exr"), Fix::OnePlainChain},
    };
    for (const Case& c : cases) {
        PackOptions options;
        c.set(options);
        const auto report = packHeightMap(missing, c.output, options);
        ASSERT_FALSE(report) << c.name;
        EXPECT_EQ(report.error().kind, ErrorKind::InconsistentOptions) << c.name << ": " << report.error().what;
        EXPECT_EQ(report.error().path, c.named) << c.name;
        EXPECT_EQ(report.error().fix, c.fix) << c.name;
    }
    // Displacement and foam go with every container (a KTX2's or DDS's further array layers): these go on
    // to read the input, and fail on it.
    for (const auto& [output, twin] : {std::pair{"o.exr", ""}, std::pair{"o.ktx2", ""}, std::pair{"o.exr", "p.dds"},
                                       std::pair{"o.dds", "p.ktx2"}}) {
        PackOptions options;
        options.shift = true;
        options.foam = true;
        if (*twin) options.plainOutput = dir.file(twin);
        const auto report = packHeightMap(missing, dir.file(output), options);
        ASSERT_FALSE(report) << output;
        EXPECT_EQ(report.error().kind, ErrorKind::BadInput) << output << ": " << report.error().what;
    }
}

TEST(NormalJob, OptionsThatCannotGoTogetherAreJudgedBeforeTheInputIsRead) {
    test::ScratchDir dir;
    const std::string missing = dir.file("missing.png");
    struct Case {
        const char* name;
        Layout layout;
        NormalFormat format;
        NormalAlpha alpha;
        std::string output;
        Fix fix;
        std::string arg;
    };
    const std::vector<Case> cases = {
        {"xy into a PNG", Layout::Xy, NormalFormat::Png8, NormalAlpha::None, dir.file("n.png"), Fix::RgbNormalsInPng, ""},
        {"xy with height in alpha", Layout::Xy, NormalFormat::Exr, NormalAlpha::Height, dir.file("n.exr"), Fix::RgbNormalsForAlpha,
         ""},
        {"slope variance into a PNG", Layout::Rgb, NormalFormat::Png8, NormalAlpha::SlopeVariance, dir.file("n.png"),
         Fix::VarianceNeedsLevels, ""},
    };
    for (const Case& c : cases) {
        NormalJobOptions options;
        options.normal.tileWidth = 8.0;
        options.normal.heightRange = 1.0;
        options.layout = c.layout;
        options.format = c.format;
        options.normal.alpha = c.alpha;
        const auto report = makeNormalMap(missing, c.output, options);
        ASSERT_FALSE(report) << c.name;
        EXPECT_EQ(report.error().kind, ErrorKind::InconsistentOptions) << c.name << ": " << report.error().what;
        EXPECT_EQ(report.error().fix, c.fix) << c.name;
        EXPECT_EQ(report.error().fixArgs.empty() ? "" : report.error().fixArgs[0], c.arg) << c.name;
    }
}

TEST(SynthJob, ShiftOrFoamIntoAFileThatIsNoExrIsAnOptionsError) {
    test::ScratchDir dir;
    for (const auto& [foam, named] : {std::pair{false, "shift"}, std::pair{true, "foam"}}) {
        SynthOptions options;
        options.spectrum.size = 16;
        options.spectrum.windSpeed = 9.0;
        options.spectrum.tileSize = 32.0;
        options.shift = true;
        options.foam = foam;
        const auto report = synthesise(dir.file("sea.png"), options);
        ASSERT_FALSE(report) << named;
        EXPECT_EQ(report.error().kind, ErrorKind::InconsistentOptions) << named;
        EXPECT_EQ(report.error().fix, Fix::CompanionsNeedExr) << named;
        ASSERT_EQ(report.error().fixArgs.size(), 1u);
        EXPECT_EQ(report.error().fixArgs[0], named);
        EXPECT_FALSE(std::filesystem::exists(dir.file("sea.png")));
    }
}

TEST(TileJob, MethodNamesAreTheDocumentedOnesAndRoundTrip) {
    EXPECT_EQ(allNames<TileMethod>(), (std::vector<std::string>{"periodic", "quilt", "moisan", "crossfade", "mirror"}));
    for (const EnumName<TileMethod>& e : NameTable<TileMethod>::entries) EXPECT_EQ(parseName<TileMethod>(e.name), e.value);
}

TEST(TileJob, AMapThatTilesKeepsItsSixteenBitSamplesInAnotherFormat) {
    // A periodic sum of cosines in 16-bit samples: it tiles, so tile copies its heights into the other
    // format, in the same type and bit for bit (a float holds k/65535 only to 0.004 steps, which once read
    // as "not whole steps" made the copy float, or refused it into a PNG).
    test::ScratchDir dir;
    const int n = 64;
    const Image map = test::makeImage(n, n, [&](int x, int y) {
        const double v = 0.5 + 0.2 * std::cos(2 * std::numbers::pi * x / n) + 0.2 * std::sin(2 * std::numbers::pi * 2 * y / n);
        return static_cast<float>(std::round(v * 65535) / 65535);
    });
    test::writeImage(dir.file("in.png"), map, OIIO::TypeDesc::UINT16);
    test::writeImage(dir.file("in.tif"), map, OIIO::TypeDesc::UINT16);
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"in.png", "out.tif"}, {"in.tif", "out.png"}}) {
        auto report = tileFile(dir.file(from), dir.file(to), TileOptions{});
        ASSERT_TRUE(report) << report.error().what;
        EXPECT_TRUE(report->alreadyTiled) << from;
        EXPECT_EQ(report->bits, 16) << from << " -> " << to;
        EXPECT_FALSE(report->widened) << from << " -> " << to;
        auto in = OIIO::ImageInput::open(dir.file(to));
        ASSERT_TRUE(in) << to;
        EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT16) << to;
        std::vector<uint16_t> samples(size_t(n) * n);
        ASSERT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT16, samples.data()));
        for (size_t i = 0; i < samples.size(); ++i)
            ASSERT_EQ(samples[i], static_cast<uint16_t>(std::lround(map.pixels[i] * 65535.0))) << to << " at " << i;
    }
}

TEST(TileJob, AMapWhoseFirstSeedFailsIsQuiltedBeforeTheOtherSeeds) {
    // A game's snowy ice texture (bright crusts on blue, a painted line along two edges: not a Gaussian
    // field). The re-synthesis' first seed breaks there at the finest level; the quilt's best match comes
    // next, before the other seeds and bands (which break as well on such maps, and cost as much again
    // each). The stages the progress names say which candidates were made, in order.
    test::ScratchDir dir;
    TileOptions options;
    options.load.channel = ChannelSelect::Luma;
    std::vector<std::string> stages;
    options.progress = [&](std::string_view stage, double) {
        if (stages.empty() || stages.back() != stage) stages.emplace_back(stage);
    };
    const std::string ice = std::string(HEIGHTPACK_SOURCE_DIR) + "/tests/corpus/etr_snowy_ice03.png";
    auto report = tileFile(ice, dir.file("ice.exr"), options);
    ASSERT_TRUE(report) << report.error().what;
    ASSERT_TRUE(report->written);
    EXPECT_EQ(report->methodUsed, "quilt");
    EXPECT_EQ(report->match, 1);
    const std::vector<std::string> tried(std::find(stages.begin(), stages.end(), "tile: re-synthesis 1 of 4"), stages.end());
    ASSERT_GE(tried.size(), 2u);
    EXPECT_EQ(tried[1], "tile: quilt 1 of 3");
    EXPECT_EQ(std::count(stages.begin(), stages.end(), "tile: re-synthesis 2 of 4"), 0);
}

TEST(NormalJob, APlaneGivesTheNormalOfItsSlope) {
    test::ScratchDir dir;
    const int n = 16;
    test::writeImage(dir.file("ramp.exr"), test::makeImage(n, n, [&](int x, int) { return float(x) / n; }),
                     OIIO::TypeDesc::FLOAT);
    NormalJobOptions o;
    o.normal.wrap = Wrap::Clamp;
    o.normal.tileWidth = 4.0;
    o.normal.heightRange = 2.0;  // the map rises 2 m over 4 m: s = 0.5 (per texel: 2/16 over 4/16)
    auto r = makeNormalMap(dir.file("ramp.exr"), dir.file("n.exr"), o);
    ASSERT_TRUE(r) << r.error().what;
    auto t = readTextureFile(dir.file("n.exr"));
    ASSERT_TRUE(t) << t.error().what;
    const double s = 0.5, len = std::sqrt(1 + s * s);
    const Image& level = t->levels[0];
    const int X = channelIndex(*t, "R"), Y = channelIndex(*t, "G"), Z = channelIndex(*t, "B");
    for (int y = 0; y < n; ++y)
        for (int x = 1; x < n - 1; ++x) {
            EXPECT_NEAR(level.at(x, y, X), -s / len, 1e-5) << x << "," << y;
            EXPECT_NEAR(level.at(x, y, Y), 0.0, 1e-5);
            EXPECT_NEAR(level.at(x, y, Z), 1.0 / len, 1e-5);
        }
}

// Schlick's reflectance at each texel centre u = N.V, and the water colour mixed by it.
TEST(FresnelJob, TheRampHoldsSchlicksReflectanceAtTexelCentres) {
    test::ScratchDir dir;
    FresnelOptions o;
    o.model = FresnelModel::Schlick;
    o.size = 32;
    o.ior = 1.5;
    ASSERT_TRUE(writeFresnelRamp(dir.file("f.exr"), o, RampFormat::Exr, "test"));
    auto t = readTextureFile(dir.file("f.exr"));
    ASSERT_TRUE(t) << t.error().what;
    const Image& level = t->levels[0];
    ASSERT_EQ(level.width, 32);
    const int A = channelIndex(*t, "A");
    const double r0 = std::pow((1.5 - 1) / (1.5 + 1), 2);
    for (int i = 0; i < 32; ++i) {
        const double cosTheta = (i + 0.5) / 32;
        EXPECT_NEAR(level.at(i, 0, A), r0 + (1 - r0) * std::pow(1 - cosTheta, 5), 1e-6) << i;
    }
}

// The library's multi-material build: the depfile lists every manifest and source, the stamp is
// written, a second build makes nothing, and two materials of one name are refused.
TEST(BuildMaterials, BuildsEveryMaterialThenTheDepfileAndStamp) {
    test::ScratchDir dir;
    test::writeImage(dir.file("a.exr"), test::makeImage(8, 8, [](int x, int y) { return 0.5f + 0.01f * float((x * 3 + y) % 4); }),
                     OIIO::TypeDesc::FLOAT);
    auto manifest = [&](const std::string& file, const std::string& name) {
        std::ofstream(dir.file(file)) << "format = 1\nname = \"" << name
                                      << "\"\n[defaults]\nwrap = \"clamp\"\n[[displacement]]\nname = \"d\"\n"
                                         "source = \"a.exr\"\ntile_size = 4.0\n";
    };
    manifest("one.toml", "one");
    manifest("two.toml", "two");
    auto manifests = parseManifests({dir.file("one.toml"), dir.file("two.toml")});
    ASSERT_TRUE(manifests) << manifests.error().what;
    BuildOptions options;
    options.outputDir = dir.file("out");
    options.version = "test";
    MaterialsOptions files;
    files.depfile = dir.file("out/build.d");
    files.stamp = dir.file("out/stamp");
    int built = 0;
    files.onBuilt = [&](const BuildReport& r, double) { built += r.rebuilt(); };
    auto r = buildMaterials(*manifests, options, files);
    ASSERT_TRUE(r) << r.error().what;
    EXPECT_TRUE(r->checksPassed);
    ASSERT_EQ(r->materials.size(), 2u);
    EXPECT_EQ(built, 2);
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/one/d.exr")));
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/two/material.json")));
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/stamp")));
    std::ifstream in(dir.file("out/build.d"));
    const std::string depfile((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(depfile.rfind(dir.file("out/stamp") + ":", 0), 0u) << depfile;
    for (const char* f : {"one.toml", "two.toml", "a.exr"})
        EXPECT_NE(depfile.find(std::filesystem::absolute(dir.file(f)).lexically_normal().string()), std::string::npos) << f;

    built = 0;
    auto again = buildMaterials(*manifests, options, files);
    ASSERT_TRUE(again);
    EXPECT_EQ(built, 0) << "nothing changed, nothing is made";
    for (const BuildReport& m : again->materials) EXPECT_EQ(m.upToDate(), 1);

    manifest("two.toml", "one");
    auto same = parseManifests({dir.file("one.toml"), dir.file("two.toml")});
    ASSERT_FALSE(same);
    EXPECT_EQ(same.error().kind, ErrorKind::BadInput);
    std::vector<Manifest> twice{(*manifests)[0], (*manifests)[0]};
    EXPECT_FALSE(buildMaterials(twice, options, files)) << "the library refuses them too";
}

}  // namespace
}  // namespace heightpack
