// The ImGui panel: every parameter the seeds name, grouped as the chapter presents them.
#pragma once

#include <string>

#include "camera.hpp"
#include "renderer.hpp"
#include "scene.hpp"

namespace heightpack::view {

struct PanelState {
    float timeScale = 1.0f;
    bool paused = false;
    bool showPanel = true;
    std::string reloadError;  // why the last reload failed; empty once one succeeds
    bool gatherAvailable = false;  // the context and the maps allow the gather lookup (Renderer::gatherAvailable)
};

void drawPanel(RenderSettings& settings, PanelState& state, Camera& camera, const Scene& scene, const PassTimes& times,
               float time);

}  // namespace heightpack::view
