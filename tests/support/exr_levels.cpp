#include "support/exr_levels.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace heightpack::test {

namespace {

bool readInto(OIIO::ImageInput& in, const std::string& path, int mip, Level& l) {
    if (!in.seek_subimage(0, mip)) return false;
    const OIIO::ImageSpec& spec = in.spec();
    l.width = spec.width;
    l.height = spec.height;
    l.names = spec.channelnames;
    l.pixels.resize(size_t(l.width) * l.height * spec.nchannels);
    EXPECT_TRUE(in.read_image(0, mip, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, l.pixels.data())) << path;
    return true;
}

}  // namespace

float Level::at(const std::string& channel, int x, int y) const {
    const size_t c = std::find(names.begin(), names.end(), channel) - names.begin();
    EXPECT_LT(c, names.size()) << channel;
    return c < names.size() ? pixels[(size_t(y) * width + x) * names.size() + c] : NAN;
}

Level readLevel(const std::string& path, int mip) {
    Level l;
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    if (in) {
        EXPECT_TRUE(readInto(*in, path, mip, l)) << path << " has no level " << mip;
    }
    return l;
}

std::vector<Level> readLevels(const std::string& path) {
    std::vector<Level> levels;
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    for (Level l; in && readInto(*in, path, int(levels.size()), l); l = Level()) levels.push_back(std::move(l));
    return levels;
}

void writeChannels(const std::string& path, const std::vector<std::string>& names, const std::vector<const Image*>& channels) {
    ASSERT_EQ(names.size(), channels.size());
    const Image& first = *channels.front();
    OIIO::ImageSpec spec(first.width, first.height, int(names.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames = names;
    std::vector<float> pixels;
    for (size_t i = 0; i < first.texelCount(); ++i)
        for (const Image* c : channels) pixels.push_back(c->pixels[i]);
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close()) << path;
}

}  // namespace heightpack::test
