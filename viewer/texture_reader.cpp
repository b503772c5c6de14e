#include "texture_reader.hpp"

#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/pixel_type.hpp"

namespace heightpack::view {

Result<ViewerTexture> readViewerTexture(const std::string& path) {
    ViewerTexture texture;
    if (const auto container = containerForPath(path); container && *container != Container::Exr) {
        auto gpu = readGpuTexture(path);
        if (!gpu) return gpu.error();
        texture.levels = std::move(gpu->levels);
        texture.attributes = std::move(gpu->keyValues);
        texture.stored = storeGpuTexture(*gpu);
        return texture;
    }
    auto file = readTextureFile(path, true);
    if (!file) return file.error();
    texture.levels = std::move(file->levels);
    texture.attributes = std::move(file->attributes);
    texture.channelNames = std::move(file->channelNames);
    if (file->pixelType == "half") texture.stored = storeFloats(texture.levels, ComponentKind::Float16);
    texture.unitIntegers = file->pixelType != "float" && file->pixelType != "half";
    return texture;
}

}  // namespace heightpack::view
