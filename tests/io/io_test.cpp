#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTiledInputFile.h>
#include <Imath/half.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>
#include <random>

#include "heightpack/bake/pack_job.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/pack.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/image_write.hpp"
#include "heightpack/io/read.hpp"

#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// A smooth field in [0.05, 0.95].
float field(int x, int y) {
    return static_cast<float>(0.5 + 0.3 * std::sin(2 * std::numbers::pi * x / 64.0) * std::cos(2 * std::numbers::pi * y / 32.0) +
                              0.15 * std::sin(2 * std::numbers::pi * (x + 2 * y) / 64.0));
}

Error loadError(const std::string& path, const LoadOptions& options = {}) {
    auto r = loadHeightMap(path, options);
    EXPECT_FALSE(r.ok()) << path << " loaded but should not";
    return r.ok() ? Error{} : r.error();
}

}  // namespace

TEST(Io, EightSixteenBitHalfAndFloatDecodeToTheSameHeights) {
    ScratchDir dir;
    const Image truth = makeImage(64, 32, field);
    struct Case { const char* name; OIIO::TypeDesc type; double tolerance; };
    const Case cases[] = {
        {"h8.png", OIIO::TypeDesc::UINT8, 0.5 / 255 + 1e-6},
        {"h16.png", OIIO::TypeDesc::UINT16, 0.5 / 65535 + 1e-7},
        {"h16.tif", OIIO::TypeDesc::UINT16, 0.5 / 65535 + 1e-7},
        {"h8.tga", OIIO::TypeDesc::UINT8, 0.5 / 255 + 1e-6},
        {"hhalf.exr", OIIO::TypeDesc::HALF, 1.0 / 2048},  // 11 significant bits
        {"hfloat.exr", OIIO::TypeDesc::FLOAT, 0.0},
        {"hfloat.tif", OIIO::TypeDesc::FLOAT, 0.0},
    };
    for (const Case& c : cases) {
        writeImage(dir.file(c.name), truth, c.type);
        auto loaded = loadHeightMap(dir.file(c.name));
        ASSERT_TRUE(loaded.ok()) << c.name << ": " << loaded.error().what;
        ASSERT_EQ(loaded->heights.width, 64);
        ASSERT_EQ(loaded->heights.height, 32);
        ASSERT_EQ(loaded->heights.channels, 1);
        double worst = 0.0;
        for (size_t i = 0; i < truth.pixels.size(); ++i)
            worst = std::max(worst, double(std::abs(loaded->heights.pixels[i] - truth.pixels[i])));
        EXPECT_LE(worst, c.tolerance) << c.name;
    }
}

TEST(Io, ColourNeedsAChannelAndEachChannelIsTakenAsStored) {
    ScratchDir dir;
    const int w = 8, h = 4;
    std::vector<float> rgba(w * h * 4);
    for (int i = 0; i < w * h; ++i) {
        rgba[4 * i + 0] = (i % 7) / 7.0f;
        rgba[4 * i + 1] = (i % 5) / 5.0f;
        rgba[4 * i + 2] = (i % 3) / 3.0f;
        rgba[4 * i + 3] = (i % 2) ? 1.0f : 0.0f;  // transparent texels must not darken the colour channels
    }
    const std::string path = dir.file("colour.png");
    writeImage(path, w, h, 4, rgba, OIIO::TypeDesc::UINT16);

    const Error e = loadError(path);
    EXPECT_EQ(e.kind, ErrorKind::BadInput);
    // The reason, not a flag: each shell names its own way to choose the channel.
    EXPECT_EQ(e.fix, Fix::ChooseChannel);
    EXPECT_NE(e.hint.find("r, g, b, a, luma"), std::string::npos) << e.hint;
    EXPECT_EQ(e.hint.find("--"), std::string::npos) << e.hint;

    const std::pair<ChannelSelect, int> channels[] = {
        {ChannelSelect::R, 0}, {ChannelSelect::G, 1}, {ChannelSelect::B, 2}, {ChannelSelect::A, 3}};
    for (const auto& [select, index] : channels) {
        LoadOptions o;
        o.channel = select;
        auto r = loadHeightMap(path, o);
        ASSERT_TRUE(r.ok()) << r.error().what;
        for (int i = 0; i < w * h; ++i) ASSERT_NEAR(r->heights.pixels[i], rgba[4 * i + index], 1e-4) << index;
    }
    LoadOptions o;
    o.channel = ChannelSelect::Luma;
    auto luma = loadHeightMap(path, o);
    ASSERT_TRUE(luma.ok());
    for (int i = 0; i < w * h; ++i)
        ASSERT_NEAR(luma->heights.pixels[i], 0.2126 * rgba[4 * i] + 0.7152 * rgba[4 * i + 1] + 0.0722 * rgba[4 * i + 2],
                    1e-4);
}

