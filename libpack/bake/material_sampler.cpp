// The viewer's scene loader (viewer/scene.cpp) reads the same files for the GPU; the two agree on the
// mid value (the first frame's 1x1 level) and on an untimed sequence's period (four frames a second).
#include "heightpack/bake/material_sampler.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "heightpack/bake/material.hpp"
#include "heightpack/core/pack.hpp"
#include "heightpack/io/attributes.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/info.hpp"

namespace heightpack {
namespace {

// One frame's packed chains: the heights, and Dx, Dy when the file holds them (heightpack:displacement).
struct FrameChains {
    std::vector<Image> heights, shiftX, shiftY;
};

// The channel indices of names in file, or -1 for the first missing one.
std::vector<int> channelIndices(const TextureFile& file, const std::vector<std::string>& names) {
    std::vector<int> out;
    for (const std::string& n : names) {
        const auto it = std::find(file.channelNames.begin(), file.channelNames.end(), n);
        out.push_back(it == file.channelNames.end() ? -1 : static_cast<int>(it - file.channelNames.begin()));
    }
    return out;
}

// One frame's chains; the first frame also settles the layer's wrap and loop period. A plain chain (and
// its Dx, Dy) is packed in memory as the viewer packs it.
Result<FrameChains> readFrameChains(const std::string& path, SampledLayer& layer, bool first) {
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
    const bool packed = layout == "neighbour4";
    const bool displaced = !findAttribute(file->attributes, attr::displacement).empty();
    // Foam coverage (pack --foam) rides in layer Foam: it moves no water, so the sampler skips it.
    const bool foam = !findAttribute(file->attributes, attr::foam).empty();
    // Without companions the heights are the file's first four (packed) or first (plain) channels, as
    // ever; with them, the channels named as pack --displacement and --foam name them.
    std::vector<int> heights = packed ? std::vector<int>{0, 1, 2, 3} : std::vector<int>{0}, dx, dy;
    if (displaced || foam)
        heights = channelIndices(*file, packed ? std::vector<std::string>{"R", "G", "B", "A"} : std::vector<std::string>{"Y"});
    if (std::find(heights.begin(), heights.end(), -1) != heights.end())
        return badInput(path, "records its companions but lacks a height channel", "pack it again");
    if (displaced) {
        dx = channelIndices(*file, packed ? std::vector<std::string>{"Dx.R", "Dx.G", "Dx.B", "Dx.A"} : std::vector<std::string>{"Dx"});
        dy = channelIndices(*file, packed ? std::vector<std::string>{"Dy.R", "Dy.G", "Dy.B", "Dy.A"} : std::vector<std::string>{"Dy"});
        for (const auto* list : {&dx, &dy})
            if (std::find(list->begin(), list->end(), -1) != list->end())
                return badInput(path, "records a displacement but lacks one of its channels", "pack it again");
    }
    FrameChains chains;
    for (const Image& level : file->levels) {
        if (packed && !displaced && !foam && level.channels != 4)
            return badInput(path, "is marked neighbour4 but has " + std::to_string(level.channels) + " channels",
                            "pack it again");
        auto packedOf = [&](const std::vector<int>& channels) {
            return packed ? selectChannels(level, channels) : packNeighbour4(selectChannels(level, channels), layer.wrap);
        };
        chains.heights.push_back(packedOf(heights));
        if (displaced) {
            chains.shiftX.push_back(packedOf(dx));
            chains.shiftY.push_back(packedOf(dy));
        }
    }
    if (chains.heights.empty()) return badInput(path, "holds no levels", "pack it again");
    return chains;
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
            auto chains = readFrameChains(files[f], layer, f == 0);
            if (!chains) return chains.error();
            const std::vector<Image>& chain = chains->heights;
            if (f > 0 && (chain.size() != layer.frames[0].size() || chain[0].width != layer.frames[0][0].width ||
                          chain[0].height != layer.frames[0][0].height))
                return badInput(files[f], "differs in size from the sequence's first frame", "make every frame the same size");
            if (f > 0 && chains->shiftX.empty() != layer.shiftX.empty())
                return badInput(files[f], "differs from the sequence's first frame in holding Dx, Dy",
                                "make every frame with the displacement, or none");
            layer.frames.push_back(std::move(chains->heights));
            if (!chains->shiftX.empty()) {
                layer.shiftX.push_back(std::move(chains->shiftX));
                layer.shiftY.push_back(std::move(chains->shiftY));
            }
        }
        // A map with Dx, Dy is choppy in the viewer: at the material's choppiness, or its own default of 1.
        if (!layer.shiftX.empty()) layer.choppiness = d.horizontalDisplacement ? static_cast<float>(d.choppiness) : 1.0f;
        if (layer.frames.size() > 1 && !(layer.loopPeriod > 0.0)) layer.loopPeriod = layer.frames.size() / 4.0;
        layer.midStored = midStoredOf(layer.frames);
        sampler.layers.push_back(std::move(layer));
    }
    if (sampler.layers.empty()) return badInput(materialPath, "lists no height maps", "build the material again");
    return sampler;
}

}  // namespace heightpack
