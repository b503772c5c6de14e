// An OpenGL context without any window system, for --screenshot and --bench on a server: EGL on a GPU
// through the device platform (EGL_EXT_platform_device: NVIDIA's driver, Mesa's GPU drivers), else
// Mesa's surfaceless platform (EGL_MESA_platform_surfaceless: its GPU driver, or llvmpipe on the CPU).
// There is no default framebuffer: everything draws into framebuffer objects.
#pragma once

#include <epoxy/egl.h>

#include <string>

namespace heightpack::view {

class HeadlessContext {
public:
    // Makes a core context current: 4.x where the platform offers it (textureGather), else 3.3. Returns
    // false with the reason in error (each platform tried, and why it did not do) when none can be made.
    bool create(std::string& error);
    // "EGL device" or "EGL surfaceless", for messages and --bench.
    const std::string& platform() const { return platform_; }
    ~HeadlessContext();

private:
    bool tryDisplay(EGLDisplay display, const std::string& platform, std::string& why);
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
    std::string platform_;
};

}  // namespace heightpack::view
