// The manifest parser, called directly: good manifests give the settings they say (and the defaults
// they do not), bad ones give BadInput naming FILE:LINE and the key.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace heightpack
