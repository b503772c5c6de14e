#include "heightpack/io/info.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>

#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/texture_write.hpp"
#include "image_input.hpp"
#include "stderr_silencer.hpp"

namespace heightpack {

namespace {

// Opens path and fills header from its first level; the caller walks the levels.
Result<detail::OpenedImage> openTexture(const std::string& path, TextureHeader& header) {
    auto opened = detail::openImage(path, detail::SizeLimits{});
    if (!opened) return opened.error();
    detail::OpenedImage in = std::move(*opened);
    header.path = path;
    header.format = in->format_name();
    // The decoder's word, read once here.
    header.kind = header.format == "openexr" ? FileKind::Exr : header.format == "png" ? FileKind::Png : FileKind::Other;
    const detail::SourceSpec& top = in->spec();
    header.pixelType = top.format.c_str();
    header.channelNames = top.channelnames;
    header.storedInTiles = top.tile_width > 0;
    header.storageTileWidth = top.tile_width;
    header.storageTileHeight = top.tile_height;
    for (const detail::SourceAttribute& p : top.extra_attribs) header.attributes.emplace_back(p.name, p.text);
    auto description = describeTexture(path, header.attributes, header.channelNames, header.pixelType);
    if (!description) return description.error();
    header.description = std::move(*description);
    return in;
}

}  // namespace

Result<TextureFile> readTextureFile(const std::string& path, bool silenceDecoderMessages) {
    // KTX2 and DDS: heightpack's own reader (OpenImageIO 2.4 reads neither's float formats).
    if (const auto c = containerForPath(path); c && *c != Container::Exr) return readGpuTextureFile(path);
    detail::StderrSilencer quiet(silenceDecoderMessages);
    TextureFile file;
    auto in = openTexture(path, file);
    if (!in) return in.error();
    for (int mip = 0; (*in)->seekLevel(mip); ++mip) {
        const detail::SourceSpec spec = (*in)->spec();
        // Every level's header is judged before its pixels are allocated.
        if (Status s = detail::judgeSize(path, spec, detail::SizeLimits{}); !s) return s.error();
        Image level;
        try {
            level = Image(spec.width, spec.height, spec.nchannels);
        } catch (const std::bad_alloc&) {
            return badInput(path, "level " + std::to_string(mip) + " is too large for this machine's memory",
                            "split or downsize the map");
        }
        if (Status s = detail::readPixels(**in, path, mip, 0, spec.nchannels, level.pixels.data(),
                                          "level " + std::to_string(mip) + " is damaged or truncated");
            !s)
            return s.error();
        file.levels.push_back(std::move(level));
    }
    return file;
}

Result<TextureLevels> readTextureLevels(const std::string& path, bool silenceDecoderMessages) {
    detail::StderrSilencer quiet(silenceDecoderMessages);
    TextureLevels layout;
    if (const auto c = containerForPath(path); c && *c != Container::Exr) {
        auto file = readGpuTextureFile(path);
        if (!file) return file.error();
        static_cast<TextureHeader&>(layout) = *file;
        for (const Image& level : file->levels) layout.levelSizes.emplace_back(level.width, level.height);
        return layout;
    }
    auto in = openTexture(path, layout);
    if (!in) return in.error();
    for (int mip = 0; (*in)->seekLevel(mip); ++mip)
        layout.levelSizes.emplace_back((*in)->spec().width, (*in)->spec().height);
    return layout;
}

Result<FileInfo> readFileInfo(const std::string& path, bool silenceDecoderMessages) {
    auto file = readTextureFile(path, silenceDecoderMessages);
    if (!file) return file.error();
    FileInfo info;
    static_cast<TextureHeader&>(info) = *file;
    const TextureDescription& described = file->description;
    const std::vector<double>& errors = described.lookupErrors;
    const bool floatTexels = described.pixelType == PixelType::Float;
    const bool blocks = described.pixelType && isBlockType(*described.pixelType);
    for (const Image& image : file->levels) {
        LevelInfo level;
        level.width = image.width;
        level.height = image.height;
        // Per layer of an array: each stored in the texture's format.
        const size_t layers = std::max<size_t>(1, file->layerNames.size());
        const int perLayer = image.channels / int(layers);
        level.gpuBytes = image.texelCount() * layers * size_t(perLayer == 3 ? 4 : perLayer) *
                         size_t(described.componentBytes);
        if (blocks) level.gpuBytes = gpuBytes(image.width, image.height, perLayer, *described.pixelType) * layers;
        const size_t index = info.levels.size();
        const size_t levels = file->levels.size();
        if (described.rmsErrors.size() == levels) level.rmsError = described.rmsErrors[index];
        if (described.angleErrors.size() == levels) level.angleError = described.angleErrors[index];
        if (described.rmsAngleErrors.size() == levels) level.rmsAngleError = described.rmsAngleErrors[index];
        if (floatTexels) level.lookupError = 0.0;  // the float chain itself
        else if (errors.size() == file->levels.size()) level.lookupError = errors[index];
        for (int c = 0; c < image.channels; ++c) {
            ChannelStats stats;
            stats.name = c < int(file->channelNames.size()) ? file->channelNames[c] : std::to_string(c);
            stats.min = std::numeric_limits<double>::infinity();
            stats.max = -stats.min;
            double sum = 0.0;
            for (size_t i = c; i < image.pixels.size(); i += image.channels) {
                stats.min = std::min<double>(stats.min, image.pixels[i]);
                stats.max = std::max<double>(stats.max, image.pixels[i]);
                sum += image.pixels[i];
            }
            stats.mean = sum / double(image.texelCount());
            level.channels.push_back(stats);
        }
        info.levels.push_back(std::move(level));
    }
    return info;
}

std::string findAttribute(const Attributes& attributes, const std::string& name) {
    for (const auto& [key, value] : attributes)
        if (key == name) return value;
    return {};
}

}  // namespace heightpack
