// Opening a built material: material.json (from `heightpack build`) names the textures and carries the
// parameters the renderer needs: each map's tile size, scroll and amplitude, the normal-map octaves,
// the Fresnel and foam settings.
#pragma once

#include <string>

#include "renderer.hpp"
#include "scene.hpp"

namespace heightpack::view {

// Fills files and settings from the material.json at path (texture paths resolved against its folder).
// note gets a line for the user when the material holds more than the renderer uses.
Status applyMaterial(const std::string& path, SceneFiles& files, RenderSettings& settings, std::string& note);

}  // namespace heightpack::view
