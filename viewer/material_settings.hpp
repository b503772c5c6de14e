// Where the renderer's parameters come from besides the command line: a built material (material.json
// from `heightpack build` names the textures and carries each map's tile size, scroll and amplitude, the
// normal-map octaves, the Fresnel and foam settings), or the maps themselves (their tile size and metres).
#pragma once

#include <string>

#include "renderer.hpp"
#include "scene.hpp"

namespace heightpack::view {

// Fills files and settings from the material.json at path (texture paths resolved against its folder).
// note gets a line for the user when the material holds more than the renderer uses.
Status applyMaterial(const std::string& path, SceneFiles& files, RenderSettings& settings, std::string& note);

// Sets each map's tile size and amplitude to what its file records (HeightLayer::units), where it does:
// the defaults of maps opened without a material.json.
void applyRecordedUnits(const Scene& scene, RenderSettings& settings);

}  // namespace heightpack::view
