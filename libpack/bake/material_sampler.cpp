// The viewer's scene loader (viewer/scene.cpp) reads the same files for the GPU; the two agree on the
// mid value (the first frame's 1x1 level) and on an untimed sequence's period (four frames a second).
#include "heightpack/bake/material_sampler.hpp"

#include <algorithm>
#include <optional>
#include <filesystem>

#include "heightpack/bake/material.hpp"
#include "heightpack/core/pack.hpp"
#include "heightpack/io/height_sequence.hpp"
#include "heightpack/io/info.hpp"

namespace heightpack {
namespace {

// One frame's packed chains: the heights, and Dx, Dy when the file holds them. A plain chain (and its
// Dx, Dy) is packed in memory as the viewer packs it; foam coverage moves no water, so it is left out.
Result<HeightChains> readFrameChains(const std::string& path, Wrap& wrap, std::optional<double>& loopPeriod, bool first) {
    auto file = readTextureFile(path, true);
    if (!file) return file.error();
    const TextureDescription& texture = file->description;
    if (!texture.isHeights())
        return badInput(path,
                        std::string("is not a packed or plain height chain (its layout: ") +
                            (texture.kind == TextureKind::Image ? "none recorded" : nameOf(texture.kind)) + ")",
                        "point the material at the output of heightpack pack");
    if (first) wrap = texture.wrap;
    loopPeriod = texture.units.loopPeriod;
    HeightChains chains = splitHeightChains(file->levels, texture.channels);
    chains.foam.clear();
    if (texture.layout == Layout::Plain)
        for (std::vector<Image>* chain : {&chains.heights, &chains.dx, &chains.dy})
            for (Image& level : *chain) level = packNeighbour4(level, wrap);
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
        auto readFrame = [&](const std::string& file, size_t index) -> Result<SequenceFrame> {
            SequenceFrame frame;
            auto chains = readFrameChains(file, layer.wrap, frame.loopPeriod, index == 0);
            if (!chains) return chains.error();
            frame.width = chains->heights[0].width;
            frame.height = chains->heights[0].height;
            frame.levels = chains->heights.size();
            frame.shift = !chains->dx.empty();
            layer.frames.push_back(std::move(chains->heights));
            if (frame.shift) {
                layer.shiftX.push_back(std::move(chains->dx));
                layer.shiftY.push_back(std::move(chains->dy));
            }
            return frame;
        };
        auto sequence = readHeightSequence((folder / d.texture.file).string(), readFrame, d.loopPeriod);
        if (!sequence) return sequence.error();
        layer.loopPeriod = sequence->loopPeriod > 0.0 ? sequence->loopPeriod : d.loopPeriod;
        // A map with Dx, Dy is choppy in the viewer: at the material's choppiness, or its own default of 1.
        if (!layer.shiftX.empty()) layer.choppiness = d.shift ? static_cast<float>(d.choppiness) : 1.0f;
        layer.midStored = midStoredOf(layer.frames);
        sampler.layers.push_back(std::move(layer));
    }
    if (sampler.layers.empty()) return badInput(materialPath, "lists no height maps", "build the material again");
    return sampler;
}

}  // namespace heightpack
