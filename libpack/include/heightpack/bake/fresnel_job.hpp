// The whole `fresnel` operation: make the ramp and write it.
#pragma once

#include <string>

#include "heightpack/core/fresnel.hpp"
#include "heightpack/core/names.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/pixel_type.hpp"

namespace heightpack {

enum class RampFormat {
    Exr,   // RGBA 32-bit float, linear
    Png8,  // 8-bit, rgb sRGB-encoded, alpha (the reflectance) linear
};
template <>
struct NameTable<RampFormat> {
    static constexpr EnumName<RampFormat> entries[] = {
        {RampFormat::Exr, "exr", "float or half (or uint16) in an .exr, .ktx2 or .dds"},
        {RampFormat::Png8, "png8", "8-bit PNG, rgb sRGB-encoded"},
    };
};

// Writes the ramp of options to output, atomically, with its parameters in the metadata. An output named
// .ktx2 or .dds gets one level in pixelType; an EXR (format Exr) is float or half.
Status writeFresnelRamp(const std::string& output, const FresnelOptions& options, RampFormat format,
                        const std::string& version, PixelType pixelType = PixelType::Float);

}  // namespace heightpack
