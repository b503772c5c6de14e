// io's name tables (channels, compression) and the typed schema of the heightpack:* attributes.
#include <gtest/gtest.h>

#include "heightpack/core/names.hpp"
#include "heightpack/io/attributes.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/read.hpp"

using namespace heightpack;

TEST(Attributes, IoNameTables) {
    using V = std::vector<std::string>;
    EXPECT_EQ(allNames<ChannelSelect>(), (V{"r", "g", "b", "a", "luma"}));
    EXPECT_EQ(allNames<Compression>(), (V{"none", "rle", "zips", "zip", "piz"}));
    EXPECT_EQ(joinedNames<ChannelSelect>("|"), "r|g|b|a|luma");
    for (const std::string& name : allNames<Compression>()) EXPECT_STREQ(nameOf(*parseName<Compression>(name)), name.c_str());
    for (const std::string& name : allNames<ChannelSelect>()) EXPECT_STREQ(nameOf(*parseName<ChannelSelect>(name)), name.c_str());
    // Auto is what no choice means and Named needs the channel's own name: neither has a name.
    EXPECT_STREQ(nameOf(ChannelSelect::Auto), "");
    EXPECT_STREQ(nameOf(ChannelSelect::Named), "");
    EXPECT_EQ(parseName<ChannelSelect>("auto"), std::nullopt);
}

// Enums go into headers by name; a variance normal map's header keeps its historical word.
TEST(Attributes, SchemaWritesEnumsByName) {
    const ExrAttribute wrap = attribute(attr::wrap, Wrap::Clamp);
    EXPECT_EQ(wrap.name, "heightpack:wrap");
    EXPECT_EQ(std::get<std::string>(wrap.value), "clamp");
    EXPECT_EQ(std::get<std::string>(attribute(attr::alpha, NormalAlpha::SlopeVariance).value), "slopeVariance");
    EXPECT_EQ(std::get<std::string>(attribute(attr::alpha, NormalAlpha::Height).value), "height");
    EXPECT_EQ(std::get<float>(attribute(attr::heightScale, 2.5f).value), 2.5f);
}

// A layout's word in a header: heights by their names, normal maps as they have always said ("normal")
// and "normalXY" for two channels; each word reads back to its layout.
TEST(Attributes, LayoutsHaveOneWordEachInHeaders) {
    EXPECT_STREQ(attributeText(Layout::Neighbour4), "neighbour4");
    EXPECT_STREQ(attributeText(Layout::Plain), "plain");
    EXPECT_STREQ(attributeText(Layout::Rgb), "normal");
    EXPECT_STREQ(attributeText(Layout::Xy), "normalXY");
    for (const Layout l : {Layout::Neighbour4, Layout::Plain, Layout::Rgb, Layout::Xy})
        EXPECT_EQ(enumFromAttribute<Layout>(attributeText(l)), l);
    EXPECT_EQ(enumFromAttribute<Layout>("fresnel"), std::nullopt);
    EXPECT_EQ(enumFromAttribute<Layout>("rgb"), std::nullopt);  // the CLI's word, not the header's
}
