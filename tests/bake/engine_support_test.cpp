// Which engine loads what (issue 25): for every container and texel format heightpack writes, made by the
// pack and normal jobs and read back by readTextureLevels, engineSupport's verdict per engine is the one
// docs/formats.md's "Which engine loads what" table gives from each loader's source or documentation (the
// expectations below are that table, written out independently of the code's own).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "heightpack/bake/normal_job.hpp"
#include "heightpack/bake/pack_job.hpp"
#include "heightpack/io/engine_support.hpp"
#include "heightpack/io/image_write.hpp"
#include "heightpack/io/info.hpp"

#include "support/exr_levels.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

TEST(EngineSupport, EveryFormatHeightpackWritesGetsTheDocumentedVerdictPerEngine) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(64, 64, smoothWave), OIIO::TypeDesc::UINT16);
    struct Case {
        bool normal;
        Layout layout;
        PixelType type;
        std::string output, format;
        std::vector<EngineSupport> expected;  // three.js, Babylon.js, Unreal, Unity, Godot
    };
    using enum EngineSupport;
    const std::vector<Case> cases = {
        {false, Layout::Neighbour4, PixelType::Float, "packed.ktx2", "ktx2 VK_FORMAT_R32G32B32A32_SFLOAT", {Loads, Refuses, Refuses, Refuses, Loads}},
        {false, Layout::Neighbour4, PixelType::Half, "half.ktx2", "ktx2 VK_FORMAT_R16G16B16A16_SFLOAT", {Loads, Refuses, Refuses, Refuses, Loads}},
        {false, Layout::Neighbour4, PixelType::Uint16, "u16.ktx2", "ktx2 VK_FORMAT_R16G16B16A16_UNORM", {Partial, Refuses, Refuses, Refuses, Partial}},
        {false, Layout::Plain, PixelType::Uint16, "plain16.ktx2", "ktx2 VK_FORMAT_R16_UNORM", {Refuses, Refuses, Refuses, Refuses, Partial}},
        {false, Layout::Plain, PixelType::Half, "plainh.ktx2", "ktx2 VK_FORMAT_R16_SFLOAT", {Loads, Refuses, Refuses, Refuses, Loads}},
        {false, Layout::Neighbour4, PixelType::Float, "packed.dds", "dds DXGI_FORMAT_R32G32B32A32_FLOAT", {Refuses, Partial, Unknown, Unknown, Loads}},
        {false, Layout::Neighbour4, PixelType::Half, "half.dds", "dds DXGI_FORMAT_R16G16B16A16_FLOAT", {Refuses, Partial, Unknown, Unknown, Loads}},
        {false, Layout::Plain, PixelType::Float, "plain.dds", "dds DXGI_FORMAT_R32_FLOAT", {Refuses, Refuses, Unknown, Unknown, Loads}},
        {false, Layout::Plain, PixelType::Uint16, "plain16.dds", "dds DXGI_FORMAT_R16_UNORM", {Refuses, Refuses, Unknown, Unknown, Partial}},
        {false, Layout::Neighbour4, PixelType::Float, "packed.exr", "openexr", {Partial, Refuses, Unknown, Unknown, Partial}},
        // xy normals in uint16 are unsigned normalised, as rgb ones: Godot's newest loaders take them, three.js's
        // KTX2Loader still only RGBA16.
        {true, Layout::Xy, PixelType::Uint16, "nxy16.ktx2", "ktx2 VK_FORMAT_R16G16_UNORM", {Refuses, Refuses, Refuses, Refuses, Partial}},
        {true, Layout::Xy, PixelType::Uint16, "nxy16.dds", "dds DXGI_FORMAT_R16G16_UNORM", {Refuses, Refuses, Unknown, Unknown, Partial}},
        {true, Layout::Rgb, PixelType::Uint16, "nrgb16.ktx2", "ktx2 VK_FORMAT_R16G16B16A16_UNORM", {Partial, Refuses, Refuses, Refuses, Partial}},
        {true, Layout::Xy, PixelType::Half, "nxyh.dds", "dds DXGI_FORMAT_R16G16_FLOAT", {Refuses, Refuses, Unknown, Unknown, Loads}},
        {true, Layout::Rgb, PixelType::Float, "nrgb.ktx2", "ktx2 VK_FORMAT_R32G32B32A32_SFLOAT", {Loads, Refuses, Refuses, Refuses, Loads}},
        // Block formats: three.js's KTX2Loader where the context has RGTC, Godot's KTX2 and DDS loaders, Unity's
        // IHVImageFormatImporter for a DDS; three.js's DDSLoader and Babylon.js's read no DX10 BC4/BC5.
        {false, Layout::Plain, PixelType::Bc4, "bc4.ktx2", "ktx2 VK_FORMAT_BC4_UNORM_BLOCK", {Partial, Refuses, Refuses, Refuses, Loads}},
        {false, Layout::Plain, PixelType::Bc4, "bc4.dds", "dds DXGI_FORMAT_BC4_UNORM", {Refuses, Refuses, Unknown, Loads, Loads}},
        {true, Layout::Xy, PixelType::Bc5, "bc5.ktx2", "ktx2 VK_FORMAT_BC5_UNORM_BLOCK", {Partial, Refuses, Refuses, Refuses, Loads}},
        {true, Layout::Xy, PixelType::Bc5, "bc5.dds", "dds DXGI_FORMAT_BC5_UNORM", {Refuses, Refuses, Unknown, Loads, Loads}},
        // ASTC (KTX2 only): three.js's KTX2Loader maps 4x4 and 6x6 (where the context has ASTC), Godot's 4x4 and 8x8.
        {false, Layout::Plain, PixelType::Astc4x4, "a4.ktx2", "ktx2 VK_FORMAT_ASTC_4x4_UNORM_BLOCK", {Partial, Refuses, Refuses, Refuses, Loads}},
        {false, Layout::Plain, PixelType::Astc6x6, "a6.ktx2", "ktx2 VK_FORMAT_ASTC_6x6_UNORM_BLOCK", {Partial, Refuses, Refuses, Refuses, Refuses}},
        {true, Layout::Xy, PixelType::Astc8x8, "a8.ktx2", "ktx2 VK_FORMAT_ASTC_8x8_UNORM_BLOCK", {Refuses, Refuses, Refuses, Refuses, Loads}},
        // ASTC HDR (SFLOAT): three.js r180's KTX2Loader maps 4x4 and 6x6 (half-float type; HDR where the context's
        // ASTC extension lists the hdr profile); Godot's KTX2 loader has no SFLOAT ASTC case.
        {false, Layout::Plain, PixelType::AstcHdr4x4, "h4.ktx2", "ktx2 VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK_EXT", {Partial, Refuses, Refuses, Refuses, Refuses}},
        {false, Layout::Plain, PixelType::AstcHdr6x6, "h6.ktx2", "ktx2 VK_FORMAT_ASTC_6x6_SFLOAT_BLOCK_EXT", {Partial, Refuses, Refuses, Refuses, Refuses}},
        {false, Layout::Plain, PixelType::AstcHdr8x8, "h8.ktx2", "ktx2 VK_FORMAT_ASTC_8x8_SFLOAT_BLOCK_EXT", {Refuses, Refuses, Refuses, Refuses, Refuses}},
    };
    const Engine engines[] = {Engine::ThreeJs, Engine::Babylon, Engine::Unreal, Engine::Unity, Engine::Godot};
    for (const Case& c : cases) {
        const std::string path = dir.file(c.output);
        if (c.normal) {
            NormalJobOptions options;
            options.normal.tileWidth = 8.0;
            options.normal.heightRange = 0.1;
            options.layout = c.layout;
            options.storage.pixelType = c.type;
            const auto made = makeNormalMap(dir.file("map.png"), path, options);
            ASSERT_TRUE(made) << c.output << ": " << made.error().what;
        } else {
            PackOptions options;
            options.layout = c.layout;
            options.storage.pixelType = c.type;
            const auto made = packHeightMap(dir.file("map.png"), path, options);
            ASSERT_TRUE(made) << c.output << ": " << made.error().what;
        }
        const auto layout = readTextureLevels(path);
        ASSERT_TRUE(layout) << c.output;
        EXPECT_EQ(layout->format, c.format) << c.output;
        for (size_t e = 0; e < std::size(engines); ++e) {
            const EngineVerdict v = engineSupport(engines[e], *layout, static_cast<int>(layout->levelSizes.size()));
            EXPECT_EQ(v.support, c.expected[e]) << c.output << " in " << nameOf(engines[e]) << ": " << v.why;
            EXPECT_FALSE(v.why.empty());
            // A refusal names a format the engine does load.
            if (v.support == Refuses) {
                EXPECT_FALSE(v.alternative.empty()) << c.output << " in " << nameOf(engines[e]);
            }
        }
    }
    // Array textures (pack --shift --foam into KTX2 and DDS): three.js and Babylon.js load layer 0
    // alone, Godot refuses a KTX2 array and loads a DDS one as a Texture2DArray (README's table, rows
    // "array").
    const Image y = makeImage(64, 64, smoothWave), d = makeImage(64, 64, [](int x, int) { return x / 64.0f - 0.5f; });
    writeChannels(dir.file("sea.exr"), {"Y", "Dx", "Dy", "Foam"}, {&y, &d, &d, &y});
    struct ArrayCase {
        std::string output;
        PixelType type;
        std::string format;
        std::vector<EngineSupport> expected;
    };
    for (const ArrayCase& c : {ArrayCase{"array.ktx2", PixelType::Float, "ktx2 VK_FORMAT_R32G32B32A32_SFLOAT", {Partial, Refuses, Refuses, Refuses, Refuses}},
                               ArrayCase{"array.dds", PixelType::Half, "dds DXGI_FORMAT_R16G16B16A16_FLOAT", {Refuses, Partial, Unknown, Unknown, Loads}},
                               ArrayCase{"array16.dds", PixelType::Uint16, "dds DXGI_FORMAT_R16G16B16A16_UNORM", {Refuses, Refuses, Unknown, Unknown, Partial}}}) {
        PackOptions options;
        options.shift = options.foam = true;
        options.storage.pixelType = c.type;
        const auto made = packHeightMap(dir.file("sea.exr"), dir.file(c.output), options);
        ASSERT_TRUE(made) << c.output << ": " << made.error().what;
        const auto header = readTextureLevels(dir.file(c.output));
        ASSERT_TRUE(header) << c.output;
        EXPECT_EQ(header->format, c.format) << c.output;
        EXPECT_EQ(header->layerNames.size(), 4u) << c.output;
        for (size_t e = 0; e < std::size(engines); ++e) {
            const EngineVerdict v = engineSupport(engines[e], *header, static_cast<int>(header->levelSizes.size()));
            EXPECT_EQ(v.support, c.expected[e]) << c.output << " in " << nameOf(engines[e]) << ": " << v.why;
            if (v.support == Refuses) {
                EXPECT_FALSE(v.alternative.empty()) << c.output << " in " << nameOf(engines[e]);
            }
        }
    }
    // A scanline EXR of one level, as tile and synth write: every engine's EXR loader reads it.
    FlatImageOptions flat;
    ASSERT_TRUE(writeFlatImage(dir.file("flat.exr"), makeImage(64, 64, smoothWave), flat));
    const auto layout = readTextureLevels(dir.file("flat.exr"));
    ASSERT_TRUE(layout);
    EXPECT_FALSE(layout->storedInTiles);
    for (Engine e : engines) EXPECT_EQ(engineSupport(e, *layout, 1).support, Loads) << nameOf(e);
}
