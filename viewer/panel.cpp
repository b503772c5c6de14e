#include "panel.hpp"

#include <imgui.h>

#include <glm/gtc/type_ptr.hpp>

namespace heightpack::view {

void drawPanel(RenderSettings& s, PanelState& state, Camera& camera, const Scene& scene, const PassTimes& times,
               float time) {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(470, 680), ImGuiCond_FirstUseEver);
    ImGui::Begin("heightpack-view (F1 hides)");
    ImGui::PushItemWidth(-190);  // inside Begin: the width belongs to this window's stack
    ImGui::Text("t = %.2f s   water %.2f ms   combine %.2f ms", time, times.water, times.combine);
    ImGui::Text("camera %.1f %.1f %.1f  yaw %.0f pitch %.0f", camera.position.x, camera.position.y, camera.position.z,
                camera.yaw, camera.pitch);
    ImGui::Checkbox("pause", &state.paused);
    ImGui::SameLine();
    ImGui::SliderFloat("speed", &state.timeScale, 0.0f, 4.0f);

    if (ImGui::CollapsingHeader("Height maps (18.2.1)", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (size_t k = 0; k < 2; ++k) {
            ImGui::PushID(static_cast<int>(k));
            if (k < scene.layers.size())
                ImGui::Text("map %zu: %s (%s)", k, scene.layers[k].path.c_str(), scene.layers[k].source.c_str());
            else
                ImGui::TextDisabled("map %zu: none", k);
            LayerSettings& l = s.layers[k];
            ImGui::SliderFloat("tile size (m)", &l.tileSize, 0.5f, 2000.0f, "%.1f", ImGuiSliderFlags_Logarithmic);
            ImGui::SliderFloat2("scroll (tiles/s)", glm::value_ptr(l.scroll), -0.2f, 0.2f);
            ImGui::SliderFloat("wave height (m)", &l.amplitude, 0.0f, 20.0f);
            ImGui::PopID();
        }
        ImGui::SliderFloat("water level (m)", &s.waterLevel, -10.0f, 10.0f);
    }
    if (ImGui::CollapsingHeader("Sampling (18.2.4)", ImGuiTreeNodeFlags_DefaultOpen)) {
        const char* lookups[] = {"packed bilinear", "packed trilinear", "reference bilinear (GL_LINEAR, R32F)",
                                 "reference trilinear (GL_LINEAR, R32F)"};
        int lookup = static_cast<int>(s.lookup);
        if (ImGui::Combo("lookup", &lookup, lookups, 4)) s.lookup = static_cast<Lookup>(lookup);
        ImGui::SliderFloat2("LOD bands", glm::value_ptr(s.bands), 0.0f, 1.0f);
        ImGui::Checkbox("frustum branch", &s.frustumBranch);
        ImGui::SliderFloat2("guard band C0, C1", glm::value_ptr(s.guardBand), 0.5f, 4.0f);
        ImGui::Checkbox("render to texture (two passes)", &s.twoPass);
    }
    if (ImGui::CollapsingHeader("Radial grid (18.2.3)")) {
        ImGui::SliderInt("rings N", &s.rings, 16, 1024);
        ImGui::SliderInt("segments M", &s.segments, 16, 1024);
        ImGui::SliderFloat("r0 (m)", &s.innerRadius, 0.01f, 10.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
        ImGui::SliderFloat("r max (m)", &s.outerRadius, 100.0f, 100000.0f, "%.0f", ImGuiSliderFlags_Logarithmic);
    }
    if (ImGui::CollapsingHeader("Shading")) {
        ImGui::Text("normals: %s", scene.normals ? scene.normals->path.c_str() : "procedural (from the height maps)");
        for (int k = 0; k < 4; ++k) {
            ImGui::PushID(100 + k);
            ImGui::SliderFloat4("octave: tiles/m, scroll u v, strength", glm::value_ptr(s.normalOctaves[k]), -1.0f, 2.0f);
            ImGui::PopID();
        }
        ImGui::Text("Fresnel: %s", scene.fresnel ? scene.fresnel->path.c_str() : "procedural (Schlick, colours below)");
        ImGui::SliderFloat("index of refraction", &s.ior, 1.0f, 2.0f);
        ImGui::ColorEdit3("deep", glm::value_ptr(s.deep));
        ImGui::ColorEdit3("shallow", glm::value_ptr(s.shallow));
        ImGui::SliderFloat3("sun direction", glm::value_ptr(s.sunDirection), -1.0f, 1.0f);
        ImGui::SliderFloat("back-side tilt", &s.tilt, 0.0f, 0.5f);
        ImGui::Text("foam: %s", scene.foam ? "texture" : "procedural");
        ImGui::SliderFloat2("foam H0, Hmax (m)", glm::value_ptr(s.foamRange), -5.0f, 10.0f);
    }
    if (ImGui::CollapsingHeader("Perturbations (18.2.5)")) {
        ImGui::Text("%zu explosions (E or click drops one)", s.explosions.size());
        ImGui::SliderFloat3("k, w, b", glm::value_ptr(s.explosionShape), 0.0f, 10.0f);
        if (ImGui::Button("clear")) s.explosions.clear();
    }
    if (ImGui::CollapsingHeader("Checking aids", ImGuiTreeNodeFlags_DefaultOpen)) {
        const char* views[] = {"shaded", "height as grey", "LOD level as colour"};
        int view = static_cast<int>(s.view);
        if (ImGui::Combo("view", &view, views, 3)) s.view = static_cast<ViewMode>(view);
        ImGui::SliderFloat2("height range (m)", glm::value_ptr(s.heightRange), -20.0f, 20.0f);
        ImGui::Checkbox("wireframe", &s.wireframe);
        ImGui::Checkbox("flat tiled view", &s.tiledView);
        ImGui::SliderInt2("tiles", glm::value_ptr(s.tiles), 1, 8);
        ImGui::Checkbox("seam lines", &s.seamLines);
    }
    ImGui::PopItemWidth();
    ImGui::End();
}

}  // namespace heightpack::view
