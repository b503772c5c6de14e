// EXRs and grey PNGs decoded without the format module (exr_source.cpp, png_source.cpp) against OpenImageIO
// itself, through the module, on families of files: every field of the header a reader uses, every
// attribute (name, text, number), every level's size and every pixel bit for bit. Files outside what the
// direct decoders present exactly must be left to OpenImageIO, never presented differently.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <OpenEXR/ImfVecAttribute.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "exr_source.hpp"
#include "format_module_loader.hpp"
#include "png_source.hpp"
#include "png_write.hpp"
#include "support/test_support.hpp"

namespace heightpack::test {
namespace {

using detail::ImageSource;
using detail::SourceSpec;

std::unique_ptr<ImageSource> throughModule(const std::string& format, const std::vector<unsigned char>& bytes,
                                           const std::string& path) {
    auto module = detail::formatModule(path, "cannot be read");
    EXPECT_TRUE(module.ok()) << module.error().what;
    if (!module) return nullptr;
    std::string error;
    bool createFailed = false;
    auto source = (*module)->open(format, bytes.data(), bytes.size(), path, error, createFailed);
    EXPECT_TRUE(source) << error;
    return source;
}

void expectSameSpec(const SourceSpec& a, const SourceSpec& b, const std::string& what) {
    EXPECT_EQ(a.width, b.width) << what;
    EXPECT_EQ(a.height, b.height) << what;
    EXPECT_EQ(a.nchannels, b.nchannels) << what;
    EXPECT_EQ(a.channelnames, b.channelnames) << what;
    EXPECT_EQ(a.alpha_channel, b.alpha_channel) << what;
    EXPECT_EQ(a.format, b.format) << what;
    EXPECT_EQ(a.tile_width, b.tile_width) << what;
    EXPECT_EQ(a.tile_height, b.tile_height) << what;
    ASSERT_EQ(a.extra_attribs.size(), b.extra_attribs.size()) << what;
    for (size_t i = 0; i < a.extra_attribs.size(); ++i) {
        const auto& x = a.extra_attribs[i];
        const auto& y = b.extra_attribs[i];
        EXPECT_EQ(x.name, y.name) << what;
        EXPECT_EQ(x.text, y.text) << what << " " << x.name;
        EXPECT_EQ(x.isFloat, y.isFloat) << what << " " << x.name;
        EXPECT_EQ(x.hasNumber, y.hasNumber) << what << " " << x.name;
        if (x.hasNumber && y.hasNumber) {
            EXPECT_EQ(x.number, y.number) << what << " " << x.name;
        }
    }
}

// Every level's header and every channel's pixels, bit for bit, one channel at a time and all at once.
void expectSameImage(ImageSource& direct, ImageSource& oiio, const std::string& what) {
    for (int level = 0;; ++level) {
        const bool more = direct.seekLevel(level);
        ASSERT_EQ(more, oiio.seekLevel(level)) << what << " level " << level;
        if (!more) break;
        expectSameSpec(direct.spec(), oiio.spec(), what + " level " + std::to_string(level));
        const SourceSpec& spec = oiio.spec();
        const size_t texels = size_t(spec.width) * size_t(spec.height);
        std::vector<std::pair<int, int>> ranges = {{0, spec.nchannels}};
        for (int c = 0; c < spec.nchannels; ++c) ranges.emplace_back(c, c + 1);
        for (const auto& [begin, end] : ranges) {
            std::vector<float> a(texels * size_t(end - begin), -1.0f), b(a.size(), -2.0f);
            std::string errorA, errorB;
            ASSERT_TRUE(direct.read(level, begin, end, a.data(), errorA)) << what << ": " << errorA;
            ASSERT_TRUE(oiio.read(level, begin, end, b.data(), errorB)) << what << ": " << errorB;
            EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0)
                << what << " level " << level << " channels " << begin << "-" << end;
        }
    }
}

// A random EXR: a subset of the channel names heightpack and others write, one pixel type, scanline or
// tiled with mip levels, heightpack's text and float attributes.
struct ExrCase {
    std::vector<std::string> channels;
    bool half = false, tiled = false, roundDown = true;
    int width = 0, height = 0, tile = 16;
    Imf::Compression compression = Imf::ZIP_COMPRESSION;
};

ExrCase randomExrCase(std::mt19937& rng) {
    static const std::vector<std::string> names = {"R",      "G",      "B",     "A",    "Y",      "Z",     "Dx",
                                                   "Dy",     "Foam",   "Foam.R", "Foam.A", "height.Y", "X", "layer.X",
                                                   "layer.Y", "alpha", "depth", "u",    "V",      "real",  "imag"};
    ExrCase c;
    std::vector<std::string> pool = names;
    std::shuffle(pool.begin(), pool.end(), rng);
    pool.resize(1 + rng() % 6);
    c.channels = pool;
    c.half = rng() % 2;
    c.tiled = rng() % 2;
    c.roundDown = rng() % 2;
    c.width = 1 + int(rng() % 70);
    c.height = 1 + int(rng() % 70);
    const Imf::Compression kinds[] = {Imf::NO_COMPRESSION, Imf::RLE_COMPRESSION, Imf::ZIPS_COMPRESSION,
                                      Imf::ZIP_COMPRESSION, Imf::PIZ_COMPRESSION};
    c.compression = kinds[rng() % 5];
    return c;
}

void writeExr(const std::string& path, const ExrCase& c, std::mt19937& rng) {
    Imf::Header header(c.width, c.height);
    header.compression() = c.compression;
    const Imf::PixelType type = c.half ? Imf::HALF : Imf::FLOAT;
    for (const std::string& n : c.channels) header.channels().insert(n, Imf::Channel(type));
    header.insert("heightpack:layout", Imf::StringAttribute("plain"));
    header.insert("heightpack:heightScale", Imf::FloatAttribute(std::uniform_real_distribution<float>(0.001f, 100.0f)(rng)));
    header.insert("heightpack:tileWidth", Imf::FloatAttribute(float(rng() % 1000) / 7.0f));
    header.insert("wrapmodes", Imf::StringAttribute("periodic,periodic"));
    if (rng() % 2) header.insert("capDate", Imf::StringAttribute("2026:12:05 01:57:56"));  // OpenImageIO: DateTime
    if (rng() % 2) header.insert("Software", Imf::StringAttribute("a tool"));
    if (rng() % 2) header.insert("frames", Imf::IntAttribute(int(rng() % 2000) - 1000));
    std::uniform_real_distribution<float> value(-1000.0f, 1000.0f);
    const size_t n = c.channels.size();
    auto fill = [&](int w, int h, std::vector<float>& f, std::vector<Imath::half>& hf, Imf::FrameBuffer& frame) {
        f.resize(size_t(w) * size_t(h) * n);
        for (float& v : f) v = value(rng);
        hf.assign(f.begin(), f.end());
        for (size_t k = 0; k < n; ++k) {
            char* base = c.half ? reinterpret_cast<char*>(hf.data() + k) : reinterpret_cast<char*>(f.data() + k);
            const size_t size = c.half ? sizeof(Imath::half) : sizeof(float);
            frame.insert(c.channels[k], Imf::Slice(type, base, size * n, size * n * size_t(w)));
        }
    };
    std::vector<float> f;
    std::vector<Imath::half> hf;
    if (!c.tiled) {
        Imf::FrameBuffer frame;
        fill(c.width, c.height, f, hf, frame);
        Imf::OutputFile out(path.c_str(), header);
        out.setFrameBuffer(frame);
        out.writePixels(c.height);
        return;
    }
    header.setTileDescription(
        Imf::TileDescription(c.tile, c.tile, Imf::MIPMAP_LEVELS, c.roundDown ? Imf::ROUND_DOWN : Imf::ROUND_UP));
    Imf::TiledOutputFile out(path.c_str(), header);
    for (int level = 0; level < out.numLevels(); ++level) {
        Imf::FrameBuffer frame;
        fill(out.levelWidth(level), out.levelHeight(level), f, hf, frame);
        out.setFrameBuffer(frame);
        out.writeTiles(0, out.numXTiles(level) - 1, 0, out.numYTiles(level) - 1, level);
    }
}

TEST(DirectDecode, ExrFamilyMatchesOpenImageIO) {
    ScratchDir dir;
    std::mt19937 rng(20261205);
    int decoded = 0;
    const int cases = 60;
    for (int i = 0; i < cases; ++i) {
        const ExrCase c = randomExrCase(rng);
        const std::string path = dir.file("case" + std::to_string(i) + ".exr");
        writeExr(path, c, rng);
        const std::vector<unsigned char> bytes = readBytes(path);
        auto direct = detail::openExrDirectly(bytes.data(), bytes.size(), path);
        auto oiio = throughModule("openexr", bytes, path);
        ASSERT_TRUE(oiio);
        if (!direct) continue;
        ++decoded;
        EXPECT_STREQ(direct->decoder(), "openexr");
        expectSameSpec(direct->spec(), oiio->spec(), path);
        expectSameImage(*direct, *oiio, path);
    }
    // Every file of the family is within what the direct decoder presents: none is left to OpenImageIO.
    EXPECT_EQ(decoded, cases);
}

TEST(DirectDecode, ExrThatOpenImageIOPresentsItsOwnWayIsLeftToIt) {
    ScratchDir dir;
    const std::string path = dir.file("owner.exr");
    Imf::Header header(4, 4);
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    header.insert("owner", Imf::StringAttribute("someone"));  // OpenImageIO calls it Copyright
    header.insert("origin", Imf::V2iAttribute(Imath::V2i(1, 2)));  // a type OpenImageIO turns into its own
    std::vector<float> pixels(16, 0.5f);
    Imf::FrameBuffer frame;
    frame.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(pixels.data()), sizeof(float), 4 * sizeof(float)));
    {
        Imf::OutputFile out(path.c_str(), header);
        out.setFrameBuffer(frame);
        out.writePixels(4);
    }
    const std::vector<unsigned char> bytes = readBytes(path);
    EXPECT_FALSE(detail::openExrDirectly(bytes.data(), bytes.size(), path));
}

