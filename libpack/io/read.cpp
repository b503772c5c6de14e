#include "heightpack/io/read.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <xxhash.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <optional>
#include <vector>

#include "heightpack/io/attributes.hpp"
#include "heightpack/io/texture_description.hpp"

#include "image_input.hpp"
#include "input_format.hpp"
#include "png_fast.hpp"
#include "stderr_silencer.hpp"
#include "text.hpp"

namespace heightpack {

namespace fs = std::filesystem;

namespace {


std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string sizeText(long long w, long long h) { return std::to_string(w) + "x" + std::to_string(h); }

// Finds the channel that --channel names: by name first (R, red, ...), then by position.
int findChannel(const detail::SourceSpec& spec, ChannelSelect select) {
    static const char* names[][2] = {{"r", "red"}, {"g", "green"}, {"b", "blue"}, {"a", "alpha"}};
    const int which = select == ChannelSelect::R ? 0 : select == ChannelSelect::G ? 1 : select == ChannelSelect::B ? 2 : 3;
    for (int c = 0; c < spec.nchannels; ++c) {
        const std::string n = lower(spec.channelnames[c]);
        if (n == names[which][0] || n == names[which][1]) return c;
    }
    if (which == 3) return spec.alpha_channel;
    return which < spec.nchannels && which != spec.alpha_channel ? which : -1;
}

// Finds the channel called name: exactly, then ignoring case, then as a layer holding one channel
// ("height" for "height.Y"). -1 when none or several match.
int findNamedChannel(const detail::SourceSpec& spec, const std::string& name) {
    const auto& names = spec.channelnames;
    for (int c = 0; c < spec.nchannels; ++c)
        if (names[c] == name) return c;
    int found = -1, count = 0;
    for (int c = 0; c < spec.nchannels; ++c)
        if (lower(names[c]) == lower(name)) found = c, ++count;
    if (count == 1) return found;
    found = -1, count = 0;
    for (int c = 0; c < spec.nchannels; ++c)
        if (lower(names[c]).rfind(lower(name) + ".", 0) == 0) found = c, ++count;
    return count == 1 ? found : -1;
}

std::string channelList(const detail::SourceSpec& spec) {
    std::string list;
    for (const std::string& n : spec.channelnames) list += (list.empty() ? "" : ", ") + n;
    return list;
}

std::string numberText(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

}  // namespace

Result<LoadedHeights> loadHeightMap(const std::string& path, const LoadOptions& options) {
    detail::StderrSilencer quiet(options.silenceDecoderMessages);
    auto opened = detail::openImage(path, detail::sizeLimitsOf(options));
    if (!opened) return opened.error();
    detail::OpenedImage& in = *opened;
    const detail::SourceSpec spec = in->spec();

    LoadedHeights out;
    SourceInfo& src = out.source;
    src.path = path;
    src.format = in->format_name();
    src.pixelType = spec.format.c_str();
    src.integerBits = src.pixelType == "uint8" ? 8 : src.pixelType == "uint16" ? 16 : 0;
    src.width = spec.width;
    src.height = spec.height;
    src.channels = spec.nchannels;
    auto described = detail::describeSpec(path, spec);
    if (!described) return described.error();
    const TextureDescription& texture = *described;
    src.units = texture.units;

    const int colourChannels = spec.nchannels - (spec.alpha_channel >= 0 ? 1 : 0);
    const bool colour = colourChannels > 1;
    // A texture heightpack wrote: packed (R = H(i,j)) or plain (Y), its values recorded as offset + scale * value.
    const bool heightTexture = texture.isHeights();
    int channel = 0;
    bool luma = false;
    switch (options.channel) {
        case ChannelSelect::Auto:
            if (texture.kind == TextureKind::Normals)
                return badInput(path, "is a normal map heightpack wrote, not a height map",
                                "give the height map it was made from");
            if (heightTexture) {
                channel = texture.channels.heights.front();  // R = H(i,j) of a packed texel
                break;
            }
            // A height with companions (synth's shift) names its height channel Y.
            if (colour && !texture.channels.heights.empty()) {
                channel = texture.channels.heights.front();
                break;
            }
            if (colour) {
                return withFix(badInput(path,
                                        "is a colour image with " + std::to_string(spec.nchannels) + " channels (" +
                                            channelList(spec) + ")",
                                        "choose the height channel: " + joinedNames<ChannelSelect>() + " or a channel's name"),
                               Fix::ChooseChannel);
            }
            channel = spec.alpha_channel == 0 && spec.nchannels > 1 ? 1 : 0;
            if (spec.alpha_channel >= 0 && spec.nchannels > 1)
                src.channelNote = "grey image with alpha: heights from '" + spec.channelnames[channel] + "', alpha '" +
                                  spec.channelnames[spec.alpha_channel] + "' ignored";
            break;
        case ChannelSelect::Luma:
            luma = colour && colourChannels >= 3;
            channel = spec.alpha_channel == 0 && spec.nchannels > 1 ? 1 : 0;
            if (!luma) src.channelNote = "not a colour image: heights from its grey '" + spec.channelnames[channel] + "'";
            break;
        case ChannelSelect::Named:
            channel = findNamedChannel(spec, options.channelName);
            if (channel < 0) {
                return withFix(badInput(path, "has no channel named '" + options.channelName + "' (it has " + channelList(spec) + ")",
                                        "pick a channel it has"),
                               Fix::ChooseExistingChannel);
            }
            break;
        default:
            // A grey image is its own red, green and blue.
            channel = colour || options.channel == ChannelSelect::A ? findChannel(spec, options.channel)
                                                                      : (spec.alpha_channel == 0 ? 1 : 0);
            if (channel < 0) {
                return withFix(badInput(path, "has no such channel (it has " + channelList(spec) + ")", "pick a channel it has"),
                               Fix::ChooseExistingChannel);
            }
            if (!colour && options.channel != ChannelSelect::A)
                src.channelNote = "grey image: its one grey channel '" + spec.channelnames[channel] +
                                  "' stands for red, green and blue";
    }
    src.channelUsed = luma ? nameOf(ChannelSelect::Luma) : spec.channelnames[channel];

    // Values back from a heightpack texture: value = (stored - offset) / scale.
    double scale = 1.0, offset = 0.0;
    if (heightTexture && !luma) {
        scale = texture.heightScale;
        offset = texture.heightOffset;
        if (scale == 0.0) scale = 1.0;
        if (src.units.heightRange) *src.units.heightRange *= scale;  // metres per unit of the values returned
        src.channelNote = std::string(texture.layout == Layout::Neighbour4 ? "packed" : "plain") + " heightpack texture: heights from '" +
                          src.channelUsed + "' of level 0, mapped back to values through its heightScale " +
                          numberText(scale) + " and heightOffset " + numberText(offset);
    }
    const auto unmap = [&](Image& heights) {
        if (scale == 1.0 && offset == 0.0) return;
        for (float& v : heights.pixels) v = static_cast<float>((v - offset) / scale);
    };

    if (!luma && src.format == "png" && spec.nchannels <= 2) {
        if (const auto plan = detail::planGreyPng(in.bytes(), spec.width, spec.height, channel)) {
            if (auto fast = detail::decodeGreyPng(in.releaseBytes(), *plan, options.threads)) {
                out.heights = std::move(*fast);
                unmap(out.heights);
                src.decoder = "heightpack-png";
                return out;  // integer samples: always finite
            }
            // Valid chunks around data that does not inflate: OpenImageIO reads the file again and says
            // what is wrong with it.
            auto reopened = detail::openImage(path, detail::sizeLimitsOf(options));
            if (!reopened) return reopened.error();
            in = std::move(*reopened);
        }
    }
    src.decoder = in->decoder();

    const int chBegin = luma ? 0 : channel;
    const int chCount = luma ? 3 : 1;
    std::vector<float> pixels;
    try {
        pixels.resize(spec.image_pixels() * chCount);
    } catch (const std::bad_alloc&) {
        return badInput(path, "is " + sizeText(spec.width, spec.height) + ", too large for this machine's memory",
                        "split or downsize the map");
    }
    if (Status read = detail::readPixels(*in, path, 0, chBegin, chBegin + chCount, pixels.data()); !read)
        return read.error();
    in->close();

    Image& heights = out.heights;
    heights = Image(spec.width, spec.height, 1);
    if (luma) {
        // Rec. 709 weights on the stored values: heights are data, so no transfer curve is undone.
        for (size_t i = 0; i < heights.pixels.size(); ++i)
            heights.pixels[i] = 0.2126f * pixels[3 * i] + 0.7152f * pixels[3 * i + 1] + 0.0722f * pixels[3 * i + 2];
    } else {
        heights.pixels = std::move(pixels);
    }
    unmap(heights);
    if (Status finite = checkFinite(heights, path); !finite) return finite.error();
    return out;
}

Status checkFinite(const Image& image, const std::string& path, int channel, const std::string& where) {
    for (size_t t = 0; t < image.texelCount(); ++t) {
        const float v = image.pixels[t * image.channels + channel];
        if (std::isfinite(v)) continue;
        const size_t x = t % image.width, y = t / image.width;
        return badInput(path,
                        (where.empty() ? "" : where + " ") + "holds " + (std::isnan(v) ? "NaN" : "an infinite value") +
                            " at texel " + std::to_string(x) + "," + std::to_string(y),
                        "fix the map in the tool that made it");
    }
    return Done{};
}

namespace detail {

Result<int> openReadable(const std::string& path) {
    if (path.empty()) return badInput("''", "the input path is empty", "name an image file");
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        if (errno == EACCES)
            return badInput(path, "permission denied", "make its folder readable (chmod) or run as a user who may read it");
        if (errno == ENOTDIR) return badInput(path, "no such file (a part of the path is not a folder)", "check the path");
        return badInput(path, "no such file", "check the path");
    }
    if (S_ISDIR(st.st_mode)) return badInput(path, "is a folder, not an image", "name an image file");
    auto notRegular = [&](mode_t mode) {
        const char* what = S_ISFIFO(mode)                   ? "is a FIFO (named pipe)"
                           : S_ISCHR(mode) || S_ISBLK(mode) ? "is a device"
                           : S_ISSOCK(mode)                 ? "is a socket"
                                                            : "is not a regular file";
        return badInput(path, std::string(what) + ", not a regular file",
                        "save the image to a file first; heightpack reads only regular files");
    };
    if (!S_ISREG(st.st_mode)) return notRegular(st.st_mode);  // never opened: opening a device can act
    // Without blocking: should the path become a FIFO after the stat, the open still returns, and the
    // descriptor's own fstat below refuses it.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        if (errno == EACCES || errno == EPERM)
            return badInput(path, "permission denied", "make it readable (chmod u+r) or run as a user who may read it");
        return badInput(path, std::string("cannot be opened: ") + std::strerror(errno), "check the file");
    }
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        const mode_t mode = st.st_mode;
        ::close(fd);
        return notRegular(mode);
    }
    if (st.st_size == 0) {
        ::close(fd);
        return badInput(path, "file is empty", "export the height map again");
    }
    return fd;
}

}  // namespace detail

Status checkReadable(const std::string& path) {
    auto fd = detail::openReadable(path);
    if (!fd) return fd.error();
    ::close(*fd);
    return Done{};
}

std::string hashPixels(const Image& image) { return hashPixels(std::vector<const Image*>{&image}); }

std::string hashPixels(const std::vector<const Image*>& images) {
    XXH3_state_t* state = XXH3_createState();
    if (!state) throw std::bad_alloc();
    XXH3_64bits_reset(state);
    for (const Image* image : images) XXH3_64bits_update(state, image->pixels.data(), image->pixels.size() * sizeof(float));
    const XXH64_hash_t h = XXH3_64bits_digest(state);
    XXH3_freeState(state);
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
    return text;
}

}  // namespace heightpack
