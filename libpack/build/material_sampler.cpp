// The viewer's scene loader (viewer/scene.cpp) reads the same files for the GPU; the two agree on the
// mid value (the first frame's 1x1 level) and on an untimed sequence's period (four frames a second).
#include "heightpack/build/material_sampler.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "heightpack/build/material.hpp"
#include "heightpack/core/pack.hpp"
#include "heightpack/io/attributes.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/info.hpp"

namespace heightpack {
namespace {

Image firstChannel(const Image& image) {
    Image out(image.width, image.height, 1);
    for (size_t i = 0; i < image.texelCount(); ++i) out.pixels[i] = image.pixels[i * image.channels];
    return out;
}

// One frame's packed chain; the first frame also settles the layer's wrap and loop period.
Result<std::vector<Image>> readPackedChain(const std::string& path, SampledLayer& layer, bool first) {
    auto file = readTextureFile(path, true);
    if (!file) return file.error();
    const std::string layout = findAttribute(file->attributes, attr::layout);
    if (layout != "neighbour4" && layout != "plain")
        return badInput(path, "is not a packed or plain height chain (layout '" + layout + "')",
                        "point the material at the output of heightpack pack");
    if (first) {
        layer.wrap = findAttribute(file->attributes, attr::wrap).value_or(Wrap::Periodic);
        const std::string period = findAttribute(file->attributes, attr::loopPeriod);
        if (!period.empty()) {
            char* end = nullptr;
            const double seconds = std::strtod(period.c_str(), &end);
            if (*end != '\0' || !std::isfinite(seconds) || seconds < 0)
                return badInput(path, "has a damaged loop period '" + period + "'", "synthesise or pack it again");
            layer.loopPeriod = seconds;
        }
    }
    std::vector<Image> chain;
    for (const Image& level : file->levels) {
        if (layout == "plain") {
            chain.push_back(packNeighbour4(firstChannel(level), layer.wrap));
        } else if (level.channels != 4) {
            return badInput(path, "is marked neighbour4 but has " + std::to_string(level.channels) + " channels",
                            "pack it again");
        } else {
            chain.push_back(level);
        }
    }
    if (chain.empty()) return badInput(path, "holds no levels", "pack it again");
    return chain;
}

}  // namespace

Result<WaterSampler> loadMaterialSampler(const std::string& materialPath) {
    auto material = readMaterial(materialPath);
    if (!material) return material.error();
    const std::filesystem::path folder = std::filesystem::path(materialPath).parent_path();
    WaterSampler sampler;
    for (const DisplacementLayer& d : material->displacement) {
        SampledLayer layer;
        layer.tileSize = static_cast<float>(d.tileSize);
        layer.scroll = {static_cast<float>(d.scroll[0]), static_cast<float>(d.scroll[1])};
        layer.amplitude = static_cast<float>(d.amplitude);
        layer.loopPeriod = d.loopPeriod;
        const std::vector<std::string> files = expandSequence((folder / d.texture.file).string());
        for (size_t f = 0; f < files.size(); ++f) {
            auto chain = readPackedChain(files[f], layer, f == 0);
            if (!chain) return chain.error();
            if (f > 0 && (chain->size() != layer.frames[0].size() || (*chain)[0].width != layer.frames[0][0].width ||
                          (*chain)[0].height != layer.frames[0][0].height))
                return badInput(files[f], "differs in size from the sequence's first frame", "make every frame the same size");
            layer.frames.push_back(std::move(*chain));
        }
        if (layer.frames.size() > 1 && !(layer.loopPeriod > 0.0)) layer.loopPeriod = layer.frames.size() / 4.0;
        layer.midStored = midStoredOf(layer.frames);
        sampler.layers.push_back(std::move(layer));
    }
    if (sampler.layers.empty()) return badInput(materialPath, "lists no height maps", "build the material again");
    return sampler;
}

}  // namespace heightpack
