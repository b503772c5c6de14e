#include "material_settings.hpp"

#include <algorithm>
#include <filesystem>

#include "heightpack/bake/material.hpp"

namespace heightpack::view {

Status applyMaterial(const std::string& path, SceneFiles& files, RenderSettings& settings, std::string& note) {
    auto material = readMaterial(path);
    if (!material) return material.error();
    const MaterialDescription& m = *material;
    if (m.displacement.empty()) return badInput(path, "lists no height maps", "build the material again");
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    auto resolve = [&](const MaterialTexture& t) { return (folder / t.file).string(); };

    files = SceneFiles{};
    const size_t used = std::min(m.displacement.size(), settings.layers.size());
    for (size_t k = 0; k < used; ++k) {
        const DisplacementLayer& d = m.displacement[k];
        files.heights.push_back(resolve(d.texture));
        settings.layers[k].tileSize = static_cast<float>(d.tileSize);
        settings.layers[k].scroll = {static_cast<float>(d.scroll[0]), static_cast<float>(d.scroll[1])};
        settings.layers[k].amplitude = static_cast<float>(d.amplitude);
        if (d.shift) settings.layers[k].choppiness = static_cast<float>(d.choppiness);
    }
    if (m.displacement.size() > used)
        note = "material " + m.name + " has " + std::to_string(m.displacement.size()) + " height maps; the viewer draws the first " +
               std::to_string(used) + " (heightpack's CPU sampler sums them all)";
    if (m.normals) {
        files.normals = resolve(m.normals->texture);
        for (size_t k = 0; k < settings.normalOctaves.size(); ++k) {
            if (k < m.normals->octaves.size()) {
                const NormalOctave& o = m.normals->octaves[k];
                settings.normalOctaves[k] = glm::vec4(1.0f / static_cast<float>(o.tileSize), static_cast<float>(o.scroll[0]),
                                                      static_cast<float>(o.scroll[1]), static_cast<float>(o.strength));
            } else {
                settings.normalOctaves[k].w = 0.0f;  // an octave the material does not use
            }
        }
    }
    if (m.fresnel) {
        files.fresnel = resolve(m.fresnel->texture);
        settings.ior = static_cast<float>(m.fresnel->ior);
    }
    if (m.foam) {
        if (m.foam->texture) files.foam = resolve(*m.foam->texture);
        settings.foamRange = {static_cast<float>(m.foam->h0), static_cast<float>(m.foam->hmax)};
        settings.foamTileSize = static_cast<float>(m.foam->tileSize);
    }
    return Done{};
}

void applyRecordedUnits(const Scene& scene, RenderSettings& settings) {
    for (size_t k = 0; k < std::min(scene.layers.size(), settings.layers.size()); ++k) {
        const MapUnits& units = scene.layers[k].units;
        if (units.tileWidth) settings.layers[k].tileSize = static_cast<float>(*units.tileWidth);
        if (units.heightRange) settings.layers[k].amplitude = static_cast<float>(*units.heightRange);
    }
}

}  // namespace heightpack::view
