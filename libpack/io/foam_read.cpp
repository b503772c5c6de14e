#include "heightpack/io/foam_read.hpp"


#include <algorithm>
#include <cmath>

#include "heightpack/io/attributes.hpp"

#include "image_input.hpp"
#include "stderr_silencer.hpp"

namespace heightpack {

namespace {

// The channel holding F(i,j) of level 0 (R of a packed layer); -1 when the file has none.
int foamChannel(const TextureDescription& texture) {
    return texture.channels.hasFoam() ? texture.channels.foam.front() : -1;
}

}  // namespace

bool hasFoam(const std::string& path) {
    detail::StderrSilencer quiet(true);
    auto opened = detail::openImage(path, detail::SizeLimits{});
    if (!opened) return false;
    auto texture = detail::describeSpec(path, (*opened)->spec());
    return texture && foamChannel(*texture) >= 0;
}

Result<Image> loadFoam(const std::string& path, const LoadOptions& options) {
    detail::StderrSilencer quiet(options.silenceDecoderMessages);
    auto opened = detail::openImage(path, detail::sizeLimitsOf(options));
    if (!opened) return opened.error();
    detail::ImageSource& in = **opened;
    const detail::SourceSpec spec = in.spec();
    auto texture = detail::describeSpec(path, spec);
    if (!texture) return texture.error();
    const int c = foamChannel(*texture);
    if (c < 0) {
        std::string list;
        for (const std::string& n : spec.channelnames) list += (list.empty() ? "" : ", ") + n;
        return withFix(badInput(path, "holds no foam coverage (no Foam channel; it has " + list + ")",
                                "make the map with its Foam channel, or leave the foam out"),
                       Fix::AddFoam);
    }
    Image foam(spec.width, spec.height, 1);
    if (Status s = detail::readPixels(in, path, 0, c, c + 1, foam.pixels.data()); !s) return s.error();
    for (size_t t = 0; t < foam.pixels.size(); ++t) {
        if (std::isfinite(foam.pixels[t])) continue;
        return badInput(path,
                        std::string("Foam holds ") + (std::isnan(foam.pixels[t]) ? "NaN" : "an infinite value") +
                            " at texel " + std::to_string(t % foam.width) + "," + std::to_string(t / foam.width),
                        "fix the map in the tool that made it");
    }
    return foam;
}

}  // namespace heightpack
