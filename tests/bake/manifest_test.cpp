// The manifest parser, called directly: good manifests give the settings they say (and the defaults
// they do not), bad ones give BadInput naming FILE:LINE and the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "heightpack/bake/manifest.hpp"

#include "support/test_support.hpp"

namespace heightpack {
namespace {

struct ManifestDir {
    test::ScratchDir dir;
    ManifestDir() {
        test::writeImage(dir.file("a.png"), test::randomImage(8, 8, 1), OIIO::TypeDesc::UINT16);
        test::writeImage(dir.file("b.png"), test::randomImage(8, 8, 2), OIIO::TypeDesc::UINT8);
    }
    Result<Manifest> parse(const std::string& text) const {
        const std::string path = dir.file("m.toml");
        std::ofstream(path, std::ios::binary) << text;
        return parseManifest(path);
    }
};

constexpr const char* kGood = R"(format = 1
name = "sea"
threshold = 3.5

[defaults]
wrap = "clamp"
filter = "box"

[[displacement]]
name = "swell"
source = "a.png"
tile_size = 64.0
height_scale = 2.0
height_offset = -1.0

[[displacement]]
name = "chop"
source = "b.png"
output = "sub/chop.exr"
tile_size = 16.0
filter = "lanczos3"
wrap = "periodic"

[normals]
source = "a.png"
tile_size = 8.0
height = 0.5
kernel = "scharr"

[fresnel]
ior = 1.5
size = 64
)";

TEST(Manifest, AGoodManifestGivesWhatItSaysAndTheDefaultsItDoesNot) {
    ManifestDir d;
    auto m = d.parse(kGood);
    ASSERT_TRUE(m) << m.error().path << ": " << m.error().what;
    EXPECT_EQ(m->name, "sea");
    EXPECT_EQ(m->threshold, 3.5);
    ASSERT_EQ(m->displacement.size(), 2u);
    const DisplacementAsset& swell = m->displacement[0];
    EXPECT_EQ(swell.output, "swell.exr");
    EXPECT_EQ(swell.settings.wrap, Wrap::Clamp);      // from [defaults]
    EXPECT_EQ(swell.settings.filter, Filter::Box);
    EXPECT_EQ(swell.settings.storage.exrCompression, Compression::Zip);  // the default of defaults
    EXPECT_FALSE(swell.mustTile) << "a clamped map need not tile";
    EXPECT_EQ(swell.layer.heightScale, 2.0);
    EXPECT_EQ(swell.layer.heightOffset, -1.0);
    EXPECT_EQ(swell.layer.tileSize, 64.0);
    ASSERT_EQ(swell.frames.size(), 1u);
    EXPECT_TRUE(std::filesystem::equivalent(swell.frames[0], d.dir.file("a.png")));
    EXPECT_EQ(swell.line, 9);
    const DisplacementAsset& chop = m->displacement[1];
    EXPECT_EQ(chop.output, "sub/chop.exr");
    EXPECT_EQ(chop.settings.filter, Filter::Lanczos3);  // its own table wins
    EXPECT_EQ(chop.settings.wrap, Wrap::Periodic);
    EXPECT_TRUE(chop.mustTile) << "a periodic map must tile unless it says otherwise";
    ASSERT_TRUE(m->normals);
    EXPECT_EQ(m->normals->kernel, SlopeKernel::Scharr);
    EXPECT_EQ(m->normals->layer.heightRange, 0.5);
    EXPECT_EQ(m->normals->output, "normals.exr");
    ASSERT_TRUE(m->fresnel);
    EXPECT_EQ(m->fresnel->options.ior, 1.5);
    EXPECT_EQ(m->fresnel->options.size, 64);
    EXPECT_EQ(m->fresnel->options.model, FresnelModel::Exact);
    EXPECT_FALSE(m->foam);
}

// kGood with the text `from` replaced by `to`.
std::string goodWith(const std::string& from, const std::string& to) {
    std::string text = kGood;
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
}

TEST(Manifest, BadManifestsAreBadInputNamingTheLineAndTheKey) {
    ManifestDir d;
    struct Case {
        std::string text;
        int line;          // 0: any line
        std::string word;  // the message (or hint) names it
    };
    const Case cases[] = {
        {goodWith("format = 1", "format = 2"), 1, "format"},
        {goodWith("format = 1\n", ""), 0, "format"},
        {goodWith("tile_size = 64.0", "tile_sise = 64.0"), 12, "tile_sise"},
        {goodWith("tile_size = 64.0", "tile_size = \"big\""), 12, "tile_size"},
        {goodWith("tile_size = 64.0", "tile_size = -1.0"), 12, "tile_size"},
        {goodWith("wrap = \"clamp\"", "wrap = \"mirror\""), 6, "wrap"},
        {goodWith("source = \"b.png\"", "source = \"missing.png\""), 0, "missing.png"},
        {goodWith("output = \"sub/chop.exr\"", "output = \"../chop.exr\""), 0, "output"},
        {goodWith("output = \"sub/chop.exr\"", "output = \"swell.exr\""), 0, "swell.exr"},
        {goodWith("name = \"sea\"", "name = \"a/b\""), 2, "name"},
        {goodWith("ior = 1.5", "ior = 9.0"), 0, "ior"},
        {"format = 1\nname = \"x\"\n[[displacement]\n", 0, ""},  // not TOML
    };
    for (const Case& c : cases) {
        auto m = d.parse(c.text);
        ASSERT_FALSE(m) << c.text;
        const Error& e = m.error();
        EXPECT_EQ(e.kind, ErrorKind::BadInput) << c.text;
        const std::string where = d.dir.file("m.toml") + ":";
        EXPECT_EQ(e.path.rfind(where, 0), 0u) << e.path << " should be FILE:LINE";
        if (c.line > 0) {
            EXPECT_EQ(e.path, where + std::to_string(c.line)) << e.what;
        }
        EXPECT_NE((e.what + " " + e.hint).find(c.word), std::string::npos) << e.what << " (" << e.hint << ")";
    }
    auto missing = parseManifest(d.dir.file("none.toml"));
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().kind, ErrorKind::BadInput);
}

