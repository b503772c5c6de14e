#include "heightpack/core/image.hpp"

#include <algorithm>

#include "heightpack/core/parallel.hpp"

namespace heightpack {

Image transposed(const Image& image, int threads) {
    assert(image.channels == 1);
    Image out(image.height, image.width, 1);
    // In 64 x 64 blocks: a plain loop writes every texel of a column to another cache line.
    constexpr int kBlock = 64;
    parallelFor((image.height + kBlock - 1) / kBlock, threads, [&](int begin, int end) {
        for (int by = begin * kBlock; by < std::min(end * kBlock, image.height); by += kBlock)
            for (int bx = 0; bx < image.width; bx += kBlock)
                for (int y = by; y < std::min(by + kBlock, image.height); ++y)
                    for (int x = bx; x < std::min(bx + kBlock, image.width); ++x) out.at(y, x) = image.at(x, y);
    });
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
