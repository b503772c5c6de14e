// The cache keys: every field of every options struct the build's steps run with either changes the key
// or is named as one that cannot change an output; equal options give equal keys.
#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "heightpack/bake/build/cache_key.hpp"

namespace heightpack {
namespace {

// One field of T changed from its default, and whether the output can depend on it.
template <class T>
struct FieldChange {
    const char* name;
    void (*change)(T&);
    bool shapesOutput;
};

// Changes each field in turn (from default options) and checks the key text against the field's verdict.
// The count check fails when a struct gains a field this list does not know.
template <class T, std::size_t N>
void expectEveryFieldJudged(const std::array<FieldChange<T>, N>& changes) {
    EXPECT_EQ(N, fieldCount<T>()) << "a field was added: add it to this test's list";
    const std::string base = keyText(T{}, "p.");
    EXPECT_EQ(base, keyText(T{}, "p.")) << "equal options give equal keys";
    EXPECT_NE(cacheKey("1", base, ""), cacheKey("2", base, "")) << "the version is part of the key";
    EXPECT_NE(cacheKey("1", base, "a"), cacheKey("1", base, "b")) << "the input's hash is part of the key";
    for (const FieldChange<T>& c : changes) {
        T changed{};
        c.change(changed);
        const std::string text = keyText(changed, "p.");
        if (c.shapesOutput) {
            EXPECT_NE(text, base) << c.name << " changes the output but not the key";
            EXPECT_NE(cacheKey("1", text, "h"), cacheKey("1", base, "h")) << c.name;
        } else {
            EXPECT_EQ(text, base) << c.name << " cannot change the output, so must not force a rebuild";
        }
    }
}

TEST(CacheKey, FieldCountCountsTheDirectMembersOfAnAggregate) {
    struct Three { int a; std::string b; double c = 1.0; };
    struct Nested { Three t; std::array<double, 3> rgb; };
    EXPECT_EQ(fieldCount<Three>(), 3u);
    EXPECT_EQ(fieldCount<Nested>(), 2u);
}

TEST(CacheKey, LoadOptions) {
    expectEveryFieldJudged(std::array<FieldChange<LoadOptions>, 6>{{
        {"channel", [](LoadOptions& o) { o.channel = ChannelSelect::G; }, true},
        {"channelName", [](LoadOptions& o) { o.channelName = std::string("Z"); }, true},
        {"maxSide", [](LoadOptions& o) { o.maxSide = 64; }, true},
        {"maxTexels", [](LoadOptions& o) { o.maxTexels = 4096; }, true},
        {"silenceDecoderMessages", [](LoadOptions& o) { o.silenceDecoderMessages = true; }, false},
        {"threads", [](LoadOptions& o) { o.threads = 3; }, false},
    }});
}

TEST(CacheKey, MipOptions) {
    expectEveryFieldJudged(std::array<FieldChange<MipOptions>, 3>{{
        {"filter", [](MipOptions& o) { o.filter = Filter::Box; }, true},
        {"wrap", [](MipOptions& o) { o.wrap = Wrap::Clamp; }, true},
        {"threads", [](MipOptions& o) { o.threads = 5; }, false},
    }});
}

TEST(CacheKey, NormalOptions) {
    expectEveryFieldJudged(std::array<FieldChange<NormalOptions>, 8>{{
        {"tileWidth", [](NormalOptions& o) { o.tileWidth = 2.0; }, true},
        {"tileHeight", [](NormalOptions& o) { o.tileHeight = 2.0; }, true},
        {"heightRange", [](NormalOptions& o) { o.heightRange = 1.0 + 1e-15; }, true},  // every digit counts
        {"kernel", [](NormalOptions& o) { o.kernel = SlopeKernel::Scharr; }, true},
        {"wrap", [](NormalOptions& o) { o.wrap = Wrap::Clamp; }, true},
        {"convention", [](NormalOptions& o) { o.convention = NormalConvention::DirectX; }, true},
        {"alpha", [](NormalOptions& o) { o.alpha = NormalAlpha::SlopeVariance; }, true},
        {"threads", [](NormalOptions& o) { o.threads = 2; }, false},
    }});
}

TEST(CacheKey, FresnelOptions) {
    expectEveryFieldJudged(std::array<FieldChange<FresnelOptions>, 6>{{
        {"ior", [](FresnelOptions& o) { o.ior = 1.5; }, true},
        {"model", [](FresnelOptions& o) { o.model = FresnelModel::Schlick; }, true},
        {"index", [](FresnelOptions& o) { o.index = FresnelIndex::TwoNdotV; }, true},
        {"size", [](FresnelOptions& o) { o.size = 512; }, true},
        {"deep", [](FresnelOptions& o) { o.deep[2] = 0.5; }, true},
        {"shallow", [](FresnelOptions& o) { o.shallow[0] = 0.5; }, true},
    }});
    // Every colour channel counts, and deep and shallow are not interchangeable.
    FresnelOptions swapped;
    std::swap(swapped.deep, swapped.shallow);
    EXPECT_NE(keyText(swapped), keyText(FresnelOptions{}));
    for (int c = 0; c < 3; ++c) {
        FresnelOptions o;
        o.deep[c] += 0.25;
        EXPECT_NE(keyText(o), keyText(FresnelOptions{})) << c;
    }
}

TEST(CacheKey, PackOptions) {
    expectEveryFieldJudged(std::array<FieldChange<PackOptions>, 13>{{
        {"load", [](PackOptions& o) { o.load.channel = ChannelSelect::Luma; }, true},
        {"mip", [](PackOptions& o) { o.mip.filter = Filter::Lanczos3; }, true},
        {"scale", [](PackOptions& o) { o.scale = 2.0f; }, true},
        {"offset", [](PackOptions& o) { o.offset = 0.5f; }, true},
        {"resizeToPowerOfTwo", [](PackOptions& o) { o.resizeToPowerOfTwo = true; }, true},
        {"storage", [](PackOptions& o) { o.storage.pixelType = PixelType::Half; }, true},  // each field: below
        {"plainOutput", [](PackOptions& o) { o.plainOutput = std::string("plain.exr"); }, true},
        {"layout", [](PackOptions& o) { o.layout = Layout::Plain; }, true},
        {"heightRange", [](PackOptions& o) { o.heightRange = 6.0; }, true},
        {"displacement", [](PackOptions& o) { o.shift = true; }, true},
        {"foam", [](PackOptions& o) { o.foam = true; }, true},
        {"version", [](PackOptions& o) { o.version = std::string("9.9"); }, true},
        {"progress", [](PackOptions& o) { o.progress = [](std::string_view, double) {}; }, false},
    }});
    // The same value in two fields gives two keys: the text names each field.
    PackOptions a, b;
    a.scale = 0.5f;
    b.offset = 0.5f;
    a.offset = 0.0f;
    b.scale = 0.0f;
    EXPECT_NE(keyText(a), keyText(b));
}

// The storage every job holds: each field that shapes the bytes is in the key of the jobs that hold it,
// and a zstd level only counts with zstd.
TEST(CacheKey, EveryStorageFieldIsInTheKey) {
    EXPECT_EQ(fieldCount<TextureStorage>(), 7u) << "a field was added: add it to this test's list";
    const std::vector<std::function<void(TextureStorage&)>> changes = {
        [](TextureStorage& s) { s.exrCompression = Compression::Piz; },
        [](TextureStorage& s) { s.pixelType = PixelType::Half; },
        [](TextureStorage& s) { s.tolerance = 1e-4; },
        [](TextureStorage& s) { s.tolerance = 1e-4, s.allowBlockCompression = true; },
        [](TextureStorage& s) { s.tolerance = 1e-4, s.toleranceInDegrees = true; },
        [](TextureStorage& s) { s.supercompression = Supercompression::Zstd; },
        [](TextureStorage& s) { s.supercompression = Supercompression::Zstd, s.zstdLevel = 19; },
    };
    for (size_t i = 0; i < changes.size(); ++i) {
        PackOptions pack;
        NormalJobOptions normal;
        changes[i](pack.storage);
        changes[i](normal.storage);
        EXPECT_NE(keyText(pack), keyText(PackOptions{})) << i;
        EXPECT_NE(keyText(normal), keyText(NormalJobOptions{})) << i;
        for (size_t j = 0; j < i; ++j) {
            PackOptions other;
            changes[j](other.storage);
            EXPECT_NE(keyText(pack), keyText(other)) << i << " " << j;
        }
    }
    PackOptions level;
    level.storage.zstdLevel = 19;  // without zstd it shapes nothing
    EXPECT_EQ(keyText(level), keyText(PackOptions{}));
}

TEST(CacheKey, NormalJobOptions) {
    expectEveryFieldJudged(std::array<FieldChange<NormalJobOptions>, 10>{{
        {"load", [](NormalJobOptions& o) { o.load.maxSide = 16; }, true},
        {"normal", [](NormalJobOptions& o) { o.normal.alpha = NormalAlpha::Height; }, true},
        {"filter", [](NormalJobOptions& o) { o.filter = Filter::Triangle; }, true},
        {"resizeToPowerOfTwo", [](NormalJobOptions& o) { o.resizeToPowerOfTwo = true; }, true},
        {"format", [](NormalJobOptions& o) { o.format = NormalFormat::Png8; }, true},
        {"storage", [](NormalJobOptions& o) { o.storage.exrCompression = Compression::None; }, true},
        {"toleranceMetres", [](NormalJobOptions& o) { o.toleranceMetres = 1e-3; }, true},
        {"layout", [](NormalJobOptions& o) { o.layout = Layout::Xy; }, true},
        {"version", [](NormalJobOptions& o) { o.version = std::string("2"); }, true},
        {"progress", [](NormalJobOptions& o) { o.progress = [](std::string_view, double) {}; }, false},
    }});
}

TEST(CacheKey, CheckOptions) {
    expectEveryFieldJudged(std::array<FieldChange<CheckOptions>, 7>{{
        {"load", [](CheckOptions& o) { o.load.channel = ChannelSelect::R; }, true},
        {"mip", [](CheckOptions& o) { o.mip.wrap = Wrap::Clamp; }, true},
        {"threshold", [](CheckOptions& o) { o.threshold = 3.0; }, true},
        {"look", [](CheckOptions& o) { o.look.echo = 0.5; }, true},
        {"lookFails", [](CheckOptions& o) { o.lookFails = true; }, true},
        {"previewPath", [](CheckOptions& o) { o.previewPath = std::string("p.png"); }, true},
        {"progress", [](CheckOptions& o) { o.progress = [](std::string_view, double) {}; }, false},
    }});
}

// A synthesised sea's key is its spectrum: every parameter shapes the heights.
TEST(CacheKey, SpectrumOptions) {
    expectEveryFieldJudged(std::array<FieldChange<SpectrumOptions>, 17>{{
        {"model", [](SpectrumOptions& o) { o.model = SpectrumModel::Phillips; }, true},
        {"windSpeed", [](SpectrumOptions& o) { o.windSpeed = 12.0; }, true},
        {"windDirection", [](SpectrumOptions& o) { o.windDirection = 30.0; }, true},
        {"fetch", [](SpectrumOptions& o) { o.fetch = 5e4; }, true},
        {"gamma", [](SpectrumOptions& o) { o.gamma = 2.0; }, true},
        {"phillipsAlpha", [](SpectrumOptions& o) { o.phillipsAlpha = 0.01; }, true},
        {"smallWaveLength", [](SpectrumOptions& o) { o.smallWaveLength = 0.1; }, true},
        {"spreading", [](SpectrumOptions& o) { o.spreading = Spreading::Cos2s; }, true},
        {"spreadingExponent", [](SpectrumOptions& o) { o.spreadingExponent = 8.0; }, true},
        {"depth", [](SpectrumOptions& o) { o.depth = 30.0; }, true},
        {"swell", [](SpectrumOptions& o) { o.swell.direction = 90.0; }, true},
        {"tileSize", [](SpectrumOptions& o) { o.tileSize = 128.0; }, true},
        {"size", [](SpectrumOptions& o) { o.size = 64; }, true},
        {"seed", [](SpectrumOptions& o) { o.seed = (uint64_t(1) << 40) + 1; }, true},  // bits past 32 count
        {"loopPeriod", [](SpectrumOptions& o) { o.loopPeriod = 8.0; }, true},
        {"bandLow", [](SpectrumOptions& o) { o.bandLow = 0.1; }, true},
        {"bandHigh", [](SpectrumOptions& o) { o.bandHigh = 2.0; }, true},
    }});
    expectEveryFieldJudged(std::array<FieldChange<SwellOptions>, 5>{{
        {"significantHeight", [](SwellOptions& o) { o.significantHeight = 2.0; }, true},
        {"peakPeriod", [](SwellOptions& o) { o.peakPeriod = 9.0; }, true},
        {"direction", [](SwellOptions& o) { o.direction = 45.0; }, true},
        {"gamma", [](SwellOptions& o) { o.gamma = 3.0; }, true},
        {"spreadingExponent", [](SwellOptions& o) { o.spreadingExponent = 20.0; }, true},
    }});
}

TEST(CacheKey, StringsCannotForgeAnotherField) {
    // A string holding a newline and another field's line must not read like that field.
    PackOptions forged;
    forged.plainOutput = "x\np.packed=0";
    PackOptions plain;
    plain.plainOutput = "x";
    plain.layout = Layout::Plain;
    EXPECT_NE(keyText(forged, "p."), keyText(plain, "p."));
}

TEST(CacheKey, EveryPixelTypeAndEveryToleranceIsItsOwnKey) {
    // A manifest's pixel_type changed from half to uint16, or auto's tolerance changed, must rebuild.
    std::vector<std::string> texts;
    for (const PixelType t : {PixelType::Float, PixelType::Half, PixelType::Uint16}) {
        PackOptions o;
        o.storage.pixelType = t;
        texts.push_back(keyText(o));
    }
    for (const double tolerance : {1e-4, 2e-4}) {
        PackOptions o;
        o.storage.tolerance = tolerance;
        texts.push_back(keyText(o));
    }
    for (size_t i = 0; i < texts.size(); ++i)
        for (size_t j = i + 1; j < texts.size(); ++j) EXPECT_NE(texts[i], texts[j]) << i << " " << j;
    // Float neighbour4 with no height range is the key text from before these fields existed.
    EXPECT_EQ(texts[0].find("tolerance"), std::string::npos);
    EXPECT_EQ(texts[0].find("heightRange"), std::string::npos);
    EXPECT_NE(texts[0].find("packed=1"), std::string::npos);
}

TEST(CacheKey, IsThirtyTwoHexDigits) {
    const std::string key = cacheKey("0.1.0", keyText(PackOptions{}), "0123");
    ASSERT_EQ(key.size(), 32u);
    EXPECT_EQ(key.find_first_not_of("0123456789abcdef"), std::string::npos);
}

}  // namespace
}  // namespace heightpack
