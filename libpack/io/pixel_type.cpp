// Pixel types, texel formats and their codes. Half conversion is Imath's (OpenEXR's own half type),
// which rounds to nearest even.
#include "heightpack/io/pixel_type.hpp"

#include <Imath/half.h>

#include <array>

#include "heightpack/io/files.hpp"

namespace heightpack {

namespace {

// Vulkan and DXGI codes from the Vulkan registry and Microsoft's DXGI_FORMAT enumeration.
constexpr std::array<TexelFormatInfo, 21> kFormats = {{
    {TexelFormat::Rgba32F, 4, ComponentKind::Float32, 109, 2, "VK_FORMAT_R32G32B32A32_SFLOAT",
     "DXGI_FORMAT_R32G32B32A32_FLOAT"},
    {TexelFormat::Rgba16F, 4, ComponentKind::Float16, 97, 10, "VK_FORMAT_R16G16B16A16_SFLOAT",
     "DXGI_FORMAT_R16G16B16A16_FLOAT"},
    {TexelFormat::Rgba16Unorm, 4, ComponentKind::Unorm16, 91, 11, "VK_FORMAT_R16G16B16A16_UNORM",
     "DXGI_FORMAT_R16G16B16A16_UNORM"},
    {TexelFormat::Rg32F, 2, ComponentKind::Float32, 103, 16, "VK_FORMAT_R32G32_SFLOAT", "DXGI_FORMAT_R32G32_FLOAT"},
    {TexelFormat::Rg16F, 2, ComponentKind::Float16, 83, 34, "VK_FORMAT_R16G16_SFLOAT", "DXGI_FORMAT_R16G16_FLOAT"},
    {TexelFormat::Rg16Unorm, 2, ComponentKind::Unorm16, 77, 35, "VK_FORMAT_R16G16_UNORM", "DXGI_FORMAT_R16G16_UNORM"},
    {TexelFormat::Rg16Snorm, 2, ComponentKind::Snorm16, 78, 37, "VK_FORMAT_R16G16_SNORM", "DXGI_FORMAT_R16G16_SNORM"},
    {TexelFormat::R32F, 1, ComponentKind::Float32, 100, 41, "VK_FORMAT_R32_SFLOAT", "DXGI_FORMAT_R32_FLOAT"},
    {TexelFormat::R16F, 1, ComponentKind::Float16, 76, 54, "VK_FORMAT_R16_SFLOAT", "DXGI_FORMAT_R16_FLOAT"},
    {TexelFormat::R16Unorm, 1, ComponentKind::Unorm16, 70, 56, "VK_FORMAT_R16_UNORM", "DXGI_FORMAT_R16_UNORM"},
    {TexelFormat::Bc4Unorm, 1, ComponentKind::Block, 139, 80, "VK_FORMAT_BC4_UNORM_BLOCK", "DXGI_FORMAT_BC4_UNORM"},
    {TexelFormat::Bc5Unorm, 2, ComponentKind::Block, 141, 83, "VK_FORMAT_BC5_UNORM_BLOCK", "DXGI_FORMAT_BC5_UNORM"},
    // The one-channel entry of each pair first: the one texelFormatFromVk gives.
    {TexelFormat::Astc4x4R, 1, ComponentKind::Block, 157, 0, "VK_FORMAT_ASTC_4x4_UNORM_BLOCK", ""},
    {TexelFormat::Astc4x4Rg, 2, ComponentKind::Block, 157, 0, "VK_FORMAT_ASTC_4x4_UNORM_BLOCK", ""},
    {TexelFormat::Astc6x6R, 1, ComponentKind::Block, 165, 0, "VK_FORMAT_ASTC_6x6_UNORM_BLOCK", ""},
    {TexelFormat::Astc6x6Rg, 2, ComponentKind::Block, 165, 0, "VK_FORMAT_ASTC_6x6_UNORM_BLOCK", ""},
    {TexelFormat::Astc8x8R, 1, ComponentKind::Block, 171, 0, "VK_FORMAT_ASTC_8x8_UNORM_BLOCK", ""},
    {TexelFormat::Astc8x8Rg, 2, ComponentKind::Block, 171, 0, "VK_FORMAT_ASTC_8x8_UNORM_BLOCK", ""},
    // VK_EXT_texture_compression_astc_hdr (core in Vulkan 1.3 without the suffix).
    {TexelFormat::AstcHdr4x4R, 1, ComponentKind::Block, 1000066000, 0, "VK_FORMAT_ASTC_4x4_SFLOAT_BLOCK_EXT", ""},
    {TexelFormat::AstcHdr6x6R, 1, ComponentKind::Block, 1000066004, 0, "VK_FORMAT_ASTC_6x6_SFLOAT_BLOCK_EXT", ""},
    {TexelFormat::AstcHdr8x8R, 1, ComponentKind::Block, 1000066007, 0, "VK_FORMAT_ASTC_8x8_SFLOAT_BLOCK_EXT", ""},
}};

}  // namespace

std::optional<Container> containerForPath(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".exr") return Container::Exr;
    if (ext == ".ktx2") return Container::Ktx2;
    if (ext == ".dds") return Container::Dds;
    return std::nullopt;
}