// A misspelt key leaves the key it meant missing, and may sit in a table read after one with a key
// missing for no such reason: either way the misspelling is what is named, with the key it was meant to
// be, in every table of a manifest. Nothing is named missing while a key is unknown.
TEST(Manifest, UnknownKeysAreNamedBeforeMissingOnesInEveryTable) {
    ManifestDir d;
    const std::string head = "format = 1\nname = \"sea\"\n";
    const std::string displacement = "\n[[displacement]]\nname = \"swell\"\nsource = \"a.png\"\ntile_size = 64.0\n";
    const std::string noTileSize = "\n[[displacement]]\nname = \"swell\"\nsource = \"a.png\"\n";
    struct Case {
        std::string text;
        std::string misspelt;  // the line holding it is the error's
        std::string key;       // as the message names it
        std::string meant;     // the suggestion ("" for none)
    };
    const Case cases[] = {
        // The top level: the name it meant, and the array of tables it meant.
        {"format = 1\nnme = \"sea\"\n" + displacement, "nme", "nme", "name"},
        {head + "\n[[displacment]]\nname = \"swell\"\nsource = \"a.png\"\ntile_size = 64.0\n", "[[displacment]]",
         "displacment", "displacement"},
        // [defaults], read after the top level's missing name.
        {"format = 1\n\n[defaults]\nfiltr = \"box\"\n" + displacement, "filtr", "defaults.filtr", "filter"},
        // The issue's manifest: source misspelt, so no source and no synth table.
        {head + "\n[[displacement]]\nname = \"swell\"\nsorce = \"swell.png\"\ntile_size = 64.0\n", "sorce",
         "displacement[0].sorce", "source"},
        // Too far from any key for a suggestion, yet still named first.
        {head + noTileSize + "size_of_tile = 64.0\n", "size_of_tile", "displacement[0].size_of_tile", ""},
        // [displacement.synth] without its wind, and a misspelt seed.
        {head + noTileSize.substr(0, noTileSize.find("source")) + "tile_size = 64.0\n\n[displacement.synth]\nsed = 3\n",
         "sed", "displacement[0].synth.sed", "seed"},
        // [normals] without its height, and a misspelt kernel.
        {head + displacement + "\n[normals]\nsource = \"a.png\"\ntile_size = 8.0\nkernal = \"scharr\"\n", "kernal",
         "normals.kernal", "kernel"},
        // [[normals.octave]] without its tile_size, and a misspelt strength.
        {head + displacement + "\n[normals]\nsource = \"a.png\"\ntile_size = 8.0\nheight = 0.5\n\n[[normals.octave]]\n"
                               "strenght = 1.0\n",
         "strenght", "normals.octave[0].strenght", "strength"},
        // [fresnel] (no key is required there) after a displacement map missing its tile_size.
        {head + noTileSize + "\n[fresnel]\niro = 1.5\n", "iro", "fresnel.iro", "ior"},
        // [foam] without its hmax, and a misspelt tile_size.
        {head + displacement + "\n[foam]\nh0 = 1.0\ntilesize = 4.0\n", "tilesize", "foam.tilesize", "tile_size"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.text);
        auto m = d.parse(c.text);
        ASSERT_FALSE(m);
        const Error& e = m.error();
        const size_t at = c.text.find(c.misspelt);
        ASSERT_NE(at, std::string::npos);
        const int line = 1 + static_cast<int>(std::count(c.text.begin(), c.text.begin() + at, '\n'));
        EXPECT_EQ(e.path, d.dir.file("m.toml") + ":" + std::to_string(line)) << e.what;
        EXPECT_EQ(e.what.rfind("unknown key '" + c.key + "'", 0), 0u) << e.what;
        EXPECT_EQ(e.what.find("missing"), std::string::npos) << e.what;
        // The suggestion leads the hint; a shell words where the reference is (Fix::ManifestReference).
        EXPECT_EQ(e.fix, Fix::ManifestReference);
        const std::string suggestion = c.meant.empty() ? "" : "did you mean '" + c.meant + "'?";
        EXPECT_EQ(e.fixArgs, std::vector<std::string>{suggestion});
        EXPECT_EQ(e.hint.rfind(suggestion, 0), 0u) << e.hint;
        if (c.meant.empty()) {
            EXPECT_EQ(e.hint.find("did you mean"), std::string::npos) << e.hint;
        }
    }

    // A manifest of another format has other keys: it is told its format first.
    auto newer = d.parse("format = 2\nname = \"sea\"\nnew_key = 1\n" + displacement);
    ASSERT_FALSE(newer);
    EXPECT_NE(newer.error().what.find("reads format 1"), std::string::npos) << newer.error().what;
    // With every key known, a missing one is named, pointing at the reference.
    auto missing = d.parse(head + noTileSize);
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().what, "missing key 'displacement[0].tile_size'");
    EXPECT_EQ(missing.error().fix, Fix::ManifestReference);
}

}  // namespace
}  // namespace heightpack
