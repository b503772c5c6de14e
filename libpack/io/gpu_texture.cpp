// The KTX2 and DDS readers behind one call, and their files as TextureFiles (the writers are writeKtx2 and
// writeDds, chosen by writeTexture from the container its caller decided).
#include "heightpack/io/gpu_texture.hpp"

#include <algorithm>
#include <string>

#include "texel_encode.hpp"

namespace heightpack {

namespace detail {
Result<GpuTexture> readKtx2(const std::string& path);
Result<GpuTexture> readDds(const std::string& path);
}  // namespace detail

namespace {

// An array's channels as pack names an EXR's: the heights' R, G, B, A (Y when plain), then NAME.R ...
// (NAME when plain) for each further layer.
std::vector<std::string> channelNamesOf(const GpuTexture& texture) {
    const TexelFormatInfo& f = texelFormatInfo(texture.format);
    static const char* names[] = {"R", "G", "B", "A"};
    std::vector<std::string> channels;
    for (size_t layer = 0; layer < std::max<size_t>(1, texture.layerNames.size()); ++layer) {
        if (!texture.layerNames.empty() && f.channels == 1) {
            channels.push_back(layer == 0 ? "Y" : texture.layerNames[layer]);
            continue;
        }
        const std::string prefix = layer == 0 ? "" : texture.layerNames[layer] + ".";
        for (int c = 0; c < f.channels; ++c) channels.push_back(prefix + names[c]);
    }
    return channels;
}

}  // namespace

Result<GpuTexture> readGpuTexture(const std::string& path) {
    const auto container = containerForPath(path);
    Result<GpuTexture> texture = container == Container::Ktx2 ? detail::readKtx2(path)
                                 : container == Container::Dds
                                     ? detail::readDds(path)
                                     : Result<GpuTexture>(badInput(path, "is neither a .ktx2 nor a .dds file",
                                                                   "name a .ktx2 or .dds file"));
    if (!texture) return texture;
    texture->channelNames = channelNamesOf(*texture);
    auto description = describeTexture(path, texture->keyValues, texture->channelNames,
                                       pixelTypeName(pixelTypeOf(texture->format)));
    if (!description) return description.error();
    texture->description = std::move(*description);
    return texture;
}

Result<TextureFile> readGpuTextureFile(const std::string& path) {
    auto texture = readGpuTexture(path);
    if (!texture) return texture.error();
    const TexelFormatInfo& f = texelFormatInfo(texture->format);
    TextureFile file;
    file.path = path;
    const bool ktx2 = texture->container == Container::Ktx2;
    file.kind = ktx2 ? FileKind::Ktx2 : FileKind::Dds;
    file.texelFormat = texture->format;
    file.format = std::string(containerName(texture->container)) + " " + (ktx2 ? f.vkName : f.dxgiName);
    if (texture->supercompression == Supercompression::Zstd) file.format += " zstd";
    file.pixelType = pixelTypeName(pixelTypeOf(texture->format));
    file.layerNames = texture->layerNames;
    file.channelNames = texture->channelNames;
    file.attributes = texture->keyValues;
    file.description = texture->description;
    file.levels = std::move(texture->levels);
    return file;
}

}  // namespace heightpack
