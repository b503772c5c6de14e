#include <gtest/gtest.h>

#include <algorithm>

#include "heightpack/bake/pack_job.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/io/info.hpp"

#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

TEST(Info, ReportsLevelsAttributesAndStatisticsOfAPackedFile) {
    ScratchDir dir;
    const Image map = randomImage(32, 16, 21);
    writeImage(dir.file("map.exr"), map, OIIO::TypeDesc::FLOAT);
    PackOptions options;
    options.mip.wrap = Wrap::Clamp;
    options.mip.filter = Filter::Box;
    ASSERT_TRUE(packHeightMap(dir.file("map.exr"), dir.file("out.exr"), options).ok());

    auto info = readFileInfo(dir.file("out.exr"));
    ASSERT_TRUE(info.ok()) << info.error().what;
    EXPECT_EQ(info->format, "openexr");
    EXPECT_TRUE(info->storedInTiles);
    EXPECT_EQ(info->channelNames, (std::vector<std::string>{"R", "G", "B", "A"}));
    EXPECT_EQ(findAttribute(*info, "heightpack:layout"), "neighbour4");
    EXPECT_EQ(findAttribute(*info, "heightpack:wrap"), "clamp");
    EXPECT_EQ(findAttribute(*info, "heightpack:filter"), "box");

    const auto chain = generateMipChain(map, Filter::Box);
    ASSERT_EQ(info->levels.size(), chain.size());
    for (size_t l = 0; l < chain.size(); ++l) {
        const auto& px = chain[l].pixels;
        double sum = 0.0;
        for (float v : px) sum += v;
        const ChannelStats& r = info->levels[l].channels[0];
        EXPECT_EQ(info->levels[l].width, chain[l].width);
        EXPECT_EQ(info->levels[l].height, chain[l].height);
        EXPECT_FLOAT_EQ(float(r.min), *std::min_element(px.begin(), px.end()));
        EXPECT_FLOAT_EQ(float(r.max), *std::max_element(px.begin(), px.end()));
        EXPECT_NEAR(r.mean, sum / px.size(), 1e-6);
    }
}

TEST(Info, RefusesWhatIsNotAnImage) {
    ScratchDir dir;
    writeBytes(dir.file("notes.exr"), {'h', 'i'});
    auto info = readFileInfo(dir.file("notes.exr"));
    ASSERT_FALSE(info.ok());
    EXPECT_EQ(info.error().kind, ErrorKind::BadInput);
}
