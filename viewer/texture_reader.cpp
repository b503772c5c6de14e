#include "texture_reader.hpp"

#include <numeric>

#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/info.hpp"
#include "heightpack/io/pixel_type.hpp"

namespace heightpack::view {

namespace {

// Layer `layer` of an array's stored chain: each level holds every layer's image in turn (GpuTexture's
// levelBytes, a DDS's reordered so), so a layer is one slice of each level.
UploadChain layerOf(const UploadChain& array, int layer) {
    UploadChain one = array;
    for (size_t l = 0; l < array.levels.size(); ++l) {
        const size_t bytes = size_t(array.levelWidth(int(l))) * size_t(array.levelHeight(int(l))) * size_t(array.bytesPerTexel());
        const auto first = array.levels[l].begin() + static_cast<std::ptrdiff_t>(bytes * size_t(layer));
        one.levels[l].assign(first, first + static_cast<std::ptrdiff_t>(bytes));
    }
    return one;
}

// A block array's levels decoded, as a float array's stored chain: each level every layer's image in turn.
// (Its layers feed the texel-by-texel packings of shift and foam, which blocks cannot.)
UploadChain layerMajorFloats(const std::vector<Image>& levels, int layers) {
    const int channels = levels[0].channels / layers;
    UploadChain chain;
    for (int layer = 0; layer < layers; ++layer) {
        std::vector<int> mine(static_cast<size_t>(channels));
        std::iota(mine.begin(), mine.end(), layer * channels);
        std::vector<Image> one;
        for (const Image& level : levels) one.push_back(selectChannels(level, mine));
        UploadChain part = storeFloats(one);
        if (layer == 0) {
            chain = std::move(part);
            continue;
        }
        for (size_t l = 0; l < levels.size(); ++l)
            chain.levels[l].insert(chain.levels[l].end(), part.levels[l].begin(), part.levels[l].end());
    }
    return chain;
}

// Splits an array texture into layer 0 (levels, stored) and its further layers (ViewerTexture::layers).
void splitLayers(ViewerTexture& texture, const std::vector<std::string>& names) {
    if (texture.stored->isBlock()) texture.stored = layerMajorFloats(texture.levels, int(names.size()));
    const UploadChain array = std::move(*texture.stored);
    for (size_t n = 1; n < names.size(); ++n) texture.layers.push_back({names[n], layerOf(array, int(n))});
    texture.stored = layerOf(array, 0);
    // A decoded texel holds every layer's channels in turn, layer 0's first.
    std::vector<int> heights(size_t(array.channels));
    std::iota(heights.begin(), heights.end(), 0);
    for (Image& level : texture.levels) level = selectChannels(level, heights);
}

}  // namespace

const UploadChain* ViewerTexture::layer(const std::string& name) const {
    for (const Layer& l : layers)
        if (l.name == name) return &l.texels;
    return nullptr;
}

Result<ViewerTexture> readViewerTexture(const std::string& path) {
    ViewerTexture texture;
    if (const auto container = containerForPath(path); container && *container != Container::Exr) {
        auto gpu = readGpuTexture(path);
        if (!gpu) return gpu.error();
        texture.stored = storeGpuTexture(*gpu);  // first: a block format's chain is made from the decoded levels
        texture.levels = std::move(gpu->levels);
        texture.description = std::move(gpu->description);
        if (gpu->layerNames.size() > 1) splitLayers(texture, gpu->layerNames);
        return texture;
    }
    auto file = readTextureFile(path, true);
    if (!file) return file.error();
    texture.levels = std::move(file->levels);
    texture.description = std::move(file->description);
    const std::optional<PixelType> type = texture.description.pixelType;
    if (type == PixelType::Half) texture.stored = storeFloats(texture.levels, ComponentKind::Float16);
    texture.unitIntegers = type != PixelType::Float && type != PixelType::Half;
    return texture;
}

}  // namespace heightpack::view