const TexelFormatInfo& texelFormatInfo(TexelFormat format) {
    for (const TexelFormatInfo& info : kFormats)
        if (info.format == format) return info;
    return kFormats[0];
}

std::optional<TexelFormat> texelFormatFromVk(std::uint32_t vkFormat) {
    for (const TexelFormatInfo& info : kFormats)
        if (info.vkFormat == vkFormat) return info.format;
    return std::nullopt;
}

std::optional<TexelFormat> texelFormatFromDxgi(std::uint32_t dxgiFormat) {
    for (const TexelFormatInfo& info : kFormats)
        if (info.dxgiFormat != 0 && info.dxgiFormat == dxgiFormat) return info.format;
    return std::nullopt;
}

TexelFormat texelFormatFor(int channels, PixelType type) {
    if (type == PixelType::Bc4) return TexelFormat::Bc4Unorm;
    if (type == PixelType::Bc5) return TexelFormat::Bc5Unorm;
    if (type == PixelType::Astc4x4) return channels == 1 ? TexelFormat::Astc4x4R : TexelFormat::Astc4x4Rg;
    if (type == PixelType::Astc6x6) return channels == 1 ? TexelFormat::Astc6x6R : TexelFormat::Astc6x6Rg;
    if (type == PixelType::Astc8x8) return channels == 1 ? TexelFormat::Astc8x8R : TexelFormat::Astc8x8Rg;
    if (type == PixelType::AstcHdr4x4) return TexelFormat::AstcHdr4x4R;
    if (type == PixelType::AstcHdr6x6) return TexelFormat::AstcHdr6x6R;
    if (type == PixelType::AstcHdr8x8) return TexelFormat::AstcHdr8x8R;
    switch (channels) {
        case 1:
            return type == PixelType::Float  ? TexelFormat::R32F
                   : type == PixelType::Half ? TexelFormat::R16F
                                             : TexelFormat::R16Unorm;
        case 2:
            return type == PixelType::Float  ? TexelFormat::Rg32F
                   : type == PixelType::Half ? TexelFormat::Rg16F
                                             : TexelFormat::Rg16Unorm;
        default:
            return type == PixelType::Float  ? TexelFormat::Rgba32F
                   : type == PixelType::Half ? TexelFormat::Rgba16F
                                             : TexelFormat::Rgba16Unorm;
    }
}

PixelType pixelTypeOf(TexelFormat format) {
    switch (texelFormatInfo(format).kind) {
        case ComponentKind::Float32: return PixelType::Float;
        case ComponentKind::Float16: return PixelType::Half;
        case ComponentKind::Unorm16:
        case ComponentKind::Snorm16: return PixelType::Uint16;
        case ComponentKind::Block: break;
    }
    switch (format) {
        case TexelFormat::Bc4Unorm: return PixelType::Bc4;
        case TexelFormat::Bc5Unorm: return PixelType::Bc5;
        case TexelFormat::Astc4x4R:
        case TexelFormat::Astc4x4Rg: return PixelType::Astc4x4;
        case TexelFormat::Astc6x6R:
        case TexelFormat::Astc6x6Rg: return PixelType::Astc6x6;
        case TexelFormat::Astc8x8R:
        case TexelFormat::Astc8x8Rg: return PixelType::Astc8x8;
        case TexelFormat::AstcHdr4x4R: return PixelType::AstcHdr4x4;
        case TexelFormat::AstcHdr6x6R: return PixelType::AstcHdr6x6;
        case TexelFormat::AstcHdr8x8R: return PixelType::AstcHdr8x8;
        default: return PixelType::Float;
    }
}

BlockShape blockShapeOf(TexelFormat format) {
    switch (pixelTypeOf(format)) {
        case PixelType::Bc5: return {4, 16};
        case PixelType::Astc4x4:
        case PixelType::AstcHdr4x4: return {4, 16};
        case PixelType::Astc6x6:
        case PixelType::AstcHdr6x6: return {6, 16};
        case PixelType::Astc8x8:
        case PixelType::AstcHdr8x8: return {8, 16};
        default: return {4, 8};
    }
}

TexelFormat astcTwoChannels(TexelFormat format) {
    switch (format) {
        case TexelFormat::Astc4x4R: return TexelFormat::Astc4x4Rg;
        case TexelFormat::Astc6x6R: return TexelFormat::Astc6x6Rg;
        case TexelFormat::Astc8x8R: return TexelFormat::Astc8x8Rg;
        default: return format;
    }
}

std::uint16_t floatToHalf(float value) { return Imath::half(value).bits(); }

float halfToFloat(std::uint16_t bits) {
    Imath::half h;
    h.setBits(bits);
    return float(h);
}

}  // namespace heightpack
