#include "heightpack/build/fresnel_job.hpp"

#include <cstdio>

#include "heightpack/io/image_write.hpp"

namespace heightpack {

namespace {

std::string rgbText(const Rgb& c) {
    char text[96];
    std::snprintf(text, sizeof text, "%.6g,%.6g,%.6g", c[0], c[1], c[2]);
    return text;
}

}  // namespace

Status writeFresnelRamp(const std::string& output, const FresnelOptions& options, RampFormat format,
                        const std::string& version) {
    FlatImageOptions flat;
    flat.bits = format == RampFormat::Png8 ? 8 : 32;
    flat.srgbChannels = 3;  // the water colours; the reflectance in alpha stays linear
    flat.attributes = {
        {"heightpack:layout", std::string("fresnel")},
        {"heightpack:ior", static_cast<float>(options.ior)},
        {"heightpack:model", std::string(fresnelModelName(options.model))},
        {"heightpack:index", std::string(fresnelIndexName(options.index))},
        {"heightpack:deep", rgbText(options.deep)},
        {"heightpack:shallow", rgbText(options.shallow)},
        {"heightpack:texelCentre", 0.5f},
        {"heightpack:version", version},
    };
    return writeFlatImage(output, makeFresnelRamp(options), flat);
}

}  // namespace heightpack