TEST(Io, ASequenceIsNameDotExtOrNameDotHashesDotExt) {
    EXPECT_EQ(frameFileName("out/sea.exr", 3, 8), "out/sea.0003.exr");
    EXPECT_EQ(frameFileName("out/sea.####.exr", 3, 8), "out/sea.0003.exr");
    EXPECT_EQ(frameFileName("out/sea.####.exr", 0, 1), "out/sea.####.exr") << "one frame: the path as given";
    EXPECT_EQ(frameFileName("out/####.exr", 2, 4), "out/####.0002.exr") << "no NAME before the hashes";
    EXPECT_EQ(frameFileName("out/sea.###.exr", 2, 4), "out/sea.###.0002.exr") << "three hashes are a name";
    ScratchDir dir;
    for (const char* name : {"sea.0000.png", "sea.0001.png", "sea.0002.png", "sea.0004.png"}) std::ofstream(dir.file(name)) << "x";
    const std::vector<std::string> frames = expandSequence(dir.file("sea.png"));
    ASSERT_EQ(frames.size(), 3u) << "consecutive frames from 0000: 0004 is after a gap";
    EXPECT_EQ(frames[2], dir.file("sea.0002.png"));
    EXPECT_EQ(expandSequence(dir.file("sea.####.png")), frames);
    EXPECT_EQ(expandSequence(dir.file("none.####.png")), std::vector<std::string>{dir.file("none.####.png")})
        << "no frames: the path as given, so the error names it";
}

TEST(Io, BadInputsAreRefusedWithAReason) {
    ScratchDir dir;
    EXPECT_NE(loadError(dir.file("missing.png")).what.find("no such file"), std::string::npos);

    writeBytes(dir.file("empty.png"), {});
    EXPECT_NE(loadError(dir.file("empty.png")).what.find("empty"), std::string::npos);

    const std::string text = "this is not an image\n";
    writeBytes(dir.file("text.png"), std::vector<unsigned char>(text.begin(), text.end()));
    EXPECT_EQ(loadError(dir.file("text.png")).kind, ErrorKind::BadInput);

    writeImage(dir.file("full.png"), randomImage(256, 256, 1), OIIO::TypeDesc::UINT8);
    auto bytes = readBytes(dir.file("full.png"));
    bytes.resize(bytes.size() / 2);
    writeBytes(dir.file("truncated.png"), bytes);
    EXPECT_EQ(loadError(dir.file("truncated.png")).kind, ErrorKind::BadInput);

    writeBytes(dir.file("huge.png"), pngWithClaimedSize(100000, 100000));
    const Error huge = loadError(dir.file("huge.png"));
    EXPECT_NE(huge.what.find("100000x100000"), std::string::npos) << huge.what;

    Image nan = makeImage(8, 8, field);
    nan.at(3, 5) = std::numeric_limits<float>::quiet_NaN();
    writeImage(dir.file("nan.exr"), nan, OIIO::TypeDesc::FLOAT);
    const Error nanError = loadError(dir.file("nan.exr"));
    EXPECT_NE(nanError.what.find("NaN at texel 3,5"), std::string::npos) << nanError.what;

    Image inf = makeImage(8, 8, field);
    inf.at(0, 0) = std::numeric_limits<float>::infinity();
    writeImage(dir.file("inf.exr"), inf, OIIO::TypeDesc::FLOAT);
    EXPECT_NE(loadError(dir.file("inf.exr")).what.find("infinite"), std::string::npos);
}

