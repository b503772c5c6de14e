// One call for every mip-mapped output: EXR, KTX2 or DDS, the container decided once from the output's
// name and carried with it, in a pixel type.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "heightpack/core/result.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/gpu_texture.hpp"

namespace heightpack {

// A mip-mapped output: the file and the container it is written as. textureOutput decides the container
// once, from the name; the planner and the writers take it as it is and never look at the name again.
struct TextureOutput {
    std::string path;
    Container container = Container::Exr;
};
// path with the container its extension names (.exr, .ktx2, .dds, in any case); CannotWrite naming path
// for any other name.
Result<TextureOutput> textureOutput(const std::string& path);

// Writes content to output.path as output.container. A float EXR is written exactly as writeTiledExr
// writes it. Fails, writing nothing, with BadInput when a value cannot be stored in the pixel type, and
// with CannotWrite for a pixel type or compression the container lacks (an EXR has no 16-bit normalised
// channels; a DDS no supercompression).
Status writeTexture(const TextureOutput& output, const MipChainSource& content, const TextureWriteOptions& options);

// What storing content with options does to its values: the format writeTexture would choose and, for
// uint16, the normalisation it would record (the whole chain's range). Fails as writeTexture would,
// writing nothing, when a value cannot be stored in the pixel type or the container lacks it.
struct TexelStorage {
    PixelType pixelType = PixelType::Float;
    TexelFormat format = TexelFormat::Rgba32F;
    std::optional<Normalisation> normalisation;
    std::function<float(float)> storeAndRead;  // what reading back a stored value gives
};
Result<TexelStorage> planTexelStorage(const TextureOutput& output, const MipChainSource& content,
                                      const TextureWriteOptions& options);

// The bytes a level of width x height texels with `channels` channels takes on the GPU in the format
// writeTexture would choose (three channels are stored as four).
size_t gpuBytes(int width, int height, int channels, PixelType type);

}  // namespace heightpack
