#include "heightpack/bake/fresnel_job.hpp"

#include <cstdio>

#include "heightpack/io/image_write.hpp"
#include "heightpack/io/texture_write.hpp"

namespace heightpack {

namespace {

std::string rgbText(const Rgb& c) {
    char text[96];
    std::snprintf(text, sizeof text, "%.6g,%.6g,%.6g", c[0], c[1], c[2]);
    return text;
}

}  // namespace

Status writeFresnelRamp(const std::string& output, const FresnelOptions& options, RampFormat format,
                        const std::string& version, PixelType pixelType) {
    FlatImageOptions flat;
    flat.bits = format == RampFormat::Png8 ? 8 : 32;
    flat.srgbChannels = 3;  // the water colours; the reflectance in alpha stays linear
    flat.attributes = {
        attribute(attr::layout, attr::fresnelRamp),
        attribute(attr::ior, static_cast<float>(options.ior)),
        attribute(attr::model, options.model),
        attribute(attr::index, options.index),
        attribute(attr::deep, rgbText(options.deep)),
        attribute(attr::shallow, rgbText(options.shallow)),
        attribute(attr::texelCentre, 0.5f),
        attribute(attr::version, version),
    };
    const Image ramp = makeFresnelRamp(options);
    // The container, decided once from the name: a KTX2 or DDS goes to writeTexture as such.
    if (const auto container = containerForPath(output); container == Container::Ktx2 || container == Container::Dds) {
        ChainToWrite content;
        content.width = ramp.width;
        content.height = ramp.height;
        content.channelNames = {"R", "G", "B", "A"};
        content.fillRows = [&](int, int y0, int rows, float* dst) {
            std::copy(ramp.row(y0), ramp.row(y0) + size_t(rows) * ramp.width * ramp.channels, dst);
        };
        content.attributes = flat.attributes;
        TextureWriteOptions write;
        write.storage.pixelType = pixelType;
        write.levels = 1;  // a ramp is looked up, never minified
        write.writer = "heightpack " + version;
        return writeTexture({output, *container}, content, write);
    }
    if (pixelType == PixelType::Uint16)
        return cannotWrite(output, "an EXR has no 16-bit normalised channels", "store float or half, or write .ktx2 or .dds");
    flat.half = format == RampFormat::Exr && pixelType == PixelType::Half;
    return writeFlatImage(output, ramp, flat);
}

}  // namespace heightpack
