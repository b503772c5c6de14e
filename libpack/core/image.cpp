#include "heightpack/core/image.hpp"

namespace heightpack {

Image transposed(const Image& image) {
    assert(image.channels == 1);
    Image out(image.height, image.width, 1);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) out.at(y, x) = image.at(x, y);
    return out;
}

Image selectChannels(const Image& image, const std::vector<int>& channels) {
    Image out(image.width, image.height, static_cast<int>(channels.size()));
    for (size_t t = 0; t < image.texelCount(); ++t)
        for (size_t c = 0; c < channels.size(); ++c) {
            assert(channels[c] >= 0 && channels[c] < image.channels);
            out.pixels[t * channels.size() + c] = image.pixels[t * image.channels + channels[c]];
        }
    return out;
}

}  // namespace heightpack
