#include "heightpack/bake/pack_shift.hpp"

#include <algorithm>
#include <cassert>

#include "heightpack/core/pack.hpp"
#include "heightpack/io/attributes.hpp"

#include "job_steps.hpp"

namespace heightpack {

Result<ShiftMaps> packShift(Image d, const SourceInfo& source, const PackOptions& options) {
    assert(d.channels == 2);
    // The same resample the heights get, so D stays where its heights are.
    auto resized = detail::ensurePowerOfTwo(d, source.path, options.resizeToPowerOfTwo, options.mip);
    if (!resized) return resized.error();
    if (options.scale != 1.0f)
        for (float& v : d.pixels) v *= options.scale;
    ShiftMaps maps;
    maps.plainX = generateMipChain(selectChannels(d, {0}), options.mip);
    maps.plainY = generateMipChain(selectChannels(d, {1}), options.mip);
    if (options.layout == Layout::Neighbour4) {
        maps.packedX = packMipChain(maps.plainX, options.mip.wrap);
        maps.packedY = packMipChain(maps.plainY, options.mip.wrap);
    }
    return maps;
}

std::vector<CompanionChain> companionsOf(const ShiftMaps* d, const std::vector<Image>* foam) {
    std::vector<CompanionChain> companions;
    if (d) companions.insert(companions.end(), {{layerName::dx, &d->plainX}, {layerName::dy, &d->plainY}});
    if (foam) companions.push_back({layerName::foam, foam});
    return companions;
}

std::vector<std::string> packedCompanionChannels(const std::vector<CompanionChain>& companions) {
    std::vector<std::string> names = {"R", "G", "B", "A"};
    for (const CompanionChain& c : companions)
        for (const char* s : {".R", ".G", ".B", ".A"}) names.push_back(c.name + s);
    return names;
}

namespace detail {

void fillPackedWithCompanions(ChainToWrite& content, const std::vector<Image>& heights,
                              std::vector<CompanionChain> companions, Wrap wrap) {
    content.channelNames = packedCompanionChannels(companions);
    content.fillRows = [&heights, companions = std::move(companions), wrap](int level, int y0, int rows, float* dst) {
        const size_t texels = size_t(rows) * heights[level].width, stride = 4 * (1 + companions.size());
        std::vector<float> band(texels * 4);
        // Each chain packed alone, then interleaved: texel t holds its 4 heights, then 4 of each companion.
        for (size_t c = 0; c <= companions.size(); ++c) {
            packNeighbour4Rows(c == 0 ? heights[level] : (*companions[c - 1].levels)[level], wrap, y0, rows, band.data());
            for (size_t t = 0; t < texels; ++t) std::copy_n(band.data() + 4 * t, 4, dst + stride * t + 4 * c);
        }
    };
}

void fillPlainWithCompanions(ChainToWrite& content, const std::vector<Image>& heights,
                             std::vector<CompanionChain> companions) {
    content.channelNames = {"Y"};
    for (const CompanionChain& c : companions) content.channelNames.push_back(c.name);
    content.fillRows = [&heights, companions = std::move(companions)](int level, int y0, int rows, float* dst) {
        const Image& h = heights[level];
        const size_t begin = size_t(y0) * h.width, texels = size_t(rows) * h.width, stride = 1 + companions.size();
        for (size_t t = 0; t < texels; ++t) {
            dst[stride * t] = h.pixels[begin + t];
            for (size_t c = 0; c < companions.size(); ++c)
                dst[stride * t + 1 + c] = (*companions[c].levels)[level].pixels[begin + t];
        }
    };
}

void fillArrayWithCompanions(ChainToWrite& content, const std::vector<Image>& heights,
                             std::vector<CompanionChain> companions, Wrap wrap, bool packed) {
    content.channelNames = packed ? std::vector<std::string>{"R", "G", "B", "A"} : std::vector<std::string>{"Y"};
    content.layerNames = {layerName::heights};
    for (const CompanionChain& c : companions) content.layerNames.push_back(c.name);
    content.fillRows = nullptr;
    content.fillLayerRows = [&heights, companions = std::move(companions), wrap, packed](int layer, int level, int y0,
                                                                                        int rows, float* dst) {
        // Each layer packed (or copied) alone, exactly as the EXR's layer of the same name.
        const Image& chain = layer == 0 ? heights[level] : (*companions[size_t(layer) - 1].levels)[level];
        if (packed) packNeighbour4Rows(chain, wrap, y0, rows, dst);
        else std::copy_n(chain.row(y0), size_t(rows) * chain.width, dst);
    };
}

void fillWithCompanions(ChainToWrite& content, Container container, const std::vector<Image>& heights,
                        std::vector<CompanionChain> companions, Wrap wrap, bool packed) {
    if (container != Container::Exr) fillArrayWithCompanions(content, heights, std::move(companions), wrap, packed);
    else if (packed) fillPackedWithCompanions(content, heights, std::move(companions), wrap);
    else fillPlainWithCompanions(content, heights, std::move(companions));
}

}  // namespace detail

}  // namespace heightpack
