// GPU containers an engine loads as they are: KTX2 (Khronos KTX 2.0) and DDS (DX10 extended header).
// Both take the same description as the EXR writer (ChainToWrite: level-0 size, channels, rows on
// demand, the heightpack:* attributes), write every mip level in the chosen pixel type, and appear
// atomically; both write texture arrays (ChainToWrite::layerNames: heights, Dx, Dy, foam as layers of
// one texture). KTX2 carries the attributes as key/values; DDS has no key/value store, so it records only
// a few of them in its header's reserved words (see dds.cpp).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/info.hpp"
#include "heightpack/io/pixel_type.hpp"
#include "heightpack/io/texture_storage.hpp"

namespace heightpack {

// How normalised texels map back to values: value = offset + scale * u / 65535 (16-bit), offset + scale
// * u (u a block format's decoded unorm).
struct Normalisation {
    float offset = 0.0f;
    float scale = 1.0f;
};

// How a mip chain is stored, by every mip-mapped writer: writeTexture (any container), writeKtx2, writeDds
// (and writeTiledExr through writeTexture). One struct from the job to the bytes.
struct TextureWriteOptions {
    TextureStorage storage;  // pixel type (as chosen: its tolerance is the job's), compressions
    // uint16 only. The chain is normalised to its range: value = offset + scale * u / 65535. When its
    // values start on a grid gridOrigin + gridSpan * k / 65535 (k integer: a painted 8- or 16-bit map),
    // the range is widened to the grid (offset on it, each grid step a whole number of codes), so level
    // 0 reads back exactly. gridSpan 0: the chain's range alone.
    float gridOrigin = 0.0f;
    float gridSpan = 0.0f;
    int levels = 0;         // how many levels to write: 0 for the full chain down to 1x1
    int threads = 0;        // for filling and encoding rows; the bytes do not depend on it
    std::string writer;     // recorded as KTXwriter, e.g. "heightpack 0.14.0"
    std::function<void(double fraction)> progress;  // may be empty
};

// A block-compressed chain as planned: every layer's every level encoded, and the error its decoded values
// make against the values given (the float chain), per level, over every layer.
struct BlockLevels {
    int levels = 0;
    std::vector<std::vector<std::uint8_t>> images;  // layer * levels + level
    std::vector<double> worst, rms;                  // in the values' units
    // Two channels (xy normals, z rebuilt as sqrt(1 - x^2 - y^2)): the angle between the decoded normal
    // and the given one, in degrees; empty otherwise.
    std::vector<double> worstDegrees, rmsDegrees;
};

// How a texture is stored, decided once before anything is written (planTexelStorage) and handed to the
// writer as it is: the pixel type and, for uint16 and block formats, the normalisation of the whole
// chain's range; for block formats the blocks themselves.
struct WritePlan {
    PixelType pixelType = PixelType::Float;
    std::optional<Normalisation> normalisation;
    std::shared_ptr<const BlockLevels> blocks;
};

// Writes content into a KTX2 or DDS file at path, whatever its name (writeTexture's caller decided the
// container: see textureOutput), every level of the chain that content's size implies (down to 1x1), as
// plan says. Fails with CannotWrite when the file cannot be written. The overloads without a plan plan
// first (planTexelStorage), failing with BadInput, writing nothing, when a value cannot be stored in the
// pixel type (a half beyond +-65504).
Status writeKtx2(const std::string& path, const ChainToWrite& content, const TextureWriteOptions& options,
                 const WritePlan& plan);
Status writeDds(const std::string& path, const ChainToWrite& content, const TextureWriteOptions& options,
                const WritePlan& plan);
Status writeKtx2(const std::string& path, const ChainToWrite& content, const TextureWriteOptions& options);
Status writeDds(const std::string& path, const ChainToWrite& content, const TextureWriteOptions& options);

// A KTX2 or DDS file as heightpack reads it.
struct GpuTexture {
    Container container = Container::Ktx2;
    TexelFormat format = TexelFormat::Rgba32F;
    Supercompression supercompression = Supercompression::None;
    int width = 0;
    int height = 0;
    // An array texture: its layers' names, in order (heightpack:layers, or as the DDS record implies);
    // empty for a single texture.
    std::vector<std::string> layerNames;
    // Level 0 first, as stored (after inflating); an array's level holds each layer's image in turn,
    // layer 0 first, as a KTX2 level does (a DDS stores each layer's whole chain in turn: reordered).
    std::vector<std::vector<std::uint8_t>> levelBytes;
    // Level 0 first; half widened, 16-bit normalised mapped back to values. An array's texel holds every
    // layer's channels in turn, layer 0's first (16 channels for four RGBA layers).
    std::vector<Image> levels;
    std::optional<Normalisation> normalisation;  // how uint16 texels were mapped, when recorded
    Attributes keyValues;  // KTX2: every key/value, in file order; DDS: what its header records
    // Its channels named as the EXR holding the same layers names them (R, G, B, A or Y, then Dx.R ...),
    // and what its key/values say, typed (readGpuTexture fails on a damaged one).
    std::vector<std::string> channelNames;
    TextureDescription description;
};

// The most texels (width x height x layers) of a KTX2 level readGpuTexture decodes: the limit a height
// map's load has (LoadOptions::maxTexels), so no map heightpack packs is refused. A Zstandard level can
// claim 32768 times its bytes, and a block level decodes to 8 to 16 times more in floats: this bounds what
// a small damaged file makes the reader allocate (a DDS's levels are as long as the file).
inline constexpr std::int64_t kMostTexelsReadALevel = std::int64_t(1) << 28;

// Reads a KTX2 or DDS file (by extension) that holds one of the formats above. Fails with BadInput
// naming what is wrong when the file is truncated, corrupt or of another format, or when a KTX2's level
// holds more than kMostTexelsReadALevel texels.
Result<GpuTexture> readGpuTexture(const std::string& path);

// The same, as the TextureFile that `info` and the tests read from any texture.
Result<TextureFile> readGpuTextureFile(const std::string& path);

}  // namespace heightpack
