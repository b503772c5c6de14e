// Flat image files: a float EXR through exr_write.cpp, a grey PNG through png_write.cpp, the rest through
// OpenImageIO (the format module), written to a temporary file and renamed into place.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <utility>
#include <vector>

#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/image_write.hpp"

#include "format_module_loader.hpp"
#include "png_write.hpp"
#include "texel_encode.hpp"
#include "text.hpp"

namespace heightpack {

namespace {

// The sRGB transfer function (IEC 61966-2-1), linear [0,1] to encoded [0,1].
double encodeSrgb(double linear) {
    const double v = std::clamp(linear, 0.0, 1.0);
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

// Whether writeFlatImage encodes the image itself: one grey channel in an 8- or 16-bit PNG.
bool encodesGreyPng(const std::string& ext, const Image& image, const FlatImageOptions& options) {
    return ext == ".png" && image.channels == 1 && options.bits != 32 && options.srgbChannels == 0;
}

}  // namespace

PreparedPixels preparePixels(const std::string& path, const Image& image, const FlatImageOptions& options) {
    if (!encodesGreyPng(lowerExtension(path), image, options)) return {};
    return {std::make_shared<const detail::GreyPngPixels>(detail::compressGreyPngPixels(image, options.bits, options.threads))};
}

Status writeFlatImage(const std::string& path, const Image& image, const FlatImageOptions& options) {
    assert(image.channels >= 1 && image.channels <= 4 && !image.empty());
    if (Status writable = checkWritable(path); !writable) return writable;
    // The extension decides the format; only those that hold what is given faithfully are written.
    const std::string ext = lowerExtension(path);
    if (std::find(kFlatImageExtensions.begin(), kFlatImageExtensions.end(), ext) == kFlatImageExtensions.end())
        return cannotWrite(path, "names no format heightpack writes", "use .png, .tif or .exr");
    // OpenImageIO's default names (Y; R, G; R, G, B; R, G, B and alpha A) unless given.
    detail::ModuleWrite spec;
    spec.channelNames = image.channels == 1 ? std::vector<std::string>{"Y"}
                                            : std::vector<std::string>{"R", "G", "B", "A"};
    spec.channelNames.resize(size_t(image.channels));
    if (image.channels == 4) spec.alphaChannel = 3;
    if (!options.channelNames.empty()) {
        assert(int(options.channelNames.size()) == image.channels);
        spec.channelNames = options.channelNames;
        spec.alphaChannel = -1;
    }
    if (ext == ".exr" && options.bits == 32) {
        // Our own ZIP writer: libdeflate on all threads, where OpenImageIO deflates with zlib.
        ScanlineExrContent content;
        content.width = image.width;
        content.height = image.height;
        content.channelNames = spec.channelNames;
        content.pixels = image.pixels.data();
        content.attributes = options.attributes;
        return writeScanlineExr(path, content, options.half, options.threads, options.compression);
    }
    // The last guard before bytes reach a file: an output never holds NaN or infinity
    // (writeScanlineExr keeps its own).
    for (size_t i = 0; i < image.pixels.size(); ++i)
        if (!std::isfinite(image.pixels[i]))
            return Error{ErrorKind::Internal, path, "internal error: the image holds a non-finite value; nothing was written",
                         "please report this with the command line"};
    // PNG keeps text chunks only: numbers go in as text there, so nothing recorded is lost.
    if (encodesGreyPng(ext, image, options)) {
        const Attributes text = detail::attributesAsText(options.attributes);
        const detail::GreyPngPixels* prepared = options.prepared.png.get();
        const bool fits = prepared && prepared->width == image.width && prepared->height == image.height && prepared->bits == options.bits;
        const std::vector<unsigned char> bytes = fits ? detail::assembleGreyPng(*prepared, text)
                                                      : detail::encodeGreyPng(image, options.bits, text, options.threads);
        TemporaryFile temp(path);
        std::unique_ptr<std::FILE, detail::FileCloser> file(std::fopen(temp.path().c_str(), "wb"));
        if (!file || std::fwrite(bytes.data(), 1, bytes.size(), file.get()) != bytes.size() || std::fflush(file.get()) != 0 ||
            std::fclose(file.release()) != 0)
            return cannotWrite(path, "writing failed", "check free disk space and permissions");
        return temp.commit();
    }
    TemporaryFile temp(path);
    spec.path = temp.path();
    spec.width = image.width;
    spec.height = image.height;
    spec.channels = image.channels;
    spec.bits = options.bits;
    spec.half = options.half;
    spec.srgb = options.srgbChannels > 0 && options.bits != 32;
    for (const ExrAttribute& a : options.attributes) {
        if (const auto* text = std::get_if<std::string>(&a.value))
            spec.attributes.push_back({a.name, *text});
        else if (ext == ".png")
            spec.attributes.push_back({a.name, detail::floatText(std::get<float>(a.value))});
        else
            spec.attributes.push_back({a.name, {}, true, std::get<float>(a.value)});
    }

    std::vector<float> pixels = image.pixels;
    if (options.bits != 32) {
        for (size_t i = 0; i < pixels.size(); ++i) {
            const int channel = static_cast<int>(i % image.channels);
            double v = pixels[i];
            if (channel < options.srgbChannels) v = encodeSrgb(v);
            pixels[i] = static_cast<float>(std::clamp(v, 0.0, 1.0));
        }
    }

    // Messages name the output, never the temporary file the user did not ask for.
    auto named = [&](std::string text) {
        for (size_t at; (at = text.find(temp.path())) != std::string::npos;) text.replace(at, temp.path().size(), path);
        return detail::firstLine(text);
    };
    auto module = detail::formatModule(path, "cannot be written");
    if (!module) return module.error();
    spec.pixels = pixels.data();
    std::string error;
    bool createFailed = false;
    if (!(*module)->write(spec, error, createFailed)) {
        if (createFailed) return cannotWrite(path, "no writer for this file type: " + named(error), "use .png, .tif or .exr");
        return cannotWrite(path, "writing failed: " + named(error), "check free disk space and permissions");
    }
    return temp.commit();
}

}  // namespace heightpack
