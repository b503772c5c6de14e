// The manifest's container and pixel_type keys (issue 14): per asset or in [defaults], each output in
// the container named (its file name follows), unknown values and contradictions refused in the
// manifest's error style, and a build whose material.json names the files written and that rebuilds
// when the pixel type changes.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "heightpack/bake/build/build_job.hpp"
#include "heightpack/bake/manifest.hpp"
#include "heightpack/bake/material.hpp"
#include "heightpack/io/gpu_texture.hpp"

#include "support/test_support.hpp"

namespace heightpack {
namespace {

struct ContainerManifestDir {
    test::ScratchDir dir;
    ContainerManifestDir() {
        test::writeImage(dir.file("a.png"), test::makeImage(16, 16, [](int x, int y) {
                             return float(0.5 + 0.3 * std::sin(x * 0.3927) * std::cos(y * 0.3927));
                         }),
                         OIIO::TypeDesc::UINT16);
    }
    std::string write(const std::string& text) const {
        std::ofstream(dir.file("m.toml"), std::ios::binary) << text;
        return dir.file("m.toml");
    }
    Result<Manifest> parse(const std::string& text) const { return parseManifest(write(text)); }
};

const std::string kHead = "format = 1\nname = \"sea\"\n";
const std::string kSwell = "[[displacement]]\nname = \"swell\"\nsource = \"a.png\"\ntile_size = 64.0\n";

TEST(ManifestContainers, DefaultsAndOwnTablesChooseContainerAndPixelType) {
    ContainerManifestDir d;
    auto m = d.parse(kHead + "[defaults]\ncontainer = \"ktx2\"\npixel_type = \"auto\"\ntolerance = 0.001\n" + kSwell +
                     "[[displacement]]\nname = \"chop\"\nsource = \"a.png\"\ntile_size = 8.0\ncontainer = \"dds\"\n"
                     "pixel_type = \"half\"\n"
                     "[[displacement]]\nname = \"third\"\nsource = \"a.png\"\ntile_size = 8.0\ntolerance = 0.01\n"
                     "[normals]\nsource = \"a.png\"\ntile_size = 8.0\nheight = 0.5\npixel_type = \"uint16\"\n"
                     "[fresnel]\noutput = \"ramp.dds\"\n");
    ASSERT_TRUE(m) << m.error().path << ": " << m.error().what;
    const MapSettings& swell = m->displacement[0].settings;
    EXPECT_EQ(m->displacement[0].output, "swell.ktx2");
    EXPECT_EQ(swell.container, Container::Ktx2);
    EXPECT_EQ(swell.storage.tolerance, 0.001);
    const MapSettings& chop = m->displacement[1].settings;
    EXPECT_EQ(m->displacement[1].output, "chop.dds");
    EXPECT_EQ(chop.storage.pixelType, PixelType::Half);
    EXPECT_EQ(chop.storage.tolerance, 0.0) << "a type of its own drops the inherited auto";
    EXPECT_EQ(m->displacement[2].settings.storage.tolerance, 0.01) << "auto inherited, its own tolerance";
    EXPECT_EQ(m->normals->output, "normals.ktx2");
    EXPECT_EQ(m->normals->settings.storage.pixelType, PixelType::Uint16);
    EXPECT_EQ(m->fresnel->output, "ramp.dds") << "an output's extension names its container";
    EXPECT_EQ(m->fresnel->pixelType, PixelType::Float) << "auto is for mip chains; a ramp under it stays float";
}

TEST(ManifestContainers, UnknownValuesAndContradictionsAreManifestErrors) {
    ContainerManifestDir d;
    struct Case {
        std::string text;
        std::string words;  // the message and hint name them
    };
    const Case cases[] = {
        {kHead + "[defaults]\ncontainer = \"png\"\n" + kSwell, "'defaults.container' is 'png', but must be one of: exr, ktx2, dds"},
        {kHead + kSwell + "pixel_type = \"int8\"\n", "float, half, uint16, bc4, bc5, astc-4x4, astc-6x6, astc-8x8, astc-hdr-4x4, astc-hdr-6x6, astc-hdr-8x8, auto"},
        {kHead + kSwell + "pixel_type = \"auto\"\n", "needs a tolerance"},
        {kHead + kSwell + "tolerance = 0.01\n", "pixel_type is not \"auto\""},
        {kHead + kSwell + "pixel_type = \"auto\"\ntolerance = -1.0\n", "tolerance"},
        {kHead + kSwell + "container = \"dds\"\noutput = \"swell.ktx2\"\n", "container is \"dds\""},
        {kHead + kSwell + "output = \"swell.png\"\n", ".exr, .ktx2 or .dds"},
        {kHead + kSwell + "pixel_type = \"uint16\"\n", "no 16-bit normalised"},
        {kHead + "[defaults]\npixel_type = \"uint16\"\n" + kSwell, "from [defaults]"},
        {kHead + kSwell + "[fresnel]\npixel_type = \"auto\"\n", "float, half, uint16"},
    };
    for (const Case& c : cases) {
        auto m = d.parse(c.text);
        ASSERT_FALSE(m) << c.text;
        EXPECT_EQ(m.error().kind, ErrorKind::BadInput);
        EXPECT_EQ(m.error().path.rfind(d.dir.file("m.toml") + ":", 0), 0u) << m.error().path;
        EXPECT_NE((m.error().what + " " + m.error().hint).find(c.words), std::string::npos)
            << m.error().what << " (" << m.error().hint << ")";
    }
}

TEST(ManifestContainers, MaterialJsonNamesTheFilesWrittenAndAPixelTypeChangeRebuilds) {
    ContainerManifestDir d;
    auto build = [&](const std::string& pixelType) {
        auto m = d.parse(kHead + "[defaults]\ncontainer = \"ktx2\"\n" + kSwell + "pixel_type = \"" + pixelType + "\"\n" +
                         "[fresnel]\ncontainer = \"dds\"\npixel_type = \"half\"\n");
        EXPECT_TRUE(m) << m.error().what;
        BuildOptions options;
        options.outputDir = d.dir.file("out");
        options.version = "test";
        auto r = buildMaterial(*m, options);
        EXPECT_TRUE(r) << r.error().what;
        return r ? r->rebuilt() : -1;
    };
    EXPECT_EQ(build("half"), 2);
    auto material = readMaterial(d.dir.file("out/material.json"));
    ASSERT_TRUE(material) << material.error().what;
    EXPECT_EQ(material->displacement[0].texture.file, "swell.ktx2");
    EXPECT_EQ(material->fresnel->texture.file, "fresnel.dds");
    auto swell = readGpuTexture(d.dir.file("out/swell.ktx2"));
    ASSERT_TRUE(swell) << swell.error().what;
    EXPECT_EQ(swell->format, TexelFormat::Rgba16F);
    EXPECT_EQ(material->displacement[0].texture.levels, int(swell->levels.size()));
    EXPECT_EQ(material->displacement[0].texture.pixelType, pixelTypeOf(swell->format));
    auto ramp = readGpuTexture(d.dir.file("out/fresnel.dds"));
    ASSERT_TRUE(ramp) << ramp.error().what;
    EXPECT_EQ(ramp->format, TexelFormat::Rgba16F);

    EXPECT_EQ(build("half"), 0) << "nothing changed";
    EXPECT_EQ(build("uint16"), 1) << "the pixel type shapes the output: only swell is made again";
    swell = readGpuTexture(d.dir.file("out/swell.ktx2"));
    ASSERT_TRUE(swell);
    EXPECT_EQ(swell->format, TexelFormat::Rgba16Unorm);
    material = readMaterial(d.dir.file("out/material.json"));
    ASSERT_TRUE(material) << material.error().what;
    EXPECT_EQ(material->displacement[0].texture.pixelType, PixelType::Uint16);
    EXPECT_EQ(material->fresnel->texture.pixelType, PixelType::Half);
}

}  // namespace
}  // namespace heightpack
