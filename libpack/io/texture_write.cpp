#include "heightpack/io/texture_write.hpp"

#include "texel_encode.hpp"

namespace heightpack {

namespace {

// What an EXR cannot hold of options: 16-bit normalised channels, Zstandard.
Status exrTakes(const std::string& path, const TextureWriteOptions& options) {
    if (options.storage.pixelType == PixelType::Uint16)
        return cannotWrite(path, "an EXR has no 16-bit normalised channels", "store float or half, or write .ktx2 or .dds");
    if (options.storage.supercompression != Supercompression::None)
        return cannotWrite(path, "an EXR has no Zstandard compression", "use one of EXR's own, or write .ktx2");
    return Done{};
}

}  // namespace

Result<TextureOutput> textureOutput(const std::string& path) {
    const auto container = containerForPath(path);
    if (!container)
        return cannotWrite(path, "names no texture container heightpack writes", "name the output .exr, .ktx2 or .dds");
    return TextureOutput{path, *container};
}

Status writeTexture(const TextureOutput& output, const MipChainSource& content, const TextureWriteOptions& options) {
    const std::string& path = output.path;
    if (output.container == Container::Ktx2) return writeKtx2(path, content, options);
    if (output.container == Container::Dds) return writeDds(path, content, options);
    // An EXR has no texture arrays: a caller writes an EXR's layers as channels NAME.R ... of one texture.
    if (!content.layerNames.empty())
        return Error{ErrorKind::Internal, path, "internal error: an EXR has no texture arrays", "please report this"};
    if (Status s = exrTakes(path, options); !s) return s;
    ExrWriteOptions exr;
    exr.compression = options.storage.exrCompression;
    exr.threads = options.threads;
    exr.progress = options.progress;
    if (options.storage.pixelType == PixelType::Half) {
        // Refuse what a half cannot hold before anything is written (writeTiledExr judges the path).
        auto plan = detail::planEncoding(path, content, options);
        if (!plan) return plan.error();
        exr.half = true;
    }
    return writeTiledExr(path, content, exr);
}

Result<TexelStorage> planTexelStorage(const TextureOutput& output, const MipChainSource& content,
                                      const TextureWriteOptions& options, const ChainValues& sameValues) {
    if (output.container == Container::Exr)
        if (Status s = exrTakes(output.path, options); !s) return s.error();
    auto plan = detail::planEncoding(output.path, content, options, sameValues);
    if (!plan) return plan.error();
    TexelStorage storage;
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
    return size_t(width) * height * texelFormatInfo(texelFormatFor(channels, type)).bytesPerTexel();
}

}  // namespace heightpack
