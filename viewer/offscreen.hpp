// Drawing without a window on screen, into a framebuffer object: --screenshot and --bench. The same
// code runs in a hidden GLFW window and in a headless EGL context.
#pragma once

#include <string>

#include "app.hpp"

namespace heightpack::view {

// Which context draws: its platform ("GLX window", "EGL surfaceless", "EGL device") and GL version.
struct ContextInfo {
    std::string platform;
    int major = 0, minor = 0;
    bool gather() const { return major >= 4; }  // textureGather is OpenGL 4.0
};
// The current context's version, under the given platform name.
ContextInfo currentContext(const std::string& platform);

// Renders the bench (the lookup asked for, or every lookup the context has with --compare-lookups; GPU
// bytes of the textures) and then the screenshot,
// as the options ask. Returns the process exit code.
int renderOffscreen(ViewerOptions& options, const Scene& scene, Renderer& renderer, const ContextInfo& context);

}  // namespace heightpack::view
