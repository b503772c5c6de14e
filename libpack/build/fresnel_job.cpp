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
        attribute(attr::layout, "fresnel"),
        attribute(attr::ior, static_cast<float>(options.ior)),
        attribute(attr::model, options.model),
        attribute(attr::index, options.index),
        attribute(attr::deep, rgbText(options.deep)),
        attribute(attr::shallow, rgbText(options.shallow)),
        attribute(attr::texelCentre, 0.5f),
        attribute(attr::version, version),
    };
    return writeFlatImage(output, makeFresnelRamp(options), flat);
}

}  // namespace heightpack