TEST(DirectDecode, GreyPngFamilyMatchesOpenImageIO) {
    ScratchDir dir;
    std::mt19937 rng(7);
    for (int i = 0; i < 24; ++i) {
        const int width = 1 + int(rng() % 90), height = 1 + int(rng() % 90), bits = rng() % 2 ? 8 : 16;
        const Image image = randomImage(width, height, unsigned(i));
        std::vector<std::pair<std::string, std::string>> text = {{"heightpack:layout", "synthesised"},
                                                                 {"heightpack:heightScale", std::to_string(i * 0.37)},
                                                                 {"heightpack:seed", "x" + std::to_string(i)}};
        text.resize(size_t(i % 4));
        const std::string path = dir.file("case" + std::to_string(i) + ".png");
        const std::vector<unsigned char> bytes = detail::encodeGreyPng(image, bits, text, 1);
        auto direct = detail::openPngDirectly(bytes, path);
        ASSERT_TRUE(direct) << path;
        auto oiio = throughModule("png", bytes, path);
        ASSERT_TRUE(oiio);
        expectSameSpec(direct->spec(), oiio->spec(), path);
        expectSameImage(*direct, *oiio, path);
    }
}

// Text chunks as other tools write them (oiiotool's Software and Exif:ImageHistory, free keys, numbers),
// and those OpenImageIO renames, decodes or merges (Description, Author, Title, XMP, Exif, a key again in
// another case, one of its own names): each file is read directly exactly as OpenImageIO reads it, or
// left to it; the plain keys are always read directly.
TEST(DirectDecode, GreyPngTextChunksMatchOpenImageIOOrAreLeftToIt) {
    ScratchDir dir;
    std::mt19937 rng(11);
    const std::vector<std::pair<std::string, bool>> keys = {  // the key, and whether OpenImageIO keeps it as written
        {"Software", true}, {"Exif:ImageHistory", true}, {"Comment", true}, {"Source", true}, {"heightpack:layout", true},
        {"Copyright", true}, {"Creation Time", true}, {"Description", false}, {"author", false}, {"Title", false},
        {"XML:com.adobe.xmp", false}, {"Raw profile type exif", false}, {"oiio:ColorSpace", false},
        {"oiio:UnassociatedAlpha", false}};
    const std::vector<std::string> values = {"OpenImageIO 2.4.7.1 : oiiotool --pattern noise 64x64 1 -o map.png", "42", "-1.5e3",
                                             "", "Gaussian noise, blurred", "1 2"};
    int direct = 0;
    for (int i = 0; i < 120; ++i) {
        const int width = 1 + int(rng() % 40), height = 1 + int(rng() % 40), bits = rng() % 2 ? 8 : 16;
        std::vector<std::pair<std::string, std::string>> text;
        bool plain = true;
        for (size_t n = rng() % 4; n > 0; --n) {
            auto [key, kept] = keys[rng() % keys.size()];
            if (rng() % 5 == 0) std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c) { return char(std::toupper(c)); });
            for (const auto& [earlier, value] : text) kept = kept && !std::equal(key.begin(), key.end(), earlier.begin(), earlier.end(),
                                                                        [](char a, char b) { return std::tolower(a) == std::tolower(b); });
            plain = plain && kept;
            text.emplace_back(key, values[rng() % values.size()]);
        }
        const std::string path = dir.file("text" + std::to_string(i) + ".png");
        const std::vector<unsigned char> bytes = detail::encodeGreyPng(randomImage(width, height, unsigned(i)), bits, text, 1);
        auto oiio = throughModule("png", bytes, path);
        ASSERT_TRUE(oiio);
        auto fast = detail::openPngDirectly(bytes, path);
        if (plain) {
            EXPECT_TRUE(fast) << path << " has only keys OpenImageIO keeps as written";
        }
        if (!fast) continue;
        ++direct;
        expectSameSpec(fast->spec(), oiio->spec(), path);
        expectSameImage(*fast, *oiio, path);
    }
    EXPECT_GE(direct, 40);
}

