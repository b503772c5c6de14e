// Reading height maps: any format OpenImageIO reads (and grey PNGs on a fast path of our own), one channel
// chosen, checked for size and finite values, as a float Image.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/map_units.hpp"

namespace heightpack {

// Which channel of a colour input holds the height. Named: the channel LoadOptions::channelName names
// (an EXR layer's "height.Y", "Z", "depth"); the others find the channel by its usual names, then by position.
enum class ChannelSelect { Auto, R, G, B, A, Luma, Named };
// Auto and Named have no name: Auto is what no choice means, and Named needs the channel's own name.
template <>
struct NameTable<ChannelSelect> {
    static constexpr EnumName<ChannelSelect> entries[] = {
        {ChannelSelect::R, "r", "the red channel"},
        {ChannelSelect::G, "g", "the green channel"},
        {ChannelSelect::B, "b", "the blue channel"},
        {ChannelSelect::A, "a", "the alpha channel"},
        {ChannelSelect::Luma, "luma", "Rec. 709 luma of the colour"},
    };
};
// "r", "g", "b", "a", "luma"; nullopt for anything else (which a caller may take as a channel name).
inline std::optional<ChannelSelect> parseChannelSelect(std::string_view name) { return parseName<ChannelSelect>(name); }

struct LoadOptions {
    // Auto takes a one-channel image (or grey + alpha), or the channel named Y of any image, and
    // refuses a colour image.
    // A heightpack texture (packed neighbour4 or plain) gives its height channel, R or Y, mapped back
    // through its recorded heightScale and heightOffset to the values it was made from.
    ChannelSelect channel = ChannelSelect::Auto;
    std::string channelName;  // with Named: matched exactly, else ignoring case
    // Images larger than this are refused from their header, before any pixel is allocated.
    int maxSide = 32768;
    int64_t maxTexels = int64_t(1) << 28;  // 1 GiB of floats
    // Some decoders (libpng under OpenImageIO 2.4) print their own diagnostics on stderr; what they say
    // also reaches the returned Error. When set, stderr (fd 2) of the whole process is sent to /dev/null
    // while a file is decoded, so a command-line tool keeps its one-line error contract.
    bool silenceDecoderMessages = false;
    int threads = 0;  // 0 = all cores; the decoded heights do not depend on it
};

// What the input file held, for reports and metadata.
struct SourceInfo {
    std::string path;
    std::string format;     // OpenImageIO's format name: "png", "openexr", "tiff", ...
    std::string pixelType;  // the decoder's word for its samples, for reports: "uint8", "uint16", "half", "float", ...
    // 8 or 16 for unsigned integer samples (values on a grid of 1/255 or 1/65535 before any scale); 0 for
    // anything else (floats).
    int integerBits = 0;
    int width = 0;
    int height = 0;
    int channels = 0;
    std::string channelUsed;  // the name of the channel the heights came from, or "luma"
    // Set when the channel was chosen in a way a person may not expect (alpha of a grey image ignored,
    // a colour choice on a grey image, a heightpack texture read back): one sentence saying what was used.
    std::string channelNote;
    std::string decoder;      // "heightpack-png" (fast path for grey PNGs) or "openimageio"
    // What the file records of its tile size, height units and place in an animation, carried into what
    // is made from it (a packed sequence still knows its timing, a packed sea its size and metres). Its
    // heightRange is per unit of the heights returned: a heightpack texture's values are mapped back
    // through its heightScale, so the range is scaled with them.
    MapUnits units;
};

struct LoadedHeights {
    Image heights;  // one channel: 8-bit / 255, 16-bit / 65535, float as is
    SourceInfo source;
};

// Loads the height map at path. Fails with BadInput for a missing, unreadable, corrupt or oversized file,
// a colour image without a channel choice, or non-finite values.
Result<LoadedHeights> loadHeightMap(const std::string& path, const LoadOptions& options = {});

// The formats an input may be in, as a person names them: "PNG, JPEG, TIFF (and BigTIFF), ..." (help
// texts list these; any other format is refused, naming what it is).
std::string readableFormats();

// Checks, before anything is opened, that path names a regular file (not a folder, FIFO, device or
// socket: those would hang or mislead a decoder) that this process may read and that is not empty.
// Fails with BadInput saying which, with a hint.
Status checkReadable(const std::string& path);

// Fails with BadInput naming the first texel of channel `channel` of image that is NaN or infinite;
// `where` (e.g. "level 2") goes before "holds NaN" in the message.
Status checkFinite(const Image& image, const std::string& path, int channel = 0, const std::string& where = {});

// A 64-bit hash (XXH3) of an image's texel values, as 16 hex digits; identical pixels give the same hash.
std::string hashPixels(const Image& image);
// The same over several images' values in turn (the heights, then the channels kept beside them): the
// hash of their concatenation, so one image gives hashPixels(image).
std::string hashPixels(const std::vector<const Image*>& images);

}  // namespace heightpack
