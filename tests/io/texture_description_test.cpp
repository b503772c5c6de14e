// describeTexture: every key of the schema it types, each with good values (which read as the values the
// writers mean) and a family of damaged ones (which are bad input naming the file and the key), and the
// channel map of every layout pack and synth write, checked against the channel lists written out by hand.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "heightpack/io/texture_description.hpp"

using namespace heightpack;

namespace {

Result<TextureDescription> describe(const Attributes& attributes, const std::vector<std::string>& channels = {"R", "G", "B", "A"},
                                    const std::string& sampleType = "float") {
    return describeTexture("t.ktx2", attributes, channels, sampleType);
}

void expectDamaged(const Attributes& attributes, const std::string& key, const std::vector<std::string>& channels = {"R", "G", "B", "A"}) {
    const auto d = describe(attributes, channels);
    ASSERT_FALSE(d) << key << " = " << (attributes.empty() ? "" : attributes.back().second);
    EXPECT_EQ(d.error().kind, ErrorKind::BadInput);
    EXPECT_EQ(d.error().path, "t.ktx2");
    EXPECT_NE(d.error().what.find(key), std::string::npos) << d.error().what;
}

}  // namespace

TEST(TextureDescription, EveryLayoutWordHeightpackWritesReadsAsItsKindAndOthersAreDamaged) {
    struct Word {
        std::string text;
        TextureKind kind;
        std::optional<Layout> layout;
    };
    for (const Word& w : std::vector<Word>{{"neighbour4", TextureKind::Heights, Layout::Neighbour4},
                                           {"plain", TextureKind::Heights, Layout::Plain},
                                           {"normal", TextureKind::Normals, Layout::Rgb},
                                           {"normalXY", TextureKind::Normals, Layout::Xy},
                                           {"fresnel", TextureKind::FresnelRamp, std::nullopt},
                                           {"synthesised", TextureKind::SynthesisedSea, std::nullopt},
                                           {"seamPreview", TextureKind::SeamPreview, std::nullopt},
                                           {"grid heights", TextureKind::GridHeights, std::nullopt},
                                           {"screenshot", TextureKind::Screenshot, std::nullopt}}) {
        const auto d = describe({{"heightpack:layout", w.text}});
        ASSERT_TRUE(d) << w.text << ": " << d.error().what;
        EXPECT_EQ(d->kind, w.kind) << w.text;
        EXPECT_EQ(d->layout, w.layout) << w.text;
        EXPECT_STREQ(layoutWord(*d), w.text.c_str()) << "the word info reports, typed";
    }
    EXPECT_EQ(describe({})->kind, TextureKind::Image);
    for (const char* bad : {"neighbourX", "Neighbour4", "rgb", "xy", "neighbour4 ", " plain", "normals", "x"})
        expectDamaged({{"heightpack:layout", bad}}, "heightpack:layout");
}

TEST(TextureDescription, EnumKeysReadTheirTableWordsAndRefuseOthers) {
    const auto d = describe({{"heightpack:wrap", "clamp"}, {"heightpack:filter", "lanczos3"}, {"heightpack:convention", "directx"},
                             {"heightpack:index", nameOf(FresnelIndex::TwoNdotV)}, {"heightpack:alpha", "slopeVariance"}});
    ASSERT_TRUE(d) << d.error().what;
    EXPECT_EQ(d->wrap, Wrap::Clamp);
    EXPECT_EQ(d->filter, Filter::Lanczos3);
    EXPECT_EQ(d->convention, NormalConvention::DirectX);
    EXPECT_EQ(d->fresnelIndex, FresnelIndex::TwoNdotV);
    EXPECT_EQ(describe({})->wrap, Wrap::Periodic);
    for (const char* key : {"heightpack:wrap", "heightpack:filter", "heightpack:convention", "heightpack:index",
                            "heightpack:alpha", "heightpack:kernel", "heightpack:model", "heightpack:spectrum",
                            "heightpack:spreading"})
        for (const char* bad : {"x", "mirror", "PERIODIC", "1"}) expectDamaged({{key, bad}}, key);
}

TEST(TextureDescription, NumbersAreFiniteAndLoopPeriodsAndLengthsPositive) {
    const auto d = describe({{"heightpack:heightScale", "0.25"}, {"heightpack:heightOffset", "-2"},
                             {"heightpack:loopPeriod", "12"}, {"heightpack:time", "0"}, {"heightpack:tileWidth", "64"}});
    ASSERT_TRUE(d) << d.error().what;
    EXPECT_EQ(d->heightScale, 0.25);
    EXPECT_EQ(d->heightOffset, -2.0);
    EXPECT_EQ(d->units.loopPeriod, 12.0);
    EXPECT_EQ(d->units.time, 0.0);
    EXPECT_EQ(d->units.tileWidth, 64.0);
    for (const char* key : {"heightpack:heightScale", "heightpack:heightOffset", "heightpack:time", "heightpack:ior",
                            "heightpack:texelCentre", "heightpack:maxLookupError", "heightpack:choppiness"})
        for (const char* bad : {"x", "nan", "inf", "-inf", "1e300", "1.5x", ""}) {
            if (*bad) expectDamaged({{key, bad}}, key);
        }
    for (const char* key : {"heightpack:loopPeriod", "heightpack:tileWidth", "heightpack:tileHeight", "heightpack:heightRange"})
        for (const char* bad : {"0", "-1", "-0", "x", "nan", "inf"}) expectDamaged({{key, bad}}, key);
}

