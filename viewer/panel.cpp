#include "panel.hpp"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <iterator>
#include <string>

#include <glm/gtc/type_ptr.hpp>

namespace heightpack::view {

void drawPanel(RenderSettings& s, PanelState& state, Camera& camera, const Scene& scene, const PassTimes& times,
               float time) {
    // Sized to the window: as tall as its contents, at most the window's height (then it scrolls), and
    // at most half the window's width.
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSizeConstraints(ImVec2(std::min(300.0f, display.x - 20), 0),
                                        ImVec2(std::max(300.0f, display.x * 0.5f), std::max(100.0f, display.y - 20)));
    ImGui::SetNextWindowSize(ImVec2(std::min(500.0f, display.x - 20), 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("heightpack-view (F1 hides)", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::PushItemWidth(-170);  // inside Begin: the width belongs to this window's stack
    if (!state.reloadError.empty())
        ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "not reloaded: %s", state.reloadError.c_str());
    ImGui::Text("t = %.2f s   water %.2f ms   combine %.2f ms", time, times.water, times.combine);
    ImGui::Text("camera %.1f %.1f %.1f  yaw %.0f pitch %.0f", camera.position.x, camera.position.y, camera.position.z,
                camera.yaw, camera.pitch);
    ImGui::Checkbox("pause", &state.paused);
    ImGui::SameLine();
    ImGui::SliderFloat("speed", &state.timeScale, 0.0f, 4.0f);

    if (ImGui::CollapsingHeader("Height maps (18.2.1)", ImGuiTreeNodeFlags_DefaultOpen)) {
        // Every map that displaces the grid (up to kMaxLayers: a cascaded sea's tiles).
        const size_t maps = std::min(scene.layers.size(), s.layers.size());
        for (size_t k = 0; k < maps; ++k) {
            ImGui::PushID(static_cast<int>(k));
            ImGui::Text("map %zu: %s (%s)", k, scene.layers[k].path.c_str(), scene.layers[k].source.c_str());
            LayerSettings& l = s.layers[k];
            ImGui::SliderFloat("tile size (m)", &l.tileSize, 0.5f, 2000.0f, "%.1f", ImGuiSliderFlags_Logarithmic);
            ImGui::SliderFloat2("scroll (tiles/s)", glm::value_ptr(l.scroll), -0.2f, 0.2f);
            ImGui::SliderFloat("wave height (m)", &l.amplitude, 0.0f, 20.0f);
            ImGui::BeginDisabled(!scene.layers[k].horizontal);  // only maps with Dx, Dy move sideways
            ImGui::SliderFloat("choppiness", &l.choppiness, 0.0f, 3.0f);
            ImGui::EndDisabled();
            ImGui::PopID();
        }
        ImGui::SliderFloat("water level (m)", &s.waterLevel, -10.0f, 10.0f);
    }
    if (ImGui::CollapsingHeader("Sampling (18.2.4)", ImGuiTreeNodeFlags_DefaultOpen)) {
        const char* lookups[std::size(NameTable<Lookup>::entries)];
        for (size_t l = 0; l < std::size(lookups); ++l) lookups[l] = NameTable<Lookup>::entries[l].description;
        int lookup = static_cast<int>(s.lookup);
        if (ImGui::Combo("lookup", &lookup, lookups, state.gatherAvailable ? 6 : 4)) s.lookup = static_cast<Lookup>(lookup);
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
        // The octaves in metres: each row edits the tile size (the shader takes its inverse), the scroll
        // in tiles per second and the strength.
        if (ImGui::BeginTable("octaves", 5, ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_SizingStretchProp)) {
            for (const char* label : {"octave", "tile (m)", "scroll u (tiles/s)", "scroll v (tiles/s)", "strength"})
                ImGui::TableSetupColumn(label);
            ImGui::TableHeadersRow();
            for (int k = 0; k < 4; ++k) {
                glm::vec4& octave = s.normalOctaves[k];
                ImGui::PushID(100 + k);
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::Text("%d", k);
                ImGui::TableNextColumn();
                float tile = octave.x != 0.0f ? 1.0f / octave.x : 0.0f;
                ImGui::SetNextItemWidth(-FLT_MIN);
                if (ImGui::DragFloat("##tile", &tile, 0.05f, 0.05f, 1000.0f, "%.2f")) octave.x = 1.0f / std::max(tile, 0.05f);
                ImGui::TableNextColumn();
                ImGui::SetNextItemWidth(-FLT_MIN);
                ImGui::DragFloat("##u", &octave.y, 0.001f, -1.0f, 1.0f, "%.3f");
                ImGui::TableNextColumn();
                ImGui::SetNextItemWidth(-FLT_MIN);
                ImGui::DragFloat("##v", &octave.z, 0.001f, -1.0f, 1.0f, "%.3f");
                ImGui::TableNextColumn();
                ImGui::SetNextItemWidth(-FLT_MIN);
                ImGui::DragFloat("##strength", &octave.w, 0.01f, 0.0f, 2.0f, "%.2f");
                ImGui::PopID();
            }
            ImGui::EndTable();
        }
        ImGui::Text("Fresnel: %s", scene.fresnel ? scene.fresnel->path.c_str() : "procedural (Schlick, colours below)");
        ImGui::SliderFloat("index of refraction", &s.ior, 1.0f, 2.0f);
        // Linear values, as the shader and the manifest take them (not 0-255 of sRGB).
        ImGui::ColorEdit3("deep (linear)", glm::value_ptr(s.deep), ImGuiColorEditFlags_Float);
        ImGui::ColorEdit3("shallow (linear)", glm::value_ptr(s.shallow), ImGuiColorEditFlags_Float);
        ImGui::SliderFloat3("sun direction", glm::value_ptr(s.sunDirection), -1.0f, 1.0f);
        ImGui::SliderFloat("back-side tilt", &s.tilt, 0.0f, 0.5f);
        ImGui::Text("foam: %s", scene.foam ? "texture" : "procedural");
        const bool baked = std::any_of(scene.layers.begin(), scene.layers.end(), [](const HeightLayer& l) { return l.foam; });
        if (baked) ImGui::Checkbox("baked foam coverage (else from H0, Hmax)", &s.bakedFoam);
        ImGui::SliderFloat2("foam H0, Hmax (m)", glm::value_ptr(s.foamRange), -5.0f, 10.0f);
    }
    if (ImGui::CollapsingHeader("Perturbations (18.2.5)")) {
        ImGui::Text("%zu explosions (E or click drops one)", s.explosions.size());
        ImGui::TextWrapped("I(r) = I0 sin(k r + w t) exp(-b t) / r^2, r smoothed within 1 m; w < 0: rings run out");
        ImGui::SliderFloat("k (1/m)", &s.explosionShape.x, 0.0f, 10.0f);
        ImGui::SliderFloat("w (1/s)", &s.explosionShape.y, -20.0f, 20.0f);
        ImGui::SliderFloat("b (1/s)", &s.explosionShape.z, 0.0f, 5.0f);
        if (ImGui::Button("clear")) s.explosions.clear();
    }
    if (ImGui::CollapsingHeader("Checking aids", ImGuiTreeNodeFlags_DefaultOpen)) {
        const char* views[] = {"shaded", "height as grey", "LOD level as colour"};
        int view = static_cast<int>(s.view);
        if (ImGui::Combo("view", &view, views, 3)) s.view = static_cast<ViewMode>(view);
        if (s.view == ViewMode::Lod) {
            // The legend of water.frag's lodColour: a colour per mip level, blended between levels.
            static const ImVec4 palette[6] = {{0.9f, 0.1f, 0.1f, 1}, {0.9f, 0.6f, 0.1f, 1}, {0.8f, 0.9f, 0.1f, 1},
                                              {0.1f, 0.8f, 0.2f, 1}, {0.1f, 0.6f, 0.9f, 1}, {0.5f, 0.2f, 0.9f, 1}};
            ImGui::TextUnformatted("mip level:");
            for (int level = 0; level < 6; ++level) {
                ImGui::SameLine();
                ImGui::ColorButton(("##lod" + std::to_string(level)).c_str(), palette[level],
                                   ImGuiColorEditFlags_NoTooltip | ImGuiColorEditFlags_NoDragDrop, ImVec2(14, 14));
                ImGui::SameLine(0, 3);
                ImGui::Text("%d", level);
            }
            ImGui::TextDisabled("colours repeat every 6 levels; between two, the level is fractional");
        }
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
