// The per-map jobs in memory (packHeights, makeNormalChain, checkHeights): checked against chains computed
// here from the definitions, and against what the file jobs write, read back with OpenImageIO itself.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "heightpack/bake/check_job.hpp"
#include "heightpack/bake/normal_job.hpp"
#include "heightpack/bake/pack_job.hpp"
#include "heightpack/io/read.hpp"

#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// Smooth and periodic over a w x h tile: whole waves along x, y and the diagonal.
Image analyticMap(int w, int h) {
    return makeImage(w, h, [&](int x, int y) {
        const double u = double(x) / w, v = double(y) / h;
        return float(0.5 + 0.25 * std::sin(2 * std::numbers::pi * u) * std::cos(4 * std::numbers::pi * v) + 0.1 * std::sin(2 * std::numbers::pi * (3 * u + v)));
    });
}

SourceInfo memorySource(const std::string& name) {
    SourceInfo source;
    source.path = name;
    source.pixelType = "float";
    return source;
}

// Every mip level of the file at path, read with OpenImageIO (not libpack's reader), as float.
std::vector<Image> readLevels(const std::string& path) {
    std::vector<Image> levels;
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    if (!in) return levels;
    for (int level = 0; in->seek_subimage(0, level); ++level) {
        const OIIO::ImageSpec& spec = in->spec();
        Image image(spec.width, spec.height, spec.nchannels);
        EXPECT_TRUE(in->read_image(0, level, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()));
        levels.push_back(std::move(image));
    }
    return levels;
}

// The box-filtered chain from its definition: each texel of a level is the mean of the 2x2 (or 2x1 once
// a side is 1) texels above it.
std::vector<Image> boxChain(const Image& level0) {
    std::vector<Image> chain = {level0};
    while (chain.back().width > 1 || chain.back().height > 1) {
        const Image& a = chain.back();
        const int sx = a.width > 1 ? 2 : 1, sy = a.height > 1 ? 2 : 1;
        Image b(a.width / sx, a.height / sy);
        for (int y = 0; y < b.height; ++y)
            for (int x = 0; x < b.width; ++x) {
                double sum = 0.0;
                for (int j = 0; j < sy; ++j)
                    for (int i = 0; i < sx; ++i) sum += a.at(x * sx + i, y * sy + j);
                b.at(x, y) = float(sum / (sx * sy));
            }
        chain.push_back(std::move(b));
    }
    return chain;
}

}  // namespace

TEST(PackHeights, EveryTexelHoldsItsFourNeighboursOfTheBoxChain) {
    const Image map = analyticMap(32, 16);
    for (const bool periodic : {true, false}) {
        PackOptions options;
        options.mip.filter = Filter::Box;
        options.mip.wrap = periodic ? Wrap::Periodic : Wrap::Clamp;
        options.scale = 2.0f;
        options.offset = 0.25f;
        const auto maps = packHeights(map, memorySource("analytic"), options);
        ASSERT_TRUE(maps) << maps.error().what;
        EXPECT_FALSE(maps->resized);

        Image stored = map;
        for (float& v : stored.pixels) v = 0.25f + 2.0f * v;
        const std::vector<Image> expected = boxChain(stored);
        ASSERT_EQ(maps->plain.size(), expected.size());  // 32x16 down to 1x1: six levels
        ASSERT_EQ(maps->packed.size(), expected.size());
        EXPECT_EQ(maps->plain[0].pixels, stored.pixels);
        for (size_t level = 0; level < expected.size(); ++level) {
            const Image& e = expected[level];
            const Image& p = maps->packed[level];
            ASSERT_EQ(p.width, e.width);
            ASSERT_EQ(p.height, e.height);
            ASSERT_EQ(p.channels, 4);
            for (int y = 0; y < e.height; ++y)
                for (int x = 0; x < e.width; ++x) {
                    const int x1 = referenceWrap(x + 1, e.width, periodic), y1 = referenceWrap(y + 1, e.height, periodic);
                    const float want[4] = {e.at(x, y), e.at(x1, y), e.at(x, y1), e.at(x1, y1)};
                    for (int c = 0; c < 4; ++c)
                        ASSERT_NEAR(p.at(x, y, c), want[c], 1e-5)
                            << "level " << level << " texel " << x << "," << y << " channel " << c;
                }
        }
    }
}

