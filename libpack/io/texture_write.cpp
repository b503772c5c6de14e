#include "heightpack/io/texture_write.hpp"

#include "texel_encode.hpp"

namespace heightpack {

Status containerTakes(const TextureOutput& output, const TextureStorage& storage) {
    const std::string& path = output.path;
    if (output.container == Container::Dds && storage.supercompression != Supercompression::None)
        return cannotWrite(path, "DDS has no supercompression", "write it uncompressed, or as KTX2");
    if (output.container == Container::Dds && isAstcType(storage.pixelType))
        return cannotWrite(path, "DDS has no ASTC format", "write .ktx2, or store bc4 or bc5 in a DDS");
    if (output.container != Container::Exr) return Done{};
    if (storage.pixelType == PixelType::Uint16)
        return cannotWrite(path, "an EXR has no 16-bit normalised channels", "store float or half, or write .ktx2 or .dds");
    if (isBlockType(storage.pixelType))
        return cannotWrite(path, std::string("an EXR has no block-compressed (") + pixelTypeName(storage.pixelType) + ") texels",
                           "write .ktx2 or .dds, or store float or half");
    if (storage.supercompression != Supercompression::None)
        return cannotWrite(path, "an EXR has no Zstandard compression", "use one of EXR's own, or write .ktx2");
    return Done{};
}

Result<TextureOutput> textureOutput(const std::string& path) {
    const auto container = containerForPath(path);
    if (!container)
        return cannotWrite(path, "names no texture container heightpack writes", "name the output .exr, .ktx2 or .dds");
    return TextureOutput{path, *container};
}

Status writeTexture(const TextureOutput& output, const ChainToWrite& content, const TextureWriteOptions& options,
                    const WritePlan& plan) {
    const std::string& path = output.path;
    if (output.container == Container::Ktx2) return writeKtx2(path, content, options, plan);
    if (output.container == Container::Dds) return writeDds(path, content, options, plan);
    // An EXR has no texture arrays: a caller writes an EXR's layers as channels NAME.R ... of one texture.
    if (!content.layerNames.empty())
        return Error{ErrorKind::Internal, path, "internal error: an EXR has no texture arrays", "please report this"};
    TextureStorage storage = options.storage;
    storage.pixelType = plan.pixelType;
    if (Status s = containerTakes(output, storage); !s) return s;
    ExrWriteOptions exr;
    exr.compression = options.storage.exrCompression;
    exr.threads = options.threads;
    exr.progress = options.progress;
    exr.half = plan.pixelType == PixelType::Half;
    return writeTiledExr(path, content, exr);
}

Status writeTexture(const TextureOutput& output, const ChainToWrite& content, const TextureWriteOptions& options) {
    auto storage = planTexelStorage(output, content, options);
    if (!storage) return storage.error();
    return writeTexture(output, content, options, storage->plan);
}

Result<TexelStorage> planTexelStorage(const TextureOutput& output, const ChainToWrite& content,
                                      const TextureWriteOptions& options, const ChainValues& sameValues) {
    if (Status s = containerTakes(output, options.storage); !s) return s.error();
    auto plan = detail::planEncoding(output.path, content, options, sameValues);
    if (!plan) return plan.error();
    TexelStorage storage;
    storage.plan = WritePlan{options.storage.pixelType, plan->normalisation, nullptr};
    if (plan->format.isBlock()) {
        auto blocks = detail::encodeBlockLevels(output.path, content, *plan, options.threads);
        if (!blocks) return blocks.error();
        storage.plan.blocks = std::make_shared<const BlockLevels>(std::move(*blocks));
    }
    storage.pixelType = options.storage.pixelType;
    storage.format = plan->format.format;
    storage.normalisation = plan->normalisation;
    storage.storeAndRead = [plan = *plan](float v) { return detail::storeAndRead(plan, v); };
    storage.storeAndReadRow = [plan = *plan](const float* values, size_t n, float* readBack) {
        detail::storeAndReadRow(plan, values, n, readBack);
    };
    return storage;
}

size_t gpuBytes(int width, int height, int channels, PixelType type) {
    return detail::imageBytes(texelFormatInfo(texelFormatFor(channels, type)), width, height);
}

}  // namespace heightpack
