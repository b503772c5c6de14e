// Internal: an image being decoded, as every reader of libpack/io sees it, whoever decodes it: OpenEXR
// directly (exr_source.cpp) or OpenImageIO, which lives in a module of its own that is loaded the first
// time a format needs it (oiio_module.hpp). The header is header-only on purpose: the module is built
// from it too, so both sides agree on the layout (kModuleInterface says which version).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace heightpack::detail {

// One attribute of a file's header, as OpenImageIO's ImageSpec gives it.
struct SourceAttribute {
    std::string name;
    std::string text;      // as ParamValue::get_string (a float as %g)
    bool isFloat = false;  // stored as one float (an EXR float attribute)
    bool hasNumber = false;  // ParamValue::get_float gives a number (float, half, double)
    float number = 0.0f;
};

// The header of the current level: the fields of OpenImageIO's ImageSpec that heightpack reads, with
// its names, so the readers read the same whoever decoded.
struct SourceSpec {
    int width = 0, height = 0, depth = 1, nchannels = 0;
    std::vector<std::string> channelnames;
    int alpha_channel = -1;
    std::string format;  // the pixel type: uint8, uint16, half, float, ...
    int tile_width = 0, tile_height = 0;
    std::vector<SourceAttribute> extra_attribs;

    int64_t image_pixels() const { return int64_t(width) * height * depth; }
    const SourceAttribute* find_attribute(const std::string& name) const {
        for (const SourceAttribute& a : extra_attribs)
            if (a.name == name) return &a;
        return nullptr;
    }
    std::string get_string_attribute(const std::string& name) const {
        const SourceAttribute* a = find_attribute(name);
        return a ? a->text : std::string();
    }
    float get_float_attribute(const std::string& name, float otherwise) const {
        const SourceAttribute* a = find_attribute(name);
        return a && a->hasNumber ? a->number : otherwise;
    }
};

// A decoder over one file's bytes (which its owner keeps alive), at subimage 0.
class ImageSource {
public:
    virtual ~ImageSource() = default;
    virtual const char* format_name() const = 0;  // "openexr", "png", "tiff", ...
    virtual const char* decoder() const = 0;      // "openexr", "openimageio"
    virtual const SourceSpec& spec() const = 0;
    // Moves to mip level `level`; false when the file has no such level.
    virtual bool seekLevel(int level) = 0;
    // Channels [chBegin, chEnd) of `level` as floats into dst. False, or an error text, when the decoder
    // reports anything: the caller refuses the file with that text.
    virtual bool read(int level, int chBegin, int chEnd, float* dst, std::string& error) = 0;
    virtual void close() = 0;
};

// What the module writes: a flat image to `path` in the format its extension names.
struct ModuleWrite {
    std::string path;
    int width = 0, height = 0, channels = 0;
    int bits = 32;  // 8, 16 or 32
    bool half = false;
    std::vector<std::string> channelNames;
    int alphaChannel = -1;
    bool srgb = false;
    struct Attribute {
        std::string name;
        std::string text;
        bool isFloat = false;
        float number = 0.0f;
    };
    std::vector<Attribute> attributes;
    const float* pixels = nullptr;
};

inline constexpr int kModuleInterface = 1;

// What the OpenImageIO module gives: readers for the formats heightpack does not decode itself, the
// flat-image writer for the formats it does not write itself, and its thread count.
class ImageModule {
public:
    virtual ~ImageModule() = default;
    virtual int interfaceVersion() const = 0;
    virtual std::string libraryVersion() const = 0;
    // A reader of formatName (OpenImageIO's name) over bytes, opened; null with error set when it fails.
    // createFailed tells a format OpenImageIO has no reader for from a file its reader refuses.
    virtual std::unique_ptr<ImageSource> open(const std::string& formatName, const unsigned char* bytes, size_t size,
                                              const std::string& path, std::string& error, bool& createFailed) = 0;
    // Writes request; false with error set when it fails (createFailed: no writer for the file type).
    virtual bool write(const ModuleWrite& request, std::string& error, bool& createFailed) = 0;
    virtual void setThreads(int threads) = 0;
};

}  // namespace heightpack::detail

// The one symbol the module exports (extern "C", so dlsym finds it by this name).
extern "C" heightpack::detail::ImageModule* heightpack_image_module();