// A map as oiiotool writes it (OpenImageIO's own PNG writer: an oFFs chunk, then Software and
// Exif:ImageHistory) is read without the format module, as the module reads it.
TEST(DirectDecode, OiiotoolPngIsReadDirectly) {
    ScratchDir dir;
    const std::string path = dir.file("oiiotool.png");
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(33, 17, 1, OIIO::TypeDesc::UINT8);
    spec.attribute("Software", "OpenImageIO 2.4.7.1 : oiiotool --pattern noise 33x17 1 -d uint8 -o oiiotool.png");
    spec.attribute("Exif:ImageHistory", "oiiotool --pattern noise 33x17 1 -d uint8 -o oiiotool.png");
    const Image values = randomImage(33, 17, 3);
    ASSERT_TRUE(out->open(path, spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, values.pixels.data()));
    ASSERT_TRUE(out->close());
    const std::vector<unsigned char> bytes = readBytes(path);
    auto fast = detail::openPngDirectly(bytes, path);
    ASSERT_TRUE(fast);
    auto oiio = throughModule("png", bytes, path);
    ASSERT_TRUE(oiio);
    expectSameSpec(fast->spec(), oiio->spec(), path);
    expectSameImage(*fast, *oiio, path);
}

TEST(DirectDecode, PngOutsideTheGreyFamilyIsLeftToOpenImageIO) {
    ScratchDir dir;
    const std::string path = dir.file("colour.png");
    writeImage(path, 8, 8, 3, std::vector<float>(8 * 8 * 3, 0.25f), OIIO::TypeDesc::UINT8);
    EXPECT_FALSE(detail::openPngDirectly(readBytes(path), path));
    // A damaged chunk: refused by OpenImageIO at open, so left to it.
    std::vector<unsigned char> bytes = detail::encodeGreyPng(randomImage(8, 8, 4), 8, {{"heightpack:layout", "plain"}}, 1);
    bytes[44] ^= 0x20;  // inside the tEXt chunk's text: its CRC no longer matches
    EXPECT_FALSE(detail::openPngDirectly(bytes, path));
}

}  // namespace
}  // namespace heightpack::test