TEST(Io, WrittenExrIsATiledMipMappedFloatTextureHoldingThePackedChain) {
    ScratchDir dir;
    const Image map = makeImage(64, 32, field);
    writeImage(dir.file("map.exr"), map, OIIO::TypeDesc::FLOAT);
    PackOptions options;
    options.mip.filter = Filter::Lanczos3;
    options.scale = 2.0f;
    options.offset = -1.0f;
    options.plainOutput = dir.file("plain.exr");
    options.version = "test";
    auto report = packHeightMap(dir.file("map.exr"), dir.file("packed.exr"), options);
    ASSERT_TRUE(report.ok()) << report.error().what;

    // What libpack computes, independently of the file.
    Image scaled = map;
    for (float& v : scaled.pixels) v = -1.0f + 2.0f * v;
    const auto chain = generateMipChain(scaled, Filter::Lanczos3);
    const auto packed = packMipChain(chain, Wrap::Periodic);

    // Read back through OpenImageIO.
    auto in = OIIO::ImageInput::open(dir.file("packed.exr"));
    ASSERT_TRUE(in) << OIIO::geterror();
    EXPECT_EQ(in->spec().tile_width, 64);
    EXPECT_EQ(in->spec().tile_height, 64);
    EXPECT_EQ(in->spec().nchannels, 4);
    EXPECT_EQ(in->spec().format, OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(in->spec().get_string_attribute("heightpack:layout"), "neighbour4");
    EXPECT_EQ(in->spec().get_string_attribute("heightpack:wrap"), "periodic");
    EXPECT_EQ(in->spec().get_string_attribute("wrapmodes"), "periodic,periodic");
    EXPECT_EQ(in->spec().get_string_attribute("heightpack:filter"), "lanczos3");
    EXPECT_FLOAT_EQ(in->spec().get_float_attribute("heightpack:heightScale"), 2.0f);
    EXPECT_FLOAT_EQ(in->spec().get_float_attribute("heightpack:heightOffset"), -1.0f);
    EXPECT_FLOAT_EQ(in->spec().get_float_attribute("heightpack:texelCentre"), 0.5f);
    EXPECT_EQ(in->spec().get_string_attribute("heightpack:source"), "map.exr");
    EXPECT_EQ(in->spec().get_string_attribute("heightpack:sourceHash"), hashPixels(map));
    int levels = 0;
    for (; in->seek_subimage(0, levels); ++levels) {
        ASSERT_LT(size_t(levels), packed.size());
        const Image& expected = packed[levels];
        ASSERT_EQ(in->spec().width, expected.width);
        ASSERT_EQ(in->spec().height, expected.height);
        std::vector<float> pixels(expected.pixels.size());
        ASSERT_TRUE(in->read_image(0, levels, 0, 4, OIIO::TypeDesc::FLOAT, pixels.data()));
        EXPECT_EQ(pixels, expected.pixels) << "level " << levels;
    }
    EXPECT_EQ(levels, 7);
    EXPECT_FALSE(in->seek_subimage(1, 0));  // one subimage: the levels are mip levels

    // OpenEXR's own reader agrees on the tiling.
    Imf::TiledInputFile exr(dir.file("packed.exr").c_str());
    EXPECT_EQ(exr.levelMode(), Imf::MIPMAP_LEVELS);
    EXPECT_EQ(exr.levelRoundingMode(), Imf::ROUND_DOWN);
    EXPECT_EQ(exr.numLevels(), 7);
    EXPECT_EQ(exr.header().compression(), Imf::ZIP_COMPRESSION);

    // The plain chain: one channel, the unpacked levels.
    auto plain = OIIO::ImageInput::open(dir.file("plain.exr"));
    ASSERT_TRUE(plain);
    EXPECT_EQ(plain->spec().nchannels, 1);
    EXPECT_EQ(plain->spec().get_string_attribute("heightpack:layout"), "plain");
    for (int level = 0; plain->seek_subimage(0, level); ++level) {
        std::vector<float> pixels(chain[level].pixels.size());
        ASSERT_TRUE(plain->read_image(0, level, 0, 1, OIIO::TypeDesc::FLOAT, pixels.data()));
        EXPECT_EQ(pixels, chain[level].pixels) << "plain level " << level;
    }
    EXPECT_EQ(dir.listing(), (std::vector<std::string>{"map.exr", "packed.exr", "plain.exr"}));
}

TEST(Io, SizesThatAreNotPowersOfTwoAreRefusedOrResized) {
    ScratchDir dir;
    writeImage(dir.file("odd.png"), makeImage(100, 60, field), OIIO::TypeDesc::UINT8);
    auto refused = packHeightMap(dir.file("odd.png"), dir.file("odd.exr"), {});
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().kind, ErrorKind::BadInput);
    // The library names no flag: it gives the remedy and the size, and each shell words it.
    EXPECT_EQ(refused.error().fix, Fix::ResizeToPowerOfTwo);
    EXPECT_EQ(refused.error().fixArgs, (std::vector<std::string>{"128x64"}));
    EXPECT_NE(refused.error().hint.find("128x64"), std::string::npos);
    EXPECT_EQ(refused.error().hint.find("--"), std::string::npos);
    EXPECT_FALSE(std::filesystem::exists(dir.file("odd.exr")));

    PackOptions resize;
    resize.resizeToPowerOfTwo = true;
    auto resized = packHeightMap(dir.file("odd.png"), dir.file("odd.exr"), resize);
    ASSERT_TRUE(resized.ok()) << resized.error().what;
    EXPECT_TRUE(resized->resized);
    EXPECT_EQ(resized->levelSizes.front(), std::make_pair(128, 64));
}

