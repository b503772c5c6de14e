#include "heightpack/io/displacement_read.hpp"


#include <algorithm>
#include <cmath>

#include "heightpack/io/attributes.hpp"

#include "image_input.hpp"
#include "stderr_silencer.hpp"

namespace heightpack {

namespace {

int findChannel(const detail::SourceSpec& spec, const std::string& name) {
    const auto it = std::find(spec.channelnames.begin(), spec.channelnames.end(), name);
    return it == spec.channelnames.end() ? -1 : static_cast<int>(it - spec.channelnames.begin());
}

// The channels holding D(i,j) of level 0, x then y; {-1, -1} when the file has none.
std::pair<int, int> displacementChannels(const detail::SourceSpec& spec) {
    const std::string stored = spec.get_string_attribute(attr::displacement.name);
    const std::string suffix = stored == "neighbour4" ? ".R" : "";  // R = D(i,j) of a packed layer
    const int x = findChannel(spec, "Dx" + suffix), y = findChannel(spec, "Dy" + suffix);
    return x >= 0 && y >= 0 ? std::pair{x, y} : std::pair{-1, -1};
}

}  // namespace

bool hasDisplacement(const std::string& path) {
    detail::StderrSilencer quiet(true);
    auto opened = detail::openImage(path, detail::SizeLimits{});
    return opened && displacementChannels((*opened)->spec()).first >= 0;
}

Result<Image> loadDisplacement(const std::string& path, const LoadOptions& options) {
    detail::StderrSilencer quiet(options.silenceDecoderMessages);
    auto opened = detail::openImage(path, detail::sizeLimitsOf(options));
    if (!opened) return opened.error();
    detail::ImageSource& in = **opened;
    const detail::SourceSpec spec = in.spec();
    const auto [cx, cy] = displacementChannels(spec);
    if (cx < 0) {
        std::string list;
        for (const std::string& n : spec.channelnames) list += (list.empty() ? "" : ", ") + n;
        return withFix(badInput(path, "holds no horizontal displacement (no Dx, Dy channels; it has " + list + ")",
                                "make the map with its Dx, Dy channels, or leave the displacement out"),
                       Fix::AddDisplacement);
    }
    Image d(spec.width, spec.height, 2);
    std::vector<float> channel(d.texelCount());
    for (const int c : {cx, cy}) {
        if (Status s = detail::readPixels(in, path, 0, c, c + 1, channel.data()); !s) return s.error();
        const int k = c == cx ? 0 : 1;
        for (size_t i = 0; i < channel.size(); ++i) d.pixels[2 * i + k] = channel[i];
    }
    // A heightpack texture stores scale * D: D follows the heights' scale but not their offset.
    if (!spec.get_string_attribute(attr::displacement.name).empty()) {
        const float scale = spec.get_float_attribute(attr::heightScale.name, 1.0f);
        if (scale != 0.0f && scale != 1.0f)
            for (float& v : d.pixels) v /= scale;
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
