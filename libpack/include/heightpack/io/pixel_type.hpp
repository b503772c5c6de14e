// What a texture's texels are stored as, and the containers that hold them: the choices a GPU texture
// makes between memory and precision.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "heightpack/core/names.hpp"

namespace heightpack {

// The file a texture goes into, chosen by the output's extension.
enum class Container { Exr, Ktx2, Dds };
template <>
struct NameTable<Container> {
    static constexpr EnumName<Container> entries[] = {
        {Container::Exr, "exr", "OpenEXR, tiled and mip-mapped: offline renderers, OpenImageIO"},
        {Container::Ktx2, "ktx2", "Khronos KTX 2.0: Vulkan, OpenGL, WebGPU engines"},
        {Container::Dds, "dds", "DirectDraw Surface with the DX10 header: Direct3D engines"},
    };
};
inline const char* containerName(Container container) { return nameOf(container); }
// The container a path names by its (lower-case) extension: .exr, .ktx2, .dds; nullopt for anything else.
std::optional<Container> containerForPath(const std::string& path);

// Pixel types offered for every output kind.
//   Float:  32-bit float, exact.
//   Half:   16-bit float, each value rounded to nearest; values a half cannot hold are refused.
//   Uint16: 16-bit normalised; value = offset + scale * u / 65535, with offset and scale recorded.
//   Bc4, Bc5: block-compressed (RGTC) one or two channels, normalised as uint16 is (value = offset + scale
//   * u, u the decoded unorm), each level's decoded error recorded.
//   Astc4x4, Astc6x6, Astc8x8: ASTC LDR blocks of that many texels in 16 bytes (KTX2 only), one channel
//   (plain heights) or two (xy normals), normalised and measured as BC4/BC5 are.
//   AstcHdr4x4, AstcHdr6x6, AstcHdr8x8: the same sizes in ASTC's HDR profile (VK_FORMAT_ASTC_*_SFLOAT_BLOCK,
//   decoded as half floats), plain heights only, normalised and measured as the LDR ones.
enum class PixelType { Float, Half, Uint16, Bc4, Bc5, Astc4x4, Astc6x6, Astc8x8, AstcHdr4x4, AstcHdr6x6, AstcHdr8x8 };
template <>
struct NameTable<PixelType> {
    static constexpr EnumName<PixelType> entries[] = {
        {PixelType::Float, "float", "32-bit float"},
        {PixelType::Half, "half", "16-bit float, rounded to nearest"},
        {PixelType::Uint16, "uint16", "16-bit normalised to the chain's range, scale and offset recorded"},
        {PixelType::Bc4, "bc4", "block-compressed one channel (plain heights), 0.5 byte a texel"},
        {PixelType::Bc5, "bc5", "block-compressed two channels (xy normals), 1 byte a texel"},
        {PixelType::Astc4x4, "astc-4x4", "ASTC 4x4 blocks (plain heights or xy normals, KTX2), 1 byte a texel"},
        {PixelType::Astc6x6, "astc-6x6", "ASTC 6x6 blocks (plain heights or xy normals, KTX2), 0.44 byte a texel"},
        {PixelType::Astc8x8, "astc-8x8", "ASTC 8x8 blocks (plain heights or xy normals, KTX2), 0.25 byte a texel"},
        {PixelType::AstcHdr4x4, "astc-hdr-4x4", "ASTC HDR 4x4 blocks (plain heights, KTX2), 1 byte a texel"},
        {PixelType::AstcHdr6x6, "astc-hdr-6x6", "ASTC HDR 6x6 blocks (plain heights, KTX2), 0.44 byte a texel"},
        {PixelType::AstcHdr8x8, "astc-hdr-8x8", "ASTC HDR 8x8 blocks (plain heights, KTX2), 0.25 byte a texel"},
    };
};
inline const char* pixelTypeName(PixelType type) { return nameOf(type); }
inline std::optional<PixelType> parsePixelType(std::string_view name) { return parseName<PixelType>(name); }

// The texel formats heightpack writes into KTX2 and DDS, with their Vulkan and DXGI codes. Rg16Snorm is
// read only: the format xy normals in uint16 had before they were normalised like every other uint16.
// An ASTC size is one Vulkan format holding one channel (R: heights as luminance) or two (Rg: x in RGB, y
// in alpha); a KTX2 says which by its KTXswizzle ("r001", "ra01"), as a loader needs to know. An ASTC HDR
// size (SFLOAT) holds one channel only.
enum class TexelFormat {
    Rgba32F, Rgba16F, Rgba16Unorm, Rg32F, Rg16F, Rg16Unorm, Rg16Snorm, R32F, R16F, R16Unorm, Bc4Unorm, Bc5Unorm,
    Astc4x4R, Astc4x4Rg, Astc6x6R, Astc6x6Rg, Astc8x8R, Astc8x8Rg, AstcHdr4x4R, AstcHdr6x6R, AstcHdr8x8R
};

// Block: blocks of texels (BC4, BC5: 4x4 in 8 bytes a channel; ASTC: 16 bytes), written and read a whole
// level at a time.
enum class ComponentKind { Float32, Float16, Unorm16, Snorm16, Block };
inline bool isAstcHdrType(PixelType type) {
    return type == PixelType::AstcHdr4x4 || type == PixelType::AstcHdr6x6 || type == PixelType::AstcHdr8x8;
}
inline bool isAstcType(PixelType type) {
    return type == PixelType::Astc4x4 || type == PixelType::Astc6x6 || type == PixelType::Astc8x8 || isAstcHdrType(type);
}
inline bool isBlockType(PixelType type) { return type == PixelType::Bc4 || type == PixelType::Bc5 || isAstcType(type); }

struct TexelFormatInfo {
    TexelFormat format;
    int channels;
    ComponentKind kind;
    std::uint32_t vkFormat;
    std::uint32_t dxgiFormat;
    const char* vkName;    // "VK_FORMAT_R16G16B16A16_SFLOAT"
    const char* dxgiName;  // "DXGI_FORMAT_R16G16B16A16_FLOAT"; "" where Direct3D has none (ASTC, dxgiFormat 0)
    // Texel formats only (kind != Block); a block format's level takes blockImageBytes.
    int bytesPerComponent() const { return kind == ComponentKind::Float32 ? 4 : 2; }
    int bytesPerTexel() const { return channels * bytesPerComponent(); }
    bool isBlock() const { return kind == ComponentKind::Block; }
};

const TexelFormatInfo& texelFormatInfo(TexelFormat format);
std::optional<TexelFormat> texelFormatFromVk(std::uint32_t vkFormat);
std::optional<TexelFormat> texelFormatFromDxgi(std::uint32_t dxgiFormat);

// The format that stores `channels` channels (1, 2, 3 or 4) as `type`. Three channels (RGB normals) go
// into a four-channel format with alpha 1, since no GPU format listed here has three 16-bit channels.
// uint16 is unsigned normalised for any channel count (xy normals too), to the range the writer records.
// bc4 and bc5 give their one format whatever the count (the planner refuses a count that differs); ASTC
// its R format for one channel, Rg for any other (refused by the planner unless two); ASTC HDR its one
// format (the planner refuses any count but one).
TexelFormat texelFormatFor(int channels, PixelType type);
PixelType pixelTypeOf(TexelFormat format);
// A block format's block: its side in texels and its bytes (BC4: 4, 8; BC5: 4, 16; ASTC NxN, LDR or HDR: N, 16).
struct BlockShape {
    int side = 4, bytes = 8;
};
BlockShape blockShapeOf(TexelFormat format);
inline bool isAstcFormat(TexelFormat format) { return isAstcType(pixelTypeOf(format)); }
// An ASTC format's two-channel twin (Astc4x4R -> Astc4x4Rg); any other format as it is.
TexelFormat astcTwoChannels(TexelFormat format);

// IEEE 754 binary16, round to nearest even; subnormals kept. floatToHalf is only defined for values
// halfCanHold accepts (finite, |v| < 65520, the first magnitude that rounds to infinity).
std::uint16_t floatToHalf(float value);
float halfToFloat(std::uint16_t half);
inline bool halfCanHold(float value) { return value > -65520.0f && value < 65520.0f; }

}  // namespace heightpack
