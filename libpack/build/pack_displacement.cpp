#include "heightpack/build/pack_displacement.hpp"

#include <algorithm>
#include <cassert>

#include "heightpack/core/pack.hpp"

#include "job_steps.hpp"

namespace heightpack {

namespace {

Image channelOf(const Image& image, int c) {
    Image out(image.width, image.height, 1);
    for (size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] = image.pixels[i * image.channels + c];
    return out;
}

}  // namespace

Result<DisplacementMaps> packDisplacement(Image d, const SourceInfo& source, const PackOptions& options) {
    assert(d.channels == 2);
    // The same resample the heights get, so D stays where its heights are.
    auto resized = detail::ensurePowerOfTwo(d, source.path, options.resizeToPowerOfTwo, options.mip);
    if (!resized) return resized.error();
    if (options.scale != 1.0f)
        for (float& v : d.pixels) v *= options.scale;
    DisplacementMaps maps;
    maps.plainX = generateMipChain(channelOf(d, 0), options.mip);
    maps.plainY = generateMipChain(channelOf(d, 1), options.mip);
    if (options.layout == Layout::Neighbour4) {
        maps.packedX = packMipChain(maps.plainX, options.mip.wrap);
        maps.packedY = packMipChain(maps.plainY, options.mip.wrap);
    }
    return maps;
}

std::vector<std::string> packedDisplacementChannels() {
    return {"R", "G", "B", "A", "Dx.R", "Dx.G", "Dx.B", "Dx.A", "Dy.R", "Dy.G", "Dy.B", "Dy.A"};
}

namespace detail {

void fillPackedWithDisplacement(TiledExrContent& content, const std::vector<Image>& heights, const DisplacementMaps& d,
                                Wrap wrap) {
    content.channelNames = packedDisplacementChannels();
    content.fillRows = [&heights, &d, wrap](int level, int y0, int rows, float* dst) {
        const Image* chains[3] = {&heights[level], &d.plainX[level], &d.plainY[level]};
        const size_t texels = size_t(rows) * heights[level].width;
        std::vector<float> band(texels * 4);
        // Each chain packed alone, then interleaved: texel t holds its 4 heights, 4 Dx, 4 Dy.
        for (int c = 0; c < 3; ++c) {
            packNeighbour4Rows(*chains[c], wrap, y0, rows, band.data());
            for (size_t t = 0; t < texels; ++t) std::copy_n(band.data() + 4 * t, 4, dst + 12 * t + 4 * c);
        }
    };
}

void fillPlainWithDisplacement(TiledExrContent& content, const std::vector<Image>& heights, const DisplacementMaps& d) {
    content.channelNames = {"Y", "Dx", "Dy"};
    content.fillRows = [&heights, &d](int level, int y0, int rows, float* dst) {
        const Image& h = heights[level];
        const size_t begin = size_t(y0) * h.width, texels = size_t(rows) * h.width;
        for (size_t t = 0; t < texels; ++t) {
            dst[3 * t] = h.pixels[begin + t];
            dst[3 * t + 1] = d.plainX[level].pixels[begin + t];
            dst[3 * t + 2] = d.plainY[level].pixels[begin + t];
        }
    };
}

}  // namespace detail

}  // namespace heightpack
