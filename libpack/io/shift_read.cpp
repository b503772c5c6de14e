#include "heightpack/io/shift_read.hpp"


#include <algorithm>
#include <cmath>

#include "heightpack/io/attributes.hpp"

#include "image_input.hpp"
#include "stderr_silencer.hpp"

namespace heightpack {

namespace {

// The channels holding D(i,j) of level 0, x then y (R of a packed layer); {-1, -1} when the file has none.
std::pair<int, int> shiftChannels(const TextureDescription& texture) {
    const TextureChannels& c = texture.channels;
    return c.shift() ? std::pair{c.dx.front(), c.dy.front()} : std::pair{-1, -1};
}

}  // namespace

bool hasShift(const std::string& path) {
    detail::StderrSilencer quiet(true);
    auto opened = detail::openImage(path, detail::SizeLimits{});
    if (!opened) return false;
    auto texture = detail::describeSpec(path, (*opened)->spec());
    return texture && shiftChannels(*texture).first >= 0;
}

Result<Image> loadShift(const std::string& path, const LoadOptions& options) {
    detail::StderrSilencer quiet(options.silenceDecoderMessages);
    auto opened = detail::openImage(path, detail::sizeLimitsOf(options));
    if (!opened) return opened.error();
    detail::ImageSource& in = **opened;
    const detail::SourceSpec spec = in.spec();
    auto texture = detail::describeSpec(path, spec);
    if (!texture) return texture.error();
    const auto [cx, cy] = shiftChannels(*texture);
    if (cx < 0) {
        std::string list;
        for (const std::string& n : spec.channelnames) list += (list.empty() ? "" : ", ") + n;
        return withFix(badInput(path, "holds no shift (no Dx, Dy channels; it has " + list + ")",
                                "make the map with its Dx, Dy channels, or leave the shift out"),
                       Fix::AddShift);
    }
    Image d(spec.width, spec.height, 2);
    std::vector<float> channel(d.texelCount());
    for (const int c : {cx, cy}) {
        if (Status s = detail::readPixels(in, path, 0, c, c + 1, channel.data()); !s) return s.error();
        const int k = c == cx ? 0 : 1;
        for (size_t i = 0; i < channel.size(); ++i) d.pixels[2 * i + k] = channel[i];
    }
    // A heightpack texture stores scale * D: D follows the heights' scale but not their offset.
    if (texture->shift) {
        const double scale = texture->heightScale;
        if (scale != 0.0 && scale != 1.0)
            for (float& v : d.pixels) v = static_cast<float>(v / scale);
    }
    for (size_t t = 0; t < d.pixels.size(); ++t) {
        if (std::isfinite(d.pixels[t])) continue;
        const size_t texel = t / 2;
        return badInput(path,
                        std::string(t % 2 ? "Dy" : "Dx") + " holds " + (std::isnan(d.pixels[t]) ? "NaN" : "an infinite value") +
                            " at texel " + std::to_string(texel % d.width) + "," + std::to_string(texel / d.width),
                        "fix the map in the tool that made it");
    }
    return d;
}

}  // namespace heightpack