TEST(PackHeights, SidesThatAreNotPowersOfTwoAreRefusedUnlessResized) {
    const Image map = randomImage(24, 10, 5);
    PackOptions options;
    const auto refused = packHeights(map, memorySource("odd.png"), options);
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().kind, ErrorKind::BadInput);
    EXPECT_EQ(refused.error().path, "odd.png");
    EXPECT_NE(refused.error().what.find("24x10"), std::string::npos) << refused.error().what;

    options.resizeToPowerOfTwo = true;
    options.layout = Layout::Plain;
    const auto resized = packHeights(map, memorySource("odd.png"), options);
    ASSERT_TRUE(resized) << resized.error().what;
    EXPECT_TRUE(resized->resized);
    EXPECT_EQ(resized->plain[0].width, 32);
    EXPECT_EQ(resized->plain[0].height, 16);
    EXPECT_EQ(resized->plain.size(), 6u);
    EXPECT_TRUE(resized->packed.empty());  // plain only, as for foam and masks
}

TEST(PackHeights, TheFileJobWritesTheInMemoryChains) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), analyticMap(64, 32), OIIO::TypeDesc::UINT16);
    PackOptions options;
    options.scale = 1.5f;
    options.offset = -0.5f;
    options.mip.wrap = Wrap::Clamp;
    options.plainOutput = dir.file("plain.exr");
    const auto report = packHeightMap(dir.file("map.png"), dir.file("packed.exr"), options);
    ASSERT_TRUE(report) << report.error().what;

    auto loaded = loadHeightMap(dir.file("map.png"));
    ASSERT_TRUE(loaded) << loaded.error().what;
    const auto maps = packHeights(loaded->heights, loaded->source, options);
    ASSERT_TRUE(maps) << maps.error().what;

    const std::vector<Image> packed = readLevels(dir.file("packed.exr"));
    const std::vector<Image> plain = readLevels(dir.file("plain.exr"));
    ASSERT_EQ(packed.size(), maps->packed.size());
    ASSERT_EQ(plain.size(), maps->plain.size());
    ASSERT_EQ(report->levelSizes.size(), maps->plain.size());
    for (size_t level = 0; level < packed.size(); ++level) {
        EXPECT_EQ(packed[level].channels, 4);
        EXPECT_EQ(packed[level].pixels, maps->packed[level].pixels) << "packed level " << level;  // bit for bit
        EXPECT_EQ(plain[level].pixels, maps->plain[level].pixels) << "plain level " << level;
        EXPECT_EQ(report->levelSizes[level], std::make_pair(maps->plain[level].width, maps->plain[level].height));
    }
}

