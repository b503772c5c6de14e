#include "scene.hpp"

#include <algorithm>
#include <cmath>

#include "heightpack/build/pack_job.hpp"
#include "heightpack/io/info.hpp"
#include "heightpack/io/read.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/core/pack.hpp"

namespace heightpack::view {

namespace {

Image channel(const Image& image, int c) {
    Image out(image.width, image.height, 1);
    for (size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] = image.pixels[i * image.channels + c];
    return out;
}


double srgbToLinear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

}  // namespace

namespace {

// One file's chain into frame; fills the layer's wrap, mid value and timing from the first file.
Status loadFrame(const std::string& path, const std::string& channelChoice, HeightLayer& layer, HeightFrame& frame,
                 bool first) {
    auto file = readTextureFile(path, true);
    if (!file) return file.error();
    const std::string layout = findAttribute(file->attributes, attr::layout);
    if (first) {
        const std::string period = findAttribute(file->attributes, attr::loopPeriod);
        layer.loopPeriod = period.empty() ? 0.0 : std::stod(period);
    }
    if (layout == "neighbour4" || layout == "plain") {
        if (first) {
            layer.wrap = findAttribute(file->attributes, attr::wrap).value_or(Wrap::Periodic);
            layer.source = layout == "neighbour4" ? "packed texture" : "plain texture, packed in memory";
        }
        for (const Image& level : file->levels) {
            if (layout == "neighbour4") {
                if (level.channels != 4) return badInput(path, "is marked neighbour4 but has no 4 channels", "pack it again");
                frame.packed.push_back(level);
                frame.plain.push_back(channel(level, 0));
            } else {
                frame.plain.push_back(channel(level, 0));
                frame.packed.push_back(packNeighbour4(frame.plain.back(), layer.wrap));
            }
        }
        return Done{};
    }
    // A painted map: the same load, mip and pack as `heightpack pack` (periodic, kaiser).
    LoadOptions load;
    load.silenceDecoderMessages = true;
    if (const auto select = parseChannelSelect(channelChoice)) {
        load.channel = *select;
    } else if (!channelChoice.empty()) {
        load.channel = ChannelSelect::Named;
        load.channelName = channelChoice;
    }
    auto loaded = loadHeightMap(path, load);
    if (!loaded) return loaded.error();
    PackOptions pack;
    pack.resizeToPowerOfTwo = true;  // a viewer shows any size; pack would ask for --resize pow2
    pack.mip.wrap = layer.wrap;      // periodic, unless the sequence's first frame said otherwise
    auto maps = packHeights(std::move(loaded->heights), loaded->source, pack);
    if (!maps) return maps.error();
    frame.plain = std::move(maps->plain);
    frame.packed = std::move(maps->packed);
    if (first) layer.source = "painted map, packed in memory";
    return Done{};
}

}  // namespace

Result<HeightLayer> loadHeightLayer(const std::string& path, const std::string& channel) {
    HeightLayer layer;
    layer.path = path;
    const std::vector<std::string> files = expandSequence(path);
    for (size_t f = 0; f < files.size(); ++f) {
        HeightFrame frame;
        if (Status s = loadFrame(files[f], channel, layer, frame, f == 0); !s) return s.error();
        if (f > 0 && (frame.packed.size() != layer.frames[0].packed.size() ||
                      frame.packed[0].width != layer.frames[0].packed[0].width ||
                      frame.packed[0].height != layer.frames[0].packed[0].height))
            return badInput(files[f], "differs in size from the sequence's first frame", "make every frame the same size");
        layer.frames.push_back(std::move(frame));
    }
    if (files.size() > 1) {
        layer.source += ", " + std::to_string(files.size()) + " frames";
        if (layer.loopPeriod <= 0.0) layer.loopPeriod = files.size() / 4.0;  // untimed: 4 frames a second
    }
    float lo = layer.frames[0].plain[0].pixels[0], hi = lo;
    for (const HeightFrame& frame : layer.frames) {
        const auto [a, b] = std::minmax_element(frame.plain[0].pixels.begin(), frame.plain[0].pixels.end());
        lo = std::min(lo, *a);
        hi = std::max(hi, *b);
    }
    layer.minStored = lo;
    layer.maxStored = hi;
    // Waves move about the map's mean: the 1x1 level of the first frame, whatever the map's units.
    layer.midStored = layer.frames[0].plain.back().pixels[0];
    return layer;
}

Result<NormalMap> loadNormalMap(const std::string& path) {
    auto file = readTextureFile(path, true);
    if (!file) return file.error();
    NormalMap map;
    map.path = path;
    // Each level of an EXR from heightpack normal holds the normals of that level's heights, better than
    // averaged normals: keep them all.
    map.levels = std::move(file->levels);
    if (map.levels[0].channels < 3) return badInput(path, "is not a normal map (fewer than 3 channels)", "make one with heightpack normal");
    // 8/16-bit maps store 0.5 + 0.5 n.
    if (file->pixelType != "float" && file->pixelType != "half")
        for (Image& level : map.levels)
            for (float& v : level.pixels) v = 2.0f * v - 1.0f;
    const bool directx = findAttribute(file->attributes, attr::convention) == NormalConvention::DirectX;
    map.greenSign = directx ? 1.0f : -1.0f;
    return map;
}

Result<FresnelRamp> loadFresnelRamp(const std::string& path) {
    auto file = readTextureFile(path, true);
    if (!file) return file.error();
    FresnelRamp ramp;
    ramp.path = path;
    ramp.ramp = file->levels[0];
    if (ramp.ramp.channels != 4) return badInput(path, "is not a Fresnel ramp (needs RGBA)", "make one with heightpack fresnel");
    if (file->pixelType != "float" && file->pixelType != "half")  // a PNG ramp's colours are sRGB-encoded
        for (size_t i = 0; i < ramp.ramp.pixels.size(); ++i)
            if (i % 4 != 3) ramp.ramp.pixels[i] = static_cast<float>(srgbToLinear(ramp.ramp.pixels[i]));
    ramp.indexScale = findAttribute(file->attributes, attr::index) == FresnelIndex::TwoNdotV ? 2.0f : 1.0f;
    return ramp;
}

Result<Scene> loadScene(const SceneFiles& files) {
    Scene scene;
    for (const std::string& path : files.heights) {
        auto layer = loadHeightLayer(path, files.channel);
        if (!layer) return layer.error();
        scene.layers.push_back(std::move(*layer));
    }
    if (!files.normals.empty()) {
        auto n = loadNormalMap(files.normals);
        if (!n) return n.error();
        scene.normals = std::move(*n);
    }
    if (!files.fresnel.empty()) {
        auto f = loadFresnelRamp(files.fresnel);
        if (!f) return f.error();
        scene.fresnel = std::move(*f);
    }
    if (!files.foam.empty()) {
        LoadOptions load;
        load.silenceDecoderMessages = true;
        auto foam = loadHeightMap(files.foam, load);
        if (!foam) return foam.error();
        scene.foam = std::move(foam->heights);
    }
    return scene;
}

std::vector<std::filesystem::file_time_type> fileTimes(const SceneFiles& files) {
    std::vector<std::filesystem::file_time_type> times;
    auto add = [&](const std::string& path) {
        std::error_code ec;
        times.push_back(path.empty() ? std::filesystem::file_time_type{} : std::filesystem::last_write_time(path, ec));
    };
    for (const auto& p : files.heights)
        for (const auto& frame : expandSequence(p)) add(frame);
    add(files.normals);
    add(files.fresnel);
    add(files.foam);
    return times;
}

}  // namespace heightpack::view