TEST(TextureDescription, ChannelsOfEveryLayoutPackAndSynthWrite) {
    const std::vector<std::string> packed = {"R", "G", "B", "A", "Dx.R", "Dx.G", "Dx.B", "Dx.A",
                                             "Dy.R", "Dy.G", "Dy.B", "Dy.A", "Foam.R", "Foam.G", "Foam.B", "Foam.A"};
    auto d = describe({{"heightpack:layout", "neighbour4"}, {"heightpack:displacement", "neighbour4"}, {"heightpack:foam", "neighbour4"}}, packed);
    ASSERT_TRUE(d) << d.error().what;
    EXPECT_EQ(d->channels.heights, (std::vector<int>{0, 1, 2, 3}));
    EXPECT_EQ(d->channels.dx, (std::vector<int>{4, 5, 6, 7}));
    EXPECT_EQ(d->channels.dy, (std::vector<int>{8, 9, 10, 11}));
    EXPECT_EQ(d->channels.foam, (std::vector<int>{12, 13, 14, 15}));
    // Foam first in the file: the map follows the names, not the order.
    d = describe({{"heightpack:layout", "plain"}, {"heightpack:displacement", "plain"}, {"heightpack:foam", "plain"}}, {"Foam", "Dy", "Dx", "Y"});
    ASSERT_TRUE(d) << d.error().what;
    EXPECT_EQ(d->channels.heights, (std::vector<int>{3}));
    EXPECT_EQ(d->channels.dx, (std::vector<int>{2}));
    EXPECT_EQ(d->channels.dy, (std::vector<int>{1}));
    EXPECT_EQ(d->channels.foam, (std::vector<int>{0}));
    d = describe({{"heightpack:layout", "synthesised"}}, {"Y", "Dx", "Dy"});
    ASSERT_TRUE(d) << d.error().what;
    EXPECT_EQ(d->channels.heights, (std::vector<int>{0}));
    EXPECT_EQ(d->channels.dx, (std::vector<int>{1}));
    EXPECT_TRUE(d->channels.foam.empty());
    d = describe({{"heightpack:layout", "neighbour4"}});
    ASSERT_TRUE(d);
    EXPECT_FALSE(d->channels.shift());
    // Recorded companions without their channels, a packed file without four channels: damaged.
    expectDamaged({{"heightpack:layout", "neighbour4"}, {"heightpack:displacement", "neighbour4"}}, "heightpack:displacement");
    expectDamaged({{"heightpack:layout", "neighbour4"}, {"heightpack:foam", "neighbour4"}}, "heightpack:foam");
    for (const char* bad : {"neighbourX", "normal", "x"})
        expectDamaged({{"heightpack:layout", "neighbour4"}, {"heightpack:displacement", bad}}, "heightpack:displacement", packed);
    EXPECT_FALSE(describe({{"heightpack:layout", "neighbour4"}}, {"Y"}));
    expectDamaged({{"heightpack:layers", "heights,Dz"}}, "heightpack:layers");
}

TEST(TextureDescription, LookupErrorsAreOneNonNegativeNumberALevel) {
    const auto d = describe({{"heightpack:lookupError", "0.5,0.25,0"}});
    ASSERT_TRUE(d) << d.error().what;
    EXPECT_EQ(d->lookupErrors, (std::vector<double>{0.5, 0.25, 0.0}));
    for (const char* bad : {"x", "0.5,,0", "0.5,", "-1", "0.5;0.25", "nan,0"})
        expectDamaged({{"heightpack:lookupError", bad}}, "heightpack:lookupError");
}

TEST(TextureDescription, PixelTypesAreTheWritersEnum) {
    EXPECT_EQ(describe({}, {"R"}, "half")->pixelType, PixelType::Half);
    EXPECT_EQ(describe({}, {"R"}, "uint16")->pixelType, PixelType::Uint16);
    EXPECT_EQ(describe({}, {"R"}, "float")->pixelType, PixelType::Float);
    EXPECT_EQ(describe({}, {"R"}, "uint8")->pixelType, std::nullopt);
    EXPECT_EQ(describe({}, {"R"}, "uint8")->componentBytes, 1);
    EXPECT_EQ(describe({}, {"R"}, "half")->componentBytes, 2);
}
