#include "headless_context.hpp"

#include <cstring>
#include <utility>

namespace heightpack::view {

namespace {

// Whether the space-separated extension list names extension.
bool listed(const char* list, const char* extension) {
    if (!list) return false;
    const size_t n = std::strlen(extension);
    for (const char* p = std::strstr(list, extension); p; p = std::strstr(p + 1, extension))
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

// Mesa lists llvmpipe as a device too; a real GPU is worth more than the surfaceless fallback.
bool isSoftwareDevice(EGLDeviceEXT device) {
    return listed(eglQueryDeviceStringEXT(device, EGL_EXTENSIONS), "EGL_MESA_device_software");
}

}  // namespace

bool HeadlessContext::tryDisplay(EGLDisplay display, const std::string& platform, std::string& why) {
    if (display == EGL_NO_DISPLAY) {
        why += platform + ": no display; ";
        return false;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        why += platform + ": eglInitialize failed; ";
        return false;
    }
    // No surface at all: the context is made current with none, and draws into framebuffer objects.
    if (!listed(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context") || !eglBindAPI(EGL_OPENGL_API)) {
        why += platform + ": no surfaceless desktop OpenGL; ";
        eglTerminate(display);
        return false;
    }
    const EGLint configAttributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (!eglChooseConfig(display, configAttributes, &config, 1, &configs) || configs < 1) config = nullptr;
    // 4.0 first: Mesa and NVIDIA then give their newest core version. 3.3 is what the viewer needs.
    for (const auto& [want, wantMinor] : {std::pair{4, 0}, std::pair{3, 3}}) {
        const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, want, EGL_CONTEXT_MINOR_VERSION, wantMinor,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        const EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
        if (context == EGL_NO_CONTEXT) continue;
        if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            display_ = display;
            context_ = context;
            platform_ = platform;
            return true;
        }
        eglDestroyContext(display, context);
    }
    why += platform + ": no OpenGL 3.3 core context; ";
    eglTerminate(display);
    return false;
}

bool HeadlessContext::create(std::string& error) {
    if (!epoxy_has_egl()) {
        error = "no EGL library (libEGL.so.1) to draw without a display";
        return false;
    }
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    std::string why;
    if (listed(client, "EGL_EXT_platform_device") && listed(client, "EGL_EXT_device_enumeration")) {
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (!eglQueryDevicesEXT(16, devices, &count)) count = 0;
        for (EGLint d = 0; d < count; ++d) {
            if (isSoftwareDevice(devices[d])) continue;
            if (tryDisplay(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[d], nullptr), "EGL device", why))
                return true;
        }
    }
    if (listed(client, "EGL_MESA_platform_surfaceless") &&
        tryDisplay(eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr), "EGL surfaceless",
                   why))
        return true;
    error = "EGL offers neither a GPU device (EGL_EXT_platform_device) nor Mesa's surfaceless platform" +
            (why.empty() ? std::string() : " (" + why.substr(0, why.size() - 2) + ")");
    return false;
}

HeadlessContext::~HeadlessContext() {
    if (display_ == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    eglTerminate(display_);
}

}  // namespace heightpack::view
