// material.json: materialJson and readMaterial are inverses, keys keep their documented order, and a
// bad file is BadInput, never a throw.
#include <gtest/gtest.h>

#include <fstream>
#include <optional>
#include <string>

#include "heightpack/bake/material.hpp"
#include "heightpack/bake/material_sampler.hpp"

#include "support/test_support.hpp"

namespace heightpack {
namespace {

MaterialDescription sampleMaterial() {
    MaterialDescription d;
    d.name = "sea";
    d.generator = "heightpack 9.8.7";
    d.manifest = "sea.toml";
    DisplacementLayer a;
    a.name = "swell";
    a.texture = {"swell.exr", 512, 256, 10, 1, std::nullopt};
    a.heightScale = 0.1;  // not exactly representable: must read back to the same double
    a.heightOffset = -0.3;
    a.tileSize = 64.0;
    a.scroll = {0.01, -0.004};
    a.amplitude = 1.5;
    d.displacement.push_back(a);
    DisplacementLayer b = a;
    b.name = "seq";
    b.texture = {"seq.ktx2", 64, 64, 7, 12, PixelType::Bc4};
    b.layout = Layout::Plain;
    b.loopPeriod = 2.5;
    d.displacement.push_back(b);
    NormalLayer n;
    n.name = "ripple_n";
    n.texture = {"ripple_n.ktx2", 128, 128, 8, 1, PixelType::Bc5};
    n.layout = Layout::Xy;
    n.tileSize = 8.0;
    n.heightRange = 0.05;
    n.octaves = {{8.0, {0.02, 0.01}, 1.0}, {2.0, {-0.05, 0.03}, 0.35}};
    d.normals = n;
    FresnelLayer f;
    f.name = "fresnel";
    f.texture = {"fresnel.exr", 256, 1, 9, 1, std::nullopt};
    f.ior = 1.34;
    d.fresnel = f;
    FoamLayer foam;
    foam.name = "foam";
    foam.texture = MaterialTexture{"foam.exr", 32, 32, 6, 1, std::nullopt};
    foam.h0 = 1.1;
    foam.hmax = 2.3;
    foam.tileSize = 3.0;
    d.foam = foam;
    return d;
}

Result<MaterialDescription> readText(const test::ScratchDir& dir, const std::string& text) {
    const std::string path = dir.file("material.json");
    std::ofstream(path, std::ios::binary) << text;
    return readMaterial(path);
}

TEST(Material, WrittenThenReadIsTheSameMaterial) {
    test::ScratchDir dir;
    const MaterialDescription d = sampleMaterial();
    const std::string json = materialJson(d);
    auto back = readText(dir, json);
    ASSERT_TRUE(back) << back.error().what;
    EXPECT_EQ(back->name, d.name);
    EXPECT_EQ(back->generator, d.generator);
    EXPECT_EQ(back->manifest, d.manifest);
    ASSERT_EQ(back->displacement.size(), 2u);
    EXPECT_EQ(back->displacement[0].heightScale, 0.1);  // exactly: numbers read back as written
    EXPECT_EQ(back->displacement[0].heightOffset, -0.3);
    EXPECT_EQ(back->displacement[0].scroll, d.displacement[0].scroll);
    EXPECT_EQ(back->displacement[0].texture.width, 512);
    EXPECT_EQ(back->displacement[0].texture.height, 256);
    EXPECT_EQ(back->displacement[0].texture.levels, 10);
    EXPECT_EQ(back->displacement[1].texture.frames, 12);
    EXPECT_EQ(back->displacement[1].texture.pixelType, PixelType::Bc4);
    EXPECT_EQ(back->displacement[0].layout, Layout::Neighbour4);
    EXPECT_EQ(back->displacement[1].layout, Layout::Plain);
    EXPECT_FALSE(back->displacement[0].texture.pixelType);  // float: not written
    EXPECT_EQ(back->displacement[1].loopPeriod, 2.5);
    ASSERT_TRUE(back->normals);
    EXPECT_EQ(back->normals->layout, Layout::Xy);
    EXPECT_EQ(back->normals->texture.pixelType, PixelType::Bc5);
    ASSERT_EQ(back->normals->octaves.size(), 2u);
    EXPECT_EQ(back->normals->octaves[1].strength, 0.35);
    EXPECT_EQ(back->normals->octaves[1].scroll, d.normals->octaves[1].scroll);
    ASSERT_TRUE(back->fresnel);
    EXPECT_EQ(back->fresnel->ior, 1.34);
    ASSERT_TRUE(back->foam && back->foam->texture);
    EXPECT_EQ(back->foam->texture->file, "foam.exr");
    EXPECT_EQ(back->foam->hmax, 2.3);
    // And the whole of it: writing what was read gives the same bytes.
    EXPECT_EQ(materialJson(*back), json);
}

TEST(Material, OptionalLayersMayBeAbsent) {
    test::ScratchDir dir;
    MaterialDescription d = sampleMaterial();
    d.normals.reset();
    d.fresnel.reset();
    d.foam->texture.reset();
    auto back = readText(dir, materialJson(d));
    ASSERT_TRUE(back) << back.error().what;
    EXPECT_FALSE(back->normals);
    EXPECT_FALSE(back->fresnel);
    ASSERT_TRUE(back->foam);
    EXPECT_FALSE(back->foam->texture);
}

TEST(Material, KeysKeepTheDocumentedOrder) {
    const std::string json = materialJson(sampleMaterial());
    size_t last = 0;
    for (const char* key : {"\"schema\"", "\"version\"", "\"name\"", "\"generator\"", "\"manifest\"", "\"displacement\"",
                            "\"normals\"", "\"fresnel\"", "\"foam\""}) {
        const size_t at = json.find(key);
        ASSERT_NE(at, std::string::npos) << key;
        EXPECT_GT(at, last) << key << " is out of order";
        last = at;
    }
    EXPECT_NE(json.find(std::string("\"schema\": \"") + kMaterialSchemaName + "\""), std::string::npos);
    EXPECT_EQ(materialJson(sampleMaterial()), json) << "the same material always gives the same bytes";
}

TEST(Material, BadFilesAreBadInputNamingTheFile) {
    test::ScratchDir dir;
    const std::string good = materialJson(sampleMaterial());
    const std::string bad[] = {
        "",
        "not json",
        good.substr(0, good.size() / 2),
        [&] { std::string t = good; return t.replace(t.find("heightpack-material"), 19, "something-else-here"); }(),
        [&] { std::string t = good; return t.replace(t.find("\"version\": 1"), 12, "\"version\": 99"); }(),
        "{\"schema\": \"heightpack-material\", \"version\": 1}",
        [&] { std::string t = good; return t.replace(t.find("\"bc4\""), 5, "\"int8\""); }(),
        // A layout of the other kind of map: heights are neighbour4 or plain, normals rgb or xy.
        [&] { std::string t = good; return t.replace(t.find("\"plain\""), 7, "\"xy\""); }(),
        [&] { std::string t = good; return t.replace(t.find("\"xy\""), 4, "\"plain\""); }(),
    };
    for (const std::string& text : bad) {
        auto m = readText(dir, text);
        ASSERT_FALSE(m) << text.substr(0, 80);
        EXPECT_EQ(m.error().kind, ErrorKind::BadInput);
        EXPECT_NE(m.error().path.find("material.json"), std::string::npos) << m.error().path;
    }
    auto missing = readMaterial(dir.file("none.json"));
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().kind, ErrorKind::BadInput);
}

TEST(Material, SamplerLoadNamesTheTextureThatIsMissingOrNotAHeightChain) {
    test::ScratchDir dir;
    std::ofstream(dir.file("material.json")) << materialJson(sampleMaterial());
    auto missing = loadMaterialSampler(dir.file("material.json"));
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().kind, ErrorKind::BadInput);
    EXPECT_NE(missing.error().path.find("swell.exr"), std::string::npos) << missing.error().path;
    // A picture where a height chain should be: refused by its layout, not sampled.
    test::writeImage(dir.file("swell.exr"), test::randomImage(8, 8, 1), OIIO::TypeDesc::FLOAT);
    auto notPacked = loadMaterialSampler(dir.file("material.json"));
    ASSERT_FALSE(notPacked);
    EXPECT_EQ(notPacked.error().kind, ErrorKind::BadInput);
    EXPECT_NE(notPacked.error().what.find("layout"), std::string::npos) << notPacked.error().what;
}

}  // namespace
// material.json holds the tables' names; its parsed form holds the enums.
// A name no table lists is a damaged file.
TEST(Material, NamesInTheFileEnumsInTheParsedForm) {
    MaterialDescription m;
    m.name = "sea";
    DisplacementLayer d;
    d.name = "long";
    d.texture = {"long.exr", 64, 64, 7, 1, std::nullopt};
    d.wrap = Wrap::Clamp;
    d.filter = Filter::Lanczos3;
    m.displacement.push_back(d);
    NormalLayer n;
    n.name = "n";
    n.texture = {"n.exr", 64, 64, 7, 1, std::nullopt};
    n.convention = NormalConvention::DirectX;
    n.alpha = NormalAlpha::SlopeVariance;
    n.octaves.push_back({8.0, {0.0, 0.0}, 1.0});
    m.normals = n;
    FresnelLayer f;
    f.name = "f";
    f.texture = {"f.exr", 256, 1, 1, 1, std::nullopt};
    f.model = FresnelModel::Schlick;
    f.index = FresnelIndex::TwoNdotV;
    m.fresnel = f;
    const std::string text = materialJson(m);
    for (const char* word : {"\"wrap\": \"clamp\"", "\"filter\": \"lanczos3\"", "\"convention\": \"directx\"",
                             "\"alpha\": \"variance\"", "\"model\": \"schlick\"", "\"index\": \"2nv\""})
        EXPECT_NE(text.find(word), std::string::npos) << word << "\n" << text;

    const std::string path = ::testing::TempDir() + "names_material.json";
    {
        std::ofstream out(path, std::ios::binary);
        out << text;
    }
    auto read = readMaterial(path);
    ASSERT_TRUE(read.ok()) << read.error().what;
    EXPECT_EQ(read->displacement[0].wrap, Wrap::Clamp);
    EXPECT_EQ(read->displacement[0].filter, Filter::Lanczos3);
    EXPECT_EQ(read->normals->convention, NormalConvention::DirectX);
    EXPECT_EQ(read->normals->alpha, NormalAlpha::SlopeVariance);
    EXPECT_EQ(read->fresnel->model, FresnelModel::Schlick);
    EXPECT_EQ(read->fresnel->index, FresnelIndex::TwoNdotV);
    EXPECT_EQ(materialJson(*read), text);

    std::string damaged = text;
    damaged.replace(damaged.find("\"clamp\""), 7, "\"mirror\"");
    {
        std::ofstream out(path, std::ios::binary);
        out << damaged;
    }
    auto refused = readMaterial(path);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().what.find("displacement[0].wrap (one of: periodic, clamp)"), std::string::npos)
        << refused.error().what;
}

}  // namespace heightpack
