// One call for every mip-mapped output: EXR, KTX2 or DDS, the container decided once from the output's
// name and carried with it, in a pixel type.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

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

// Writes content to output.path as output.container, stored as plan (from planTexelStorage for this
// content) decided. A float EXR is written exactly as writeTiledExr writes it. Fails, writing nothing,
// with CannotWrite for a pixel type or compression the container lacks (an EXR has no 16-bit normalised
// channels; a DDS no supercompression).
Status writeTexture(const TextureOutput& output, const ChainToWrite& content, const TextureWriteOptions& options,
                    const WritePlan& plan);
// The same, planning first in options.storage.pixelType: fails also, writing nothing, with BadInput when a
// value cannot be stored in the pixel type.
Status writeTexture(const TextureOutput& output, const ChainToWrite& content, const TextureWriteOptions& options);

// Whether output's container holds storage's pixel type and compression: CannotWrite naming output.path
// and what to write instead when it does not.
Status containerTakes(const TextureOutput& output, const TextureStorage& storage);

// Chains (each a mip chain, level 0 first) that hold, level by level, exactly the values a
// ChainToWrite writes: every value it writes is in one of them, and every value of theirs is written.
// A packed chain's plain levels are such (a packed texel holds copies of four plain values), as are a
// texture's layers' plain chains.
using ChainValues = std::vector<const std::vector<Image>*>;

// What storing content with options does to its values: the format writeTexture would choose and, for
// uint16, the normalisation it would record (the whole chain's range). Fails as writeTexture would,
// writing nothing, when a value cannot be stored in the pixel type or the container lacks it. sameValues
// (see ChainValues), when given, are read for the range instead of content's rows, which are then never
// filled (a packed content's are four times as many, and packed on the way): the result is the same.
struct TexelStorage {
    WritePlan plan;  // what the writer takes
    PixelType pixelType = PixelType::Float;
    TexelFormat format = TexelFormat::Rgba32F;
    std::optional<Normalisation> normalisation;
    std::function<float(float)> storeAndRead;  // what reading back a stored value gives
    // The same for n values at once, into readBack (vectorised: half through F16C where the processor
    // has it); bit for bit what storeAndRead gives each value.
    std::function<void(const float* values, size_t n, float* readBack)> storeAndReadRow;
};
Result<TexelStorage> planTexelStorage(const TextureOutput& output, const ChainToWrite& content,
                                      const TextureWriteOptions& options, const ChainValues& sameValues = {});

// The bytes a level of width x height texels with `channels` channels takes on the GPU in the format
// writeTexture would choose (three channels are stored as four).
size_t gpuBytes(int width, int height, int channels, PixelType type);

}  // namespace heightpack
