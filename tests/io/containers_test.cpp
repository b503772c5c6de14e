// KTX2 and DDS, end to end: every container x pixel type x output kind (packed, plain, normal, fresnel)
// written by the heightpack binary, read back by heightpack's own reader and by an independent one
// (tests/io/read_container.mjs: ktx-parse from npm for KTX2; nvddsinfo and Microsoft's DX10 layout for
// DDS), the two agreeing, and both equal to a chain computed here (halves rounded by a conversion
// written here, from the definition). EXR outputs are read by OpenImageIO.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "heightpack/core/fresnel.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/normal.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/read.hpp"
#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
using nlohmann::json;

namespace {

// Nearest binary16 value to v, ties to even, from the definition: a 10-bit fraction at v's binary
// exponent (subnormals at 2^-24 steps).
double referenceHalf(double v) {
    if (v == 0.0) return 0.0;
    const int e = std::max(int(std::floor(std::log2(std::fabs(v)))), -14);
    const double ulp = std::ldexp(1.0, e - 10);
    return std::nearbyint(v / ulp) * ulp;  // the default rounding mode rounds ties to even
}

float smooth(int x, int y) { return static_cast<float>(0.5 + 0.35 * std::sin(x * 0.39) * std::cos(y * 0.27)); }

// Texel (i,j) holds H(i,j), H(i+1,j), H(i,j+1), H(i+1,j+1), wrapped: written from design.md.
Image referencePack(const Image& h) {
    Image out(h.width, h.height, 4);
    for (int y = 0; y < h.height; ++y)
        for (int x = 0; x < h.width; ++x)
            for (int c = 0; c < 4; ++c)
                out.at(x, y, c) = h.at(referenceWrap(x + (c & 1), h.width, true), referenceWrap(y + (c >> 1), h.height, true));
    return out;
}

Image withAlpha(const Image& rgb) {
    if (rgb.channels != 3) return rgb;
    Image out(rgb.width, rgb.height, 4, 1.0f);
    for (size_t t = 0; t < rgb.texelCount(); ++t)
        for (int c = 0; c < 3; ++c) out.pixels[t * 4 + c] = rgb.pixels[t * 3 + c];
    return out;
}

struct Output {
    std::string kind;            // packed, plain, normal, fresnel
    std::string path;
    std::vector<Image> expected;  // float chain, as the container holds it (RGB padded for KTX2/DDS)
};

struct Case {
    std::string container;  // exr, ktx2, dds
    std::string pixelType;  // float, half, uint16
    bool zstd = false;
};

std::string caseName(const testing::TestParamInfo<Case>& info) {
    return info.param.container + "_" + info.param.pixelType + (info.param.zstd ? "_zstd" : "");
}

class Containers : public testing::TestWithParam<Case> {};

// Expected stored value of v: the float itself, its half, or the 16-bit normalised value.
double stored(double v, const std::string& type, const Normalisation& n) {
    if (type == "half") return referenceHalf(v);
    if (type == "uint16") return n.offset + n.scale * (std::nearbyint((v - n.offset) / n.scale * 65535.0) / 65535.0);
    return v;
}

}  // namespace