TEST(Io, OutputsThatCannotBeWrittenAreRefusedAndLeftAlone) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(16, 16, field), OIIO::TypeDesc::UINT8);

    auto noFolder = packHeightMap(dir.file("map.png"), dir.file("nowhere/out.exr"), {});
    ASSERT_FALSE(noFolder.ok());
    EXPECT_EQ(noFolder.error().kind, ErrorKind::CannotWrite);
    EXPECT_NE(noFolder.error().what.find("does not exist"), std::string::npos);

    const std::vector<unsigned char> old = {'o', 'l', 'd'};
    writeBytes(dir.file("locked.exr"), old);
    ::chmod(dir.file("locked.exr").c_str(), 0444);
    auto locked = packHeightMap(dir.file("map.png"), dir.file("locked.exr"), {});
    ASSERT_FALSE(locked.ok());
    EXPECT_EQ(locked.error().kind, ErrorKind::CannotWrite);
    EXPECT_EQ(readBytes(dir.file("locked.exr")), old);
    EXPECT_EQ(dir.listing(), (std::vector<std::string>{"locked.exr", "map.png"}));  // no temporary file left
}

TEST(Io, ReplacingAnOutputKeepsItsPermissions) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(16, 16, field), OIIO::TypeDesc::UINT8);
    writeBytes(dir.file("out.exr"), {'x'});
    ::chmod(dir.file("out.exr").c_str(), 0640);
    ASSERT_TRUE(packHeightMap(dir.file("map.png"), dir.file("out.exr"), {}).ok());
    struct stat st {};
    ASSERT_EQ(::stat(dir.file("out.exr").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0640u);
    EXPECT_GT(st.st_size, 100);
}

TEST(Io, PixelHashFollowsThePixels) {
    Image a = makeImage(8, 8, field), b = a;
    EXPECT_EQ(hashPixels(a), hashPixels(b));
    b.at(7, 7) += 1e-6f;
    EXPECT_NE(hashPixels(a), hashPixels(b));
    EXPECT_EQ(hashPixels(a).size(), 16u);
}