TEST(MakeNormalChain, TheFileJobWritesTheInMemoryNormals) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), analyticMap(32, 32), OIIO::TypeDesc::UINT16);
    auto loaded = loadHeightMap(dir.file("map.png"));
    ASSERT_TRUE(loaded) << loaded.error().what;

    NormalJobOptions options;
    options.normal.tileWidth = 8.0;
    options.normal.heightRange = 0.5;
    options.normal.alpha = NormalAlpha::SlopeVariance;
    const auto maps = makeNormalChain(loaded->heights, loaded->source, options);
    ASSERT_TRUE(maps) << maps.error().what;
    ASSERT_EQ(maps->chain.size(), 6u);
    const auto report = makeNormalMap(dir.file("map.png"), dir.file("n.exr"), options);
    ASSERT_TRUE(report) << report.error().what;
    EXPECT_EQ(report->maxSlopeDegrees, maps->maxSlopeDegrees);
    EXPECT_GT(maps->maxSlopeDegrees, 0.0);
    const std::vector<Image> file = readLevels(dir.file("n.exr"));
    ASSERT_EQ(file.size(), maps->chain.size());
    for (size_t level = 0; level < file.size(); ++level)
        EXPECT_EQ(file[level].pixels, maps->chain[level].pixels) << "level " << level;

    // PNG: level 0 alone, at any size, stored as 0.5 + 0.5 n in 8 bits.
    options.format = NormalFormat::Png8;
    options.normal.alpha = NormalAlpha::None;
    const auto flat = makeNormalChain(loaded->heights, loaded->source, options);
    ASSERT_TRUE(flat) << flat.error().what;
    ASSERT_EQ(flat->chain.size(), 1u);
    ASSERT_TRUE(makeNormalMap(dir.file("map.png"), dir.file("n.png"), options));
    const std::vector<Image> png = readLevels(dir.file("n.png"));
    ASSERT_EQ(png.size(), 1u);
    ASSERT_EQ(png[0].pixels.size(), flat->chain[0].pixels.size());
    for (size_t i = 0; i < png[0].pixels.size(); ++i)
        ASSERT_NEAR(png[0].pixels[i], 0.5f + 0.5f * flat->chain[0].pixels[i], 0.5 / 255 + 1e-6) << i;
}

TEST(MakeNormalChain, FlatWaterPointsStraightUp) {
    NormalJobOptions options;
    options.resizeToPowerOfTwo = true;
    const auto maps = makeNormalChain(Image(12, 20, 1, 0.3f), memorySource("flat"), options);
    ASSERT_TRUE(maps) << maps.error().what;
    EXPECT_TRUE(maps->resized);
    EXPECT_EQ(maps->maxSlopeDegrees, 0.0);
    for (const Image& level : maps->chain)
        for (size_t i = 0; i < level.texelCount(); ++i) {
            ASSERT_NEAR(level.pixels[i * level.channels + 0], 0.0f, 1e-6);
            ASSERT_NEAR(level.pixels[i * level.channels + 1], 0.0f, 1e-6);
            ASSERT_NEAR(level.pixels[i * level.channels + 2], 1.0f, 1e-6);
        }
}

TEST(CheckHeights, AgreesWithTheFileJobAndJudgesKnownMaps) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), analyticMap(64, 64), OIIO::TypeDesc::UINT16);
    CheckOptions options;
    const auto file = checkFile(dir.file("map.png"), options);
    ASSERT_TRUE(file) << file.error().what;
    auto loaded = loadHeightMap(dir.file("map.png"));
    ASSERT_TRUE(loaded) << loaded.error().what;
    const CheckReport memory = checkHeights(loaded->heights, loaded->source, options);
    EXPECT_EQ(memory.kind, "image");
    EXPECT_EQ(memory.input, dir.file("map.png"));
    EXPECT_TRUE(memory.tiles);
    EXPECT_EQ(memory.tiles, file->tiles);
    ASSERT_EQ(memory.levels.size(), file->levels.size());
    for (size_t level = 0; level < memory.levels.size(); ++level) {
        EXPECT_EQ(memory.levels[level].leftRight.value, file->levels[level].leftRight.value) << level;
        EXPECT_EQ(memory.levels[level].topBottom.value, file->levels[level].topBottom.value) << level;
        EXPECT_EQ(memory.levels[level].leftRight.slope, file->levels[level].leftRight.slope) << level;
    }

    // A ramp across x jumps from top to bottom where its left and right edges meet.
    const Image ramp = makeImage(64, 64, [](int x, int) { return x / 63.0f; });
    const CheckReport steep = checkHeights(ramp, memorySource("ramp"), options);
    EXPECT_FALSE(steep.tiles);
    ASSERT_TRUE(steep.failure);
    EXPECT_EQ(steep.failure->edge, SeamEdge::LeftRight);
    EXPECT_TRUE(steep.note.empty());

    const CheckReport odd = checkHeights(Image(48, 40, 1, 0.5f), memorySource("odd"), options);
    EXPECT_EQ(odd.levels.size(), 1u);  // level 0 alone: pack would resize first
    EXPECT_FALSE(odd.note.empty());
}
