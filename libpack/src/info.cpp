#include "heightpack/info.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <filesystem>
#include <limits>

#include "stderr_silencer.hpp"
#include "strings.hpp"

namespace heightpack {

namespace {


}  // namespace

Result<FileInfo> readFileInfo(const std::string& path, bool silenceDecoderMessages) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return badInput(path, "no such file", "check the path");
    detail::StderrSilencer quiet(silenceDecoderMessages);
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) return badInput(path, "cannot be read as an image: " + detail::firstLine(OIIO::geterror()), "check the file");

    FileInfo info;
    info.path = path;
    info.format = in->format_name();
    const OIIO::ImageSpec& top = in->spec();
    info.pixelType = top.format.c_str();
    info.channelNames = top.channelnames;
    info.tiled = top.tile_width > 0;
    info.tileWidth = top.tile_width;
    info.tileHeight = top.tile_height;
    for (const OIIO::ParamValue& p : top.extra_attribs) info.attributes.emplace_back(p.name().string(), p.get_string());

    std::vector<float> pixels;
    for (int mip = 0; in->seek_subimage(0, mip); ++mip) {
        const OIIO::ImageSpec spec = in->spec();
        const int nch = spec.nchannels;
        pixels.resize(spec.image_pixels() * nch);
        if (!in->read_image(0, mip, 0, nch, OIIO::TypeDesc::FLOAT, pixels.data()))
            return badInput(path, "level " + std::to_string(mip) + " is damaged: " + detail::firstLine(in->geterror()),
                            "write the file again");
        LevelInfo level;
        level.width = spec.width;
        level.height = spec.height;
        for (int c = 0; c < nch; ++c) {
            ChannelStats stats;
            stats.name = spec.channelnames[c];
            stats.min = std::numeric_limits<double>::infinity();
            stats.max = -stats.min;
            double sum = 0.0;
            for (size_t i = c; i < pixels.size(); i += nch) {
                stats.min = std::min<double>(stats.min, pixels[i]);
                stats.max = std::max<double>(stats.max, pixels[i]);
                sum += pixels[i];
            }
            stats.mean = sum / double(spec.image_pixels());
            level.channels.push_back(stats);
        }
        info.levels.push_back(std::move(level));
    }
    return info;
}

std::string findAttribute(const FileInfo& info, const std::string& name) {
    for (const auto& [key, value] : info.attributes)
        if (key == name) return value;
    return {};
}

}  // namespace heightpack