TEST(Io, FastPngDecoderMatchesOpenImageIOExactly) {
    // Grey PNGs take heightpack's own decoder; the same samples in single-channel TIFFs go through
    // OpenImageIO. The heights must be identical to the bit, for 8 and 16 bits, grey and grey + alpha,
    // every PNG filter (random data makes libpng choose all five).
    ScratchDir dir;
    const Image noise = randomImage(97, 61, 17);  // odd sizes: rows that are not a multiple of anything
    const Image smooth = makeImage(128, 64, field);
    struct Case { const Image* image; int channels; OIIO::TypeDesc type; };
    const Case cases[] = {{&noise, 1, OIIO::TypeDesc::UINT8}, {&noise, 1, OIIO::TypeDesc::UINT16},
                          {&smooth, 1, OIIO::TypeDesc::UINT16}, {&smooth, 2, OIIO::TypeDesc::UINT8},
                          {&noise, 2, OIIO::TypeDesc::UINT16}};
    int n = 0;
    for (const Case& c : cases) {
        const Image& grey = *c.image;
        const Image alpha = makeImage(grey.width, grey.height, [&](int x, int y) {
            return 1.0f - grey.at((x * 7 + 3) % grey.width, (y * 5 + 1) % grey.height);
        });
        std::vector<float> pixels;
        for (size_t i = 0; i < grey.pixels.size(); ++i) {
            pixels.push_back(grey.pixels[i]);
            if (c.channels == 2) pixels.push_back(alpha.pixels[i]);
        }
        const std::string name = "c" + std::to_string(n++);
        {
            // A PNG with two channels is grey + alpha.
            auto out = OIIO::ImageOutput::create(dir.file(name + ".png"));
            OIIO::ImageSpec spec(grey.width, grey.height, c.channels, c.type);
            if (c.channels == 2) {
                spec.channelnames = {"Y", "A"};
                spec.alpha_channel = 1;
                spec.attribute("oiio:UnassociatedAlpha", 1);
            }
            ASSERT_TRUE(out->open(dir.file(name + ".png"), spec));
            ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
            ASSERT_TRUE(out->close());
        }
        writeImage(dir.file(name + "_grey.tif"), grey, c.type);
        writeImage(dir.file(name + "_alpha.tif"), alpha, c.type);
        for (ChannelSelect select : {ChannelSelect::Auto, ChannelSelect::A}) {
            if (select == ChannelSelect::A && c.channels == 1) continue;
            LoadOptions o;
            o.channel = select;
            auto fast = loadHeightMap(dir.file(name + ".png"), o);
            auto reference =
                loadHeightMap(dir.file(name + (select == ChannelSelect::A ? "_alpha.tif" : "_grey.tif")));
            ASSERT_TRUE(fast.ok()) << fast.error().what;
            ASSERT_TRUE(reference.ok()) << reference.error().what;
            EXPECT_EQ(fast->source.decoder, "heightpack-png");
            EXPECT_EQ(reference->source.decoder, "openimageio");
            EXPECT_EQ(fast->heights.pixels, reference->heights.pixels) << name;
        }
    }
}

TEST(Io, FastPngDecoderReadsThinAndTinyMapsAsOpenImageIODoes) {
    // The fast decoder inflates the rows into the float image's own memory and turns them into floats
    // front to back, in batches, a row that would overwrite its own bytes alone (16-bit grey + alpha rows
    // are held apart); the row filters are undone by rows side by side, a 4096-byte chunk at a time. Thin,
    // tiny and wide shapes reach every case; libpng, through OpenImageIO, is the reference, and the
    // thread count changes nothing.
    ScratchDir dir;
    struct Shape { int w, h; };
    int n = 0;
    const Shape shapes[] = {{1, 1}, {1, 57}, {57, 1}, {2, 3}, {5, 300}, {300, 5}, {2100, 9}};
    for (const Shape shape : shapes) {
        for (const OIIO::TypeDesc type : {OIIO::TypeDesc::UINT8, OIIO::TypeDesc::UINT16}) {
            for (int channels = 1; channels <= 2; ++channels) {
                const Image values = randomImage(shape.w * channels, shape.h, unsigned(n + 1));
                const std::string path = dir.file("t" + std::to_string(n++) + ".png");
                auto out = OIIO::ImageOutput::create(path);
                OIIO::ImageSpec spec(shape.w, shape.h, channels, type);
                if (channels == 2) {
                    spec.channelnames = {"Y", "A"};
                    spec.alpha_channel = 1;
                    spec.attribute("oiio:UnassociatedAlpha", 1);
                }
                ASSERT_TRUE(out->open(path, spec));
                ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, values.pixels.data()));
                ASSERT_TRUE(out->close());
                OIIO::ImageSpec asStored;  // grey as stored, not multiplied by alpha
                asStored.attribute("oiio:UnassociatedAlpha", 1);
                auto in = OIIO::ImageInput::open(path, &asStored);
                ASSERT_TRUE(in);
                std::vector<float> reference(size_t(shape.w) * shape.h);
                ASSERT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, reference.data()));
                for (const int threads : {1, 3}) {
                    LoadOptions o;
                    o.threads = threads;
                    auto fast = loadHeightMap(path, o);
                    ASSERT_TRUE(fast.ok()) << fast.error().what;
                    EXPECT_EQ(fast->source.decoder, "heightpack-png") << path;
                    EXPECT_EQ(fast->heights.pixels, reference) << shape.w << "x" << shape.h << " " << type << " "
                                                              << channels << " channels, " << threads << " threads";
                }
            }
        }
    }
}

