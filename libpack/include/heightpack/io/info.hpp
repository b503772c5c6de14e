// What is in an image file: size, channels, mip levels with per-level statistics, and header attributes.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/attributes.hpp"
#include "heightpack/io/pixel_type.hpp"
#include "heightpack/io/texture_description.hpp"

namespace heightpack {

struct ChannelStats {
    std::string name;
    double min = 0.0;
    double max = 0.0;
    double mean = 0.0;
};

struct LevelInfo {
    int width = 0;
    int height = 0;
    std::vector<ChannelStats> channels;
    // Bytes the level takes on the GPU, uploaded as stored: width * height * texel bytes (three channels
    // count as four, since GPUs have no 16- or 32-bit RGB formats to sample).
    size_t gpuBytes = 0;
    // The worst difference between a bilinear lookup of the level as stored and of the float chain it
    // was made from, in the file's units: 0 for float texels, the recorded figure for half and uint16
    // (heightpack:lookupError), nullopt where the file records none (a DDS, a file from elsewhere).
    std::optional<double> lookupError;
    // Block formats (bc4, bc5), as recorded: the RMS decoded error in the same units, and for xy normals
    // the worst and RMS angle in degrees (heightpack:rmsError, angleError, rmsAngleError).
    std::optional<double> rmsError, angleError, rmsAngleError;
};

// What kind of file holds the texels, typed where the header is read.
enum class FileKind { Ktx2, Dds, Exr, Png, Other };

// What a texture file's header says.
struct TextureHeader {
    std::string path;
    FileKind kind = FileKind::Other;
    std::optional<TexelFormat> texelFormat;  // a KTX2's or DDS's texels
    std::string format;     // for reports: OpenImageIO's format name, or the container and its texel format
    std::string pixelType;  // the decoder's word for its samples, for reports: "float", "half", "uint16", "uint8", ...
    std::vector<std::string> channelNames;
    // An array texture's layers (KTX2, DDS), in order; empty for a single texture. Its channels are then
    // named as the EXR holding the same layers names them: the heights' R, G, B, A (Y when plain), then
    // each further layer's NAME.R ... (NAME when plain).
    std::vector<std::string> layerNames;
    // An EXR stored in tiles (storage blocks of texels), and their size; not the map's tile in metres.
    bool storedInTiles = false;
    int storageTileWidth = 0;
    int storageTileHeight = 0;
    Attributes attributes;  // header metadata, as text, for reports
    TextureDescription description;  // what the header says, typed: what every reader asks
};

// A file's header and per-level statistics.
struct FileInfo : TextureHeader {
    std::vector<LevelInfo> levels;  // level 0 first; one entry for a file without mip levels
};

// Every level of a texture file as float images, all channels, with the header.
struct TextureFile : TextureHeader {
    std::vector<Image> levels;  // level 0 first; one entry for a file without mip levels
};

// Reads every level of the image at path through OpenImageIO. Fails with BadInput when the file cannot
// be read. silenceDecoderMessages: see LoadOptions.
Result<TextureFile> readTextureFile(const std::string& path, bool silenceDecoderMessages = false);

// A file's header and the size of each level, without reading any pixels.
struct TextureLevels : TextureHeader {
    std::vector<std::pair<int, int>> levelSizes;  // level 0 first
};
Result<TextureLevels> readTextureLevels(const std::string& path, bool silenceDecoderMessages = false);

// readTextureFile, summarised: per-level, per-channel statistics instead of pixels.
Result<FileInfo> readFileInfo(const std::string& path, bool silenceDecoderMessages = false);

inline std::string findAttribute(const FileInfo& info, const std::string& name) {
    return findAttribute(info.attributes, name);
}

}  // namespace heightpack