TEST_P(Containers, EveryOutputKindReadsBackTheSameThroughBothReaders) {
    const Case& p = GetParam();
    if (p.container != "exr" && !independentReaderInstalled())
        HEIGHTPACK_WITHOUT_ORACLE("the independent readers are not installed: run scripts/test.sh (npm install into "
                     << HEIGHTPACK_NPM_DIR << ")");
    ScratchDir dir;
    const std::string ext = "." + p.container;
    writeImage(dir.file("map.png"), makeImage(32, 16, smooth), OIIO::TypeDesc::UINT16);
    auto loaded = loadHeightMap(dir.file("map.png"));
    ASSERT_TRUE(loaded.ok());
    const std::vector<Image> chain = generateMipChain(loaded->heights, Filter::Kaiser);

    std::vector<std::string> extra = {"--pixel-type", p.pixelType, "--quiet"};
    if (p.zstd) extra.insert(extra.end(), {"--compression", "zstd"});
    std::vector<std::string> pack = {"pack", dir.file("map.png"), "-o", dir.file("packed" + ext), "--emit-plain",
                                     dir.file("plain" + ext)};
    std::vector<std::string> normal = {"normal", dir.file("map.png"), "--tile-size", "8m", "--height", "0.5m",
                                       "-o", dir.file("normal" + ext)};
    std::vector<std::string> fresnel = {"fresnel", "--size", "64", "-o", dir.file("fresnel" + ext)};
    const std::vector<std::vector<std::string>*> runs = {&pack, &normal, &fresnel};
    const bool refused = p.container == "exr" && p.pixelType == "uint16";
    for (auto* args : runs) {
        if (args == &fresnel && p.zstd) args->insert(args->end(), {"--pixel-type", p.pixelType, "--quiet"});
        else args->insert(args->end(), extra.begin(), extra.end());
        const ProcessResult r = heightpackRun(*args);
        if (refused) {  // an EXR has no 16-bit normalised channels: a usage error, nothing written
            EXPECT_EQ(r.code, 2) << r.err;
            EXPECT_NE(r.err.find("uint16"), std::string::npos) << r.err;
        } else {
            ASSERT_EQ(r.code, 0) << (*args)[0] << ": " << r.err;
        }
    }
    if (refused) {
        EXPECT_EQ(dir.listing(), std::vector<std::string>{"map.png"});
        return;
    }

    std::vector<Output> outputs;
    {
        Output o{"packed", dir.file("packed" + ext), {}};
        for (const Image& level : chain) o.expected.push_back(referencePack(level));
        outputs.push_back(o);
        outputs.push_back({"plain", dir.file("plain" + ext), chain});
        NormalOptions n;
        n.tileWidth = 8.0;
        n.heightRange = 0.5;
        Output normals{"normal", dir.file("normal" + ext), {}};
        for (const Image& level : generateNormalChain(chain, n))
            normals.expected.push_back(p.container == "exr" ? level : withAlpha(level));
        outputs.push_back(normals);
        FresnelOptions f;
        f.size = 64;
        outputs.push_back({"fresnel", dir.file("fresnel" + ext), {makeFresnelRamp(f)}});
    }

    for (const Output& o : outputs) {
        SCOPED_TRACE(o.kind + " " + o.path);
        if (p.container == "exr") {
            // OpenImageIO reads the EXR; half channels are widened exactly.
            auto in = OIIO::ImageInput::open(o.path);
            ASSERT_TRUE(in);
            EXPECT_EQ(in->spec().format, p.pixelType == "half" ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
            int level = 0;
            for (; in->seek_subimage(0, level); ++level) {
                ASSERT_LT(level, int(o.expected.size()));
                const Image& e = o.expected[level];
                std::vector<float> pixels(e.pixels.size());
                ASSERT_TRUE(in->read_image(0, level, 0, e.channels, OIIO::TypeDesc::FLOAT, pixels.data()));
                for (size_t i = 0; i < pixels.size(); ++i)
                    ASSERT_EQ(double(pixels[i]), stored(e.pixels[i], p.pixelType, {})) << "level " << level << " #" << i;
            }
            EXPECT_EQ(level, int(o.expected.size()));
            continue;
        }

        auto own = readGpuTexture(o.path);
        ASSERT_TRUE(own.ok()) << own.error().what;
        const json other = readIndependently(o.path);
        ASSERT_FALSE(other.is_null());
        const TexelFormatInfo& f = texelFormatInfo(own->format);
        EXPECT_EQ(other["format"], p.container == "ktx2" ? f.vkName : f.dxgiName);
        EXPECT_EQ(f.channels, o.expected[0].channels == 3 ? 4 : o.expected[0].channels);
        EXPECT_EQ(pixelTypeName(pixelTypeOf(own->format)), p.pixelType);
        const bool zstd = p.zstd && o.kind != "fresnel";  // fresnel has no --compression
        EXPECT_EQ(own->supercompression == Supercompression::Zstd, zstd);
        ASSERT_EQ(own->levels.size(), o.expected.size());
        ASSERT_EQ(other["levels"].size(), o.expected.size());
        EXPECT_EQ(other["width"], o.expected[0].width);
        EXPECT_EQ(other["height"], o.expected[0].height);

        Normalisation n;
        if (p.pixelType == "uint16") {
            ASSERT_TRUE(own->normalisation.has_value());
            n = *own->normalisation;
            double lo = 1e30, hi = -1e30;
            for (const Image& level : o.expected)
                for (float v : level.pixels) lo = std::min(lo, double(v)), hi = std::max(hi, double(v));
            // Normalised to the chain's range (widened at most to the painted map's 16-bit grid).
            EXPECT_LE(n.offset, lo + 1e-6);
            EXPECT_GE(n.offset + n.scale, hi - 1e-6);
            EXPECT_LE(n.scale, 2.0 * (hi - lo) + 1e-6);  // at least half the codes in use
        }
        if (p.container == "ktx2") {
            json expectedKeys = json::object();
            for (const auto& [k, v] : own->keyValues) expectedKeys[k] = v;
            EXPECT_EQ(other["keyValues"], expectedKeys);
            EXPECT_EQ(other["keyValues"].value("KTXwriter", "").rfind("heightpack ", 0), 0u);
            const std::string layout = o.kind == "packed" ? "neighbour4" : o.kind;
            EXPECT_EQ(other["keyValues"].value("heightpack:layout", ""), layout);
            if (zstd) {
                EXPECT_EQ(other["keyValues"].value("KTXwriterScParams", ""), "--zstd 9");
            }
            EXPECT_EQ(other["supercompressionScheme"], zstd ? 2 : 0);
            // The Data Format Descriptor: RGBSDA, linear, a sample per channel of the format's width.
            const json& dfd = other["dfd"];
            EXPECT_EQ(dfd["colorModel"], 1);
            EXPECT_EQ(dfd["transferFunction"], 1);
            EXPECT_EQ(dfd["bytesPlane0"], f.bytesPerTexel());
            ASSERT_EQ(dfd["samples"].size(), size_t(f.channels));
            for (int c = 0; c < f.channels; ++c) {
                const json& s = dfd["samples"][c];
                EXPECT_EQ(s["bitOffset"], c * 8 * f.bytesPerComponent());
                EXPECT_EQ(s["bitLength"], 8 * f.bytesPerComponent() - 1);
                EXPECT_EQ(s["channelType"].get<int>() & 0xF, c == 3 ? 15 : c);
                EXPECT_EQ((s["channelType"].get<int>() & 0x80) != 0, p.pixelType != "uint16");
            }
        } else {
            // DDS records layout, wrap and the normalisation in its reserved header words; the
            // independent reader decodes the record from the header's bytes and agrees.
            const std::string layout = o.kind == "packed" ? "neighbour4" : o.kind;
            EXPECT_EQ(findAttribute(own->keyValues, "heightpack:layout"), layout);
            EXPECT_EQ(other["keyValues"].value("heightpack:layout", ""), layout);
            if (o.kind != "fresnel") {
                EXPECT_EQ(findAttribute(own->keyValues, "heightpack:wrap"), "periodic");
                EXPECT_EQ(other["keyValues"].value("heightpack:wrap", ""), "periodic");
            }
        }

        for (size_t level = 0; level < o.expected.size(); ++level) {
            const Image& e = o.expected[level];
            const Image& mine = own->levels[level];
            const json& theirs = other["levels"][level]["values"];
            ASSERT_EQ(mine.width, e.width);
            ASSERT_EQ(mine.height, e.height);
            ASSERT_EQ(theirs.size(), mine.pixels.size());
            const size_t channels = size_t(e.channels == 3 ? 4 : e.channels);
            for (size_t i = 0; i < mine.pixels.size(); ++i) {
                const double v = i % channels < size_t(e.channels) ? e.pixels[i / channels * e.channels + i % channels] : 1.0;
                const double want = stored(v, p.pixelType, n);
                double independent = theirs[i].get<double>();
                if (p.pixelType == "uint16") independent = n.offset + n.scale * (independent / 65535.0);
                const double tolerance = p.pixelType == "uint16" ? 1e-6 * std::max(1.0, double(n.scale)) : 0.0;
                ASSERT_NEAR(double(mine.pixels[i]), want, tolerance) << "level " << level << " #" << i;
                ASSERT_NEAR(independent, want, tolerance) << "level " << level << " #" << i;
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(AllContainersAndPixelTypes, Containers,
                         testing::Values(Case{"exr", "float"}, Case{"exr", "half"}, Case{"exr", "uint16"},
                                         Case{"ktx2", "float"}, Case{"ktx2", "half"}, Case{"ktx2", "uint16"},
                                         Case{"ktx2", "float", true}, Case{"ktx2", "half", true},
                                         Case{"ktx2", "uint16", true}, Case{"dds", "float"}, Case{"dds", "half"},
                                         Case{"dds", "uint16"}),
                         caseName);

TEST(ContainersUint16, A16BitPaintedMapIsExactAtLevel0) {
    ScratchDir dir;
    std::vector<float> painted(64 * 32);
    for (size_t i = 0; i < painted.size(); ++i) painted[i] = float((i * 2654435761u) % 50000 + 7000) / 65535.0f;
    writeImage(dir.file("map.png"), 64, 32, 1, painted, OIIO::TypeDesc::UINT16);
    for (const char* name : {"plain.ktx2", "plain.dds"}) {
        SCOPED_TRACE(name);
        const ProcessResult r = heightpackRun({"pack", dir.file("map.png"), "--pixel-type", "uint16", "--filter", "box",
                                               "--quiet", "-o", dir.file(std::string("p_") + name), "--emit-plain",
                                               dir.file(name)});
        ASSERT_EQ(r.code, 0) << r.err;
        auto t = readGpuTexture(dir.file(name));
        ASSERT_TRUE(t.ok()) << t.error().what;
        ASSERT_TRUE(t->normalisation.has_value());
        // Each of the painted map's 1/65535 steps is a whole number of codes, from an offset on its grid.
        const long split = std::lround(1.0 / t->normalisation->scale);
        EXPECT_GE(split, 1);
        EXPECT_FLOAT_EQ(t->normalisation->scale, 1.0f / float(split));
        const long kLo = std::lround(t->normalisation->offset * 65535.0);
        EXPECT_FLOAT_EQ(t->normalisation->offset, float(kLo) / 65535.0f);
        const auto& bytes = t->levelBytes[0];
        ASSERT_EQ(bytes.size(), painted.size() * 2);
        for (size_t i = 0; i < painted.size(); ++i) {
            const long u = long(bytes[2 * i]) | long(bytes[2 * i + 1]) << 8;
            ASSERT_EQ(u, split * (std::lround(painted[i] * 65535.0) - kLo)) << "texel " << i;
            ASSERT_NEAR(t->levels[0].pixels[i], painted[i], 3e-7) << "texel " << i;
        }
    }
}

TEST(ContainersCli, SameBytesWhateverTheThreadCount) {
    ScratchDir dir;
    // Levels of many bands (a band is at most 1 MiB, 64 rows under Zstandard).
    writeImage(dir.file("map.png"), makeImage(512, 1024, smooth), OIIO::TypeDesc::UINT16);
    for (const std::string name : {"zstd.ktx2", "a.ktx2", "a.dds"}) {
        for (const char* type : {"float", "half", "uint16"}) {
            std::vector<std::vector<unsigned char>> outputs;
            for (const char* threads : {"1", "3"}) {
                std::vector<std::string> args = {"pack", dir.file("map.png"), "--pixel-type", type, "--threads",
                                                 threads, "--quiet", "-o", dir.file(name)};
                if (name == "zstd.ktx2") args.insert(args.end(), {"--compression", "zstd"});
                const ProcessResult r = heightpackRun(args);
                ASSERT_EQ(r.code, 0) << r.err;
                outputs.push_back(readBytes(dir.file(name)));
            }
            EXPECT_EQ(outputs[0], outputs[1]) << name << " " << type;
            auto t = readGpuTexture(dir.file(name));
            ASSERT_TRUE(t.ok()) << t.error().what;
            EXPECT_EQ(t->levels.size(), 11u);
        }
    }
}

TEST(ContainersCli, RefusalsExitWithTheContractsCodesAndWriteNothing) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(16, 16, smooth), OIIO::TypeDesc::UINT16);
    struct Refusal {
        std::vector<std::string> args;
        int code;
        std::string mentions;
    };
    const std::vector<Refusal> refusals = {
        // A half cannot hold 85000: bad input (exit 3), nothing written.
        {{"pack", dir.file("map.png"), "--scale", "100000", "--pixel-type", "half", "-o", dir.file("o.ktx2")}, 3, "half"},
        {{"pack", dir.file("map.png"), "--scale", "100000", "--pixel-type", "half", "-o", dir.file("o.dds")}, 3, "half"},
        {{"pack", dir.file("map.png"), "--scale", "100000", "--pixel-type", "half", "-o", dir.file("o.exr")}, 3, "half"},
        {{"pack", dir.file("map.png"), "--pixel-type", "uint16", "-o", dir.file("o.exr")}, 2, "uint16"},
        {{"pack", dir.file("map.png"), "--compression", "zstd", "-o", dir.file("o.dds")}, 2, "compression"},
        {{"pack", dir.file("map.png"), "--compression", "zstd", "-o", dir.file("o.exr")}, 2, "zstd"},
        {{"pack", dir.file("map.png"), "--compression", "piz", "-o", dir.file("o.ktx2")}, 2, "zstd"},
        {{"normal", dir.file("map.png"), "--tile-size", "8m", "--height", "1m", "--pixel-type", "half", "-o",
          dir.file("o.png")},
         2, "pixel-type"},
    };
    for (const Refusal& r : refusals) {
        const ProcessResult run = heightpackRun(r.args);
        EXPECT_EQ(run.code, r.code) << r.args.back() << ": " << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
        EXPECT_NE(run.err.find(r.mentions), std::string::npos) << run.err;
        EXPECT_EQ(dir.listing(), std::vector<std::string>{"map.png"}) << r.args.back();
    }
}

TEST(ContainersCli, InfoReadsKtx2AndDdsWithItsOwnReader) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(32, 32, smooth), OIIO::TypeDesc::UINT16);
    for (const std::string name : {"m.ktx2", "m.dds"}) {
        ASSERT_EQ(heightpackRun({"pack", dir.file("map.png"), "--pixel-type", "half", "--quiet", "-o", dir.file(name)}).code, 0);
        const ProcessResult r = heightpackRun({"info", dir.file(name), "--json"});
        ASSERT_EQ(r.code, 0) << r.err;
        const json doc = json::parse(r.out);
        EXPECT_EQ(doc["levelCount"], 6);
        EXPECT_EQ(doc["pixelType"], "half");
        EXPECT_EQ(doc["layout"], "neighbour4");
        EXPECT_NE(doc["format"].get<std::string>().find("R16G16B16A16"), std::string::npos) << doc["format"];
        EXPECT_EQ(doc["levels"][5]["width"], 1);
        EXPECT_EQ(doc["levels"][0]["channels"].size(), 4u);
        const ProcessResult text = heightpackRun({"info", dir.file(name)});
        ASSERT_EQ(text.code, 0) << text.err;
        EXPECT_NE(text.out.find("layout"), std::string::npos) << text.out;
    }
    // A truncated KTX2: bad input, one line naming the file.
    auto bytes = readBytes(dir.file("m.ktx2"));
    bytes.resize(bytes.size() / 2);
    writeBytes(dir.file("cut.ktx2"), bytes);
    const ProcessResult r = heightpackRun({"info", dir.file("cut.ktx2")});
    EXPECT_EQ(r.code, 3) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("cut.ktx2"), std::string::npos) << r.err;
}