TEST(Io, DamagedPngsFallBackToOpenImageIOAndAreRefused) {
    ScratchDir dir;
    writeImage(dir.file("good.png"), randomImage(64, 64, 2), OIIO::TypeDesc::UINT16);
    auto bytes = readBytes(dir.file("good.png"));
    // One flipped bit inside the image data: the chunk CRC no longer matches.
    auto flipped = bytes;
    flipped[bytes.size() / 2] ^= 0x10;
    writeBytes(dir.file("flipped.png"), flipped);
    auto r = loadHeightMap(dir.file("flipped.png"), {});
    ASSERT_FALSE(r.ok()) << "a corrupted PNG decoded";
    EXPECT_EQ(r.error().kind, ErrorKind::BadInput);
}

TEST(Io, FastPngDecoderReadsTheExamplesAsOpenImageIODoes) {
    // The example maps use every PNG row filter (choppy.png: sub, up, average and Paeth).
    for (const char* name : {"swell.png", "choppy.png", "ripple.png", "painted_not_tileable.png"}) {
        const std::string path = std::string(HEIGHTPACK_SOURCE_DIR) + "/examples/maps/" + name;
        auto fast = loadHeightMap(path);
        ASSERT_TRUE(fast.ok()) << fast.error().what;
        EXPECT_EQ(fast->source.decoder, "heightpack-png") << name;
        auto in = OIIO::ImageInput::open(path);
        ASSERT_TRUE(in);
        std::vector<float> reference(in->spec().image_pixels());
        ASSERT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, reference.data()));
        EXPECT_EQ(fast->heights.pixels, reference) << name;
    }
}

// A grey 8- or 16-bit PNG from writeFlatImage is heightpack's own (libdeflate, rows filtered on all
// threads): libpng, through OpenImageIO, reads back the same samples as from the PNG OpenImageIO writes of
// the same floats (its own rounding), with the attributes as text; the bytes are the same at any thread
// count. Values: random in [0,1], beyond it (clamped), and exactly half a step off a level (ties).
TEST(Io, FlatGreyPngIsReadBackByLibpngAsOpenImageIOWouldWriteIt) {
    ScratchDir dir;
    std::mt19937 random(5);
    for (int bits : {8, 16}) {
        const int w = 37 + bits, h = 29;
        Image image(w, h, 1);
        const double steps = bits == 8 ? 255.0 : 65535.0;
        for (size_t i = 0; i < image.pixels.size(); ++i) {
            const double u = std::uniform_real_distribution<double>(-0.05, 1.05)(random);
            image.pixels[i] = static_cast<float>(i % 5 == 0 ? (std::floor(u * steps) + 0.5) / steps : u);
        }
        FlatImageOptions flat;
        flat.bits = bits;
        flat.attributes = {attribute(attr::tileMethod, "periodic"), attribute(attr::crossfadeWidth, 0.125f)};
        for (int threads : {1, 3}) {
            flat.threads = threads;
            ASSERT_TRUE(writeFlatImage(dir.file("t" + std::to_string(threads) + ".png"), image, flat).ok());
        }
        // Pixels compressed ahead (as tile does while it judges) give the same file; pixels prepared for
        // another image (here a smaller one) are not used.
        flat.prepared = preparePixels(dir.file("ahead.png"), image, flat);
        ASSERT_TRUE(flat.prepared.png);
        ASSERT_TRUE(writeFlatImage(dir.file("ahead.png"), image, flat).ok());
        flat.prepared = preparePixels(dir.file("other.png"), Image(5, 4, 1, 0.5f), flat);
        ASSERT_TRUE(writeFlatImage(dir.file("other.png"), image, flat).ok());
        flat.prepared = {};
        EXPECT_FALSE(preparePixels(dir.file("x.exr"), image, flat).png);  // heightpack does not encode those itself
        auto bytes = [&](const std::string& name) {
            std::ifstream in(dir.file(name), std::ios::binary);
            return std::vector<char>(std::istreambuf_iterator<char>(in), {});
        };
        EXPECT_EQ(bytes("t1.png"), bytes("t3.png"));
        EXPECT_EQ(bytes("ahead.png"), bytes("t1.png"));
        EXPECT_EQ(bytes("other.png"), bytes("t1.png"));
        // OpenImageIO's own writer, given the same clamped floats, as a reference.
        std::vector<float> clamped(image.pixels);
        for (float& v : clamped) v = std::clamp(v, 0.0f, 1.0f);
        {
            auto out = OIIO::ImageOutput::create(dir.file("oiio.png"));
            ASSERT_TRUE(out && out->open(dir.file("oiio.png"), OIIO::ImageSpec(w, h, 1, bits == 8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16)));
            ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, clamped.data()) && out->close());
        }
        auto samples = [&](const std::string& name, OIIO::ImageSpec* spec) {
            auto in = OIIO::ImageInput::open(dir.file(name));
            EXPECT_TRUE(in) << name;
            std::vector<uint16_t> v(size_t(w) * h);
            if (!in) return v;
            if (spec) *spec = in->spec();
            EXPECT_EQ(in->spec().format, bits == 8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16);
            EXPECT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT16, v.data()));
            return v;
        };
        OIIO::ImageSpec spec;
        EXPECT_EQ(samples("t3.png", &spec), samples("oiio.png", nullptr)) << bits;
        EXPECT_EQ(spec.width, w);
        EXPECT_EQ(spec.nchannels, 1);
        EXPECT_EQ(spec.get_string_attribute("heightpack:tileMethod"), "periodic");
        EXPECT_EQ(spec.get_string_attribute("heightpack:crossfadeWidth"), "0.125");
    }
}

