#include "scene.hpp"

#include <algorithm>
#include <cmath>

#include "heightpack/info.hpp"
#include "heightpack/io.hpp"
#include "heightpack/mip.hpp"
#include "heightpack/pack.hpp"

namespace heightpack::view {

namespace {

Image channel(const Image& image, int c) {
    Image out(image.width, image.height, 1);
    for (size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] = image.pixels[i * image.channels + c];
    return out;
}

float attributeFloat(const Attributes& attributes, const char* name, float fallback) {
    const std::string v = findAttribute(attributes, name);
    return v.empty() ? fallback : std::stof(v);
}

double srgbToLinear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

}  // namespace

Result<HeightLayer> loadHeightLayer(const std::string& path) {
    HeightLayer layer;
    layer.path = path;
    auto file = readTextureFile(path, true);
    if (!file) return file.error();
    const std::string layout = findAttribute(file->attributes, "heightpack:layout");
    if (layout == "neighbour4" || layout == "plain") {
        layer.wrap = findAttribute(file->attributes, "heightpack:wrap") == "clamp" ? Wrap::Clamp : Wrap::Periodic;
        const float scale = attributeFloat(file->attributes, "heightpack:heightScale", 1.0f);
        const float offset = attributeFloat(file->attributes, "heightpack:heightOffset", 0.0f);
        layer.midStored = offset + 0.5f * scale;
        for (const Image& level : file->levels) {
            if (layout == "neighbour4") {
                if (level.channels != 4) return badInput(path, "is marked neighbour4 but has no 4 channels", "pack it again");
                layer.packed.push_back(level);
                layer.plain.push_back(channel(level, 0));
            } else {
                layer.plain.push_back(channel(level, 0));
                layer.packed.push_back(packNeighbour4(layer.plain.back(), layer.wrap));
            }
        }
        layer.source = layout == "neighbour4" ? "packed texture" : "plain texture, packed in memory";
    } else {
        // A painted map: the same load, mip and pack as `heightpack pack` (periodic, kaiser).
        LoadOptions load;
        load.silenceDecoderMessages = true;
        auto loaded = loadHeightMap(path, load);
        if (!loaded) return loaded.error();
        Image heights = std::move(loaded->heights);
        MipOptions mip;
        if (!isPowerOfTwo(heights.width) || !isPowerOfTwo(heights.height))
            heights = resample(heights, nextPowerOfTwo(heights.width), nextPowerOfTwo(heights.height), mip);
        layer.plain = generateMipChain(heights, mip);
        layer.packed = packMipChain(layer.plain, layer.wrap);
        layer.source = "painted map, packed in memory";
    }
    const auto [lo, hi] = std::minmax_element(layer.plain[0].pixels.begin(), layer.plain[0].pixels.end());
    layer.minStored = *lo;
    layer.maxStored = *hi;
    return layer;
}

Result<NormalMap> loadNormalMap(const std::string& path) {
    auto file = readTextureFile(path, true);
    if (!file) return file.error();
    NormalMap map;
    map.path = path;
    map.level0 = file->levels[0];
    if (map.level0.channels < 3) return badInput(path, "is not a normal map (fewer than 3 channels)", "make one with heightpack normal");
    // 8/16-bit maps store 0.5 + 0.5 n.
    if (file->pixelType != "float" && file->pixelType != "half")
        for (float& v : map.level0.pixels) v = 2.0f * v - 1.0f;
    const bool directx = findAttribute(file->attributes, "heightpack:convention") == "directx";
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
    ramp.indexScale = findAttribute(file->attributes, "heightpack:index") == "2nv" ? 2.0f : 1.0f;
    return ramp;
}

Result<Scene> loadScene(const SceneFiles& files) {
    Scene scene;
    for (const std::string& path : files.heights) {
        auto layer = loadHeightLayer(path);
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
    for (const auto& p : files.heights) add(p);
    add(files.normals);
    add(files.fresnel);
    add(files.foam);
    return times;
}

}  // namespace heightpack::view
