// The viewer application: a window (visible, or hidden for --screenshot and --bench) or a headless EGL
// context, the frame loop, input, the panel, and reloading inputs when they change on disk.
#pragma once

#include <optional>
#include <string>

#include "camera.hpp"
#include "renderer.hpp"
#include "scene.hpp"

namespace heightpack::view {

struct ViewerOptions {
    SceneFiles files;
    std::string material;         // the material.json the files and settings came from, if any
    std::string screenshot;       // render one frame offscreen to this PNG and exit
    std::string gridHeights;      // render one frame two-pass and write the grid's heights and shifts to this EXR
    int width = 1280, height = 720;
    std::optional<float> time;    // fixed animation clock
    int bench = 0;                // render this many frames offscreen, print GPU time per pass, exit
    bool compareLookups = false;  // --bench: time every other lookup the context has too, on the same frames
    int frames = 0;               // interactive: close the window after this many frames (0: when the user does)
    bool json = false;
    bool panelInScreenshot = false;  // draw the ImGui panel into the screenshot too
    bool headless = false;        // no window system: EGL (headless_context.hpp), --screenshot, --grid-heights and --bench only
    Camera camera;
    RenderSettings settings;
};

// Runs the viewer on a loaded scene. Returns the process exit code.
int runViewer(ViewerOptions& options, Scene& scene);

}  // namespace heightpack::view