// A float EXR from writeFlatImage is our own ZIP scanline file: OpenEXR's C++ library (its own zlib
// decoder) reads back every value exactly, by channel name, with the attributes; a half file rounds each
// value to nearest; the bytes are the same at any thread count. 1100 rows: more than one batch of blocks,
// and a last block of 12 rows.
TEST(Io, FlatFloatExrIsAZipScanlineFileThatOpenExrReadsBackExactly) {
    ScratchDir dir;
    const int w = 21, h = 1100, channels = 4;
    Image image(w, h, channels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c)  // noise-like low bits, so some blocks do not shrink
                image.pixels[(size_t(y) * w + x) * channels + c] = float(std::sin(0.37 * x + 0.011 * y * (c + 1)) * (c + 1) + 1e-3 * ((x * 7919 + y * 104729 + c) % 1000));
    FlatImageOptions flat;
    flat.channelNames = {"Y", "Dx", "Dy", "Foam"};  // not EXR's (alphabetical) order
    flat.attributes = {attribute(attr::significantWaveHeight, 2.5f), attribute(attr::layout, "synthesised")};
    auto bytes = [&](const std::string& name) {
        std::ifstream in(dir.file(name), std::ios::binary);
        return std::vector<char>(std::istreambuf_iterator<char>(in), {});
    };
    for (int threads : {1, 3}) {
        flat.threads = threads;
        ASSERT_TRUE(writeFlatImage(dir.file("t" + std::to_string(threads) + ".exr"), image, flat).ok());
    }
    EXPECT_EQ(bytes("t1.exr"), bytes("t3.exr"));
    flat.half = true;
    ASSERT_TRUE(writeFlatImage(dir.file("half.exr"), image, flat).ok());

    for (const char* name : {"t3.exr", "half.exr"}) {
        const bool half = std::string(name) == "half.exr";
        Imf::InputFile exr(dir.file(name).c_str());
        EXPECT_FALSE(exr.header().hasTileDescription());
        EXPECT_EQ(exr.header().compression(), Imf::ZIP_COMPRESSION);
        const auto* hs = exr.header().findTypedAttribute<Imf::FloatAttribute>("heightpack:significantWaveHeight");
        ASSERT_TRUE(hs);
        EXPECT_EQ(hs->value(), 2.5f);
        const auto* layout = exr.header().findTypedAttribute<Imf::StringAttribute>("heightpack:layout");
        ASSERT_TRUE(layout);
        EXPECT_EQ(layout->value(), "synthesised");
        std::vector<float> back(image.pixels.size(), -1.0f);
        Imf::FrameBuffer frame;
        for (int c = 0; c < channels; ++c)
            frame.insert(flat.channelNames[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(back.data() + c),
                                                          sizeof(float) * channels, sizeof(float) * channels * w));
        exr.setFrameBuffer(frame);
        exr.readPixels(0, h - 1);
        for (size_t i = 0; i < back.size(); ++i)
            ASSERT_EQ(back[i], half ? float(Imath::half(image.pixels[i])) : image.pixels[i]) << name << " value " << i;
        for (const char* c : {"Dx", "Dy", "Foam", "Y"})
            EXPECT_EQ(exr.header().channels().findChannel(c)->type, half ? Imf::HALF : Imf::FLOAT) << c;
    }
    // OpenImageIO reads it too, Y first as before.
    auto in = OIIO::ImageInput::open(dir.file("t1.exr"));
    ASSERT_TRUE(in) << OIIO::geterror();
    EXPECT_EQ(in->spec().channelnames, (std::vector<std::string>{"Y", "Dx", "Dy", "Foam"}));
    EXPECT_FLOAT_EQ(in->spec().get_float_attribute("heightpack:significantWaveHeight"), 2.5f);
}

TEST(Io, WritersNeverWriteNonFiniteTexelsOrOneFormatUnderAnothersName) {
    ScratchDir dir;
    Image nan = makeImage(8, 8, field);
    nan.at(3, 2) = std::numeric_limits<float>::quiet_NaN();
    FlatImageOptions flat;
    const Status flatNan = writeFlatImage(dir.file("nan.exr"), nan, flat);
    ASSERT_FALSE(flatNan.ok());
    EXPECT_EQ(flatNan.error().kind, ErrorKind::Internal);

    ChainToWrite content;
    content.width = content.height = 8;
    content.channelNames = {"Y"};
    content.fillRows = [](int, int, int rows, float* dst) {
        std::fill(dst, dst + rows * 8, std::numeric_limits<float>::infinity());
    };
    for (Compression c : {Compression::Zip, Compression::Piz}) {
        ExrWriteOptions options;
        options.compression = c;
        const Status tiledInf = writeTiledExr(dir.file("inf.exr"), content, options);
        ASSERT_FALSE(tiledInf.ok());
        EXPECT_EQ(tiledInf.error().kind, ErrorKind::Internal);
    }

    // EXR bytes under a PNG's name, a JPEG (lossy) height map: refused, not written.
    content.fillRows = [](int, int, int rows, float* dst) { std::fill(dst, dst + rows * 8, 0.5f); };
    EXPECT_FALSE(writeTiledExr(dir.file("x.png"), content, {}).ok());
    EXPECT_FALSE(writeFlatImage(dir.file("x.jpg"), makeImage(8, 8, field), flat).ok());
    EXPECT_TRUE(dir.listing().empty());
}

TEST(Io, InputsThatAreNotRegularFilesAreRefusedBeforeTheyAreOpened) {
    ScratchDir dir;
    ASSERT_EQ(::mkfifo(dir.file("pipe.png").c_str(), 0644), 0);
    EXPECT_NE(loadError(dir.file("pipe.png")).what.find("FIFO"), std::string::npos);
    EXPECT_NE(loadError("/dev/zero").what.find("device"), std::string::npos);
    EXPECT_FALSE(checkReadable(dir.path().string()).ok());
    writeImage(dir.file("a.png"), makeImage(8, 8, field), OIIO::TypeDesc::UINT8);
    EXPECT_TRUE(checkReadable(dir.file("a.png")).ok());
    // sameFile sees through other spellings and links.
    ASSERT_EQ(::link(dir.file("a.png").c_str(), dir.file("b.png").c_str()), 0);
    EXPECT_TRUE(sameFile(dir.file("a.png"), (dir.path() / "." / "b.png").string()));
    EXPECT_FALSE(sameFile(dir.file("a.png"), dir.file("missing.png")));
}
