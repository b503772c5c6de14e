#include "app.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "exit_codes.hpp"
#include "headless_context.hpp"
#include "material_settings.hpp"
#include "offscreen.hpp"
#include "panel.hpp"
#include "texture_upload.hpp"

namespace heightpack::view {

namespace {

void onGlfwError(int code, const char* description) { std::fprintf(stderr, "heightpack-view: GLFW error %d: %s\n", code, description); }

// Key presses, counted by GLFW's key callback as they happen: a press shorter than a frame still counts
// (polling glfwGetKey once a frame misses it). Held keys (flying) are still polled.
struct KeyPresses {
    int explode = 0, togglePanel = 0;
    bool quit = false;
};

void onKey(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
    if (action != GLFW_PRESS) return;
    auto* presses = static_cast<KeyPresses*>(glfwGetWindowUserPointer(window));
    if (!presses || (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard)) return;
    if (key == GLFW_KEY_E) ++presses->explode;
    if (key == GLFW_KEY_F1) ++presses->togglePanel;
    if (key == GLFW_KEY_ESCAPE) presses->quit = true;
}

// Where the ray through a window pixel meets the water plane, if it does.
bool pickWater(const Camera& camera, double x, double y, int width, int height, float level, glm::vec2& hit) {
    const glm::mat4 inverse = glm::inverse(camera.projection(float(width) / height) * camera.view());
    const glm::vec2 ndc(2.0 * x / width - 1.0, 1.0 - 2.0 * y / height);
    glm::vec4 a = inverse * glm::vec4(ndc, -1.0f, 1.0f), b = inverse * glm::vec4(ndc, 1.0f, 1.0f);
    const glm::vec3 from = glm::vec3(a) / a.w, to = glm::vec3(b) / b.w, dir = to - from;
    if (std::abs(dir.z) < 1e-6f) return false;
    const float t = (level - from.z) / dir.z;
    if (t <= 0.0f) return false;
    hit = glm::vec2(from + dir * t);
    return true;
}

int interactive(GLFWwindow* window, ViewerOptions& o, Scene& scene, Renderer& renderer) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    // No imgui.ini in whatever folder the viewer was started from: the panel sizes itself to the window.
    ImGui::GetIO().IniFilename = nullptr;
    KeyPresses presses;
    glfwSetWindowUserPointer(window, &presses);
    glfwSetKeyCallback(window, onKey);  // before ImGui's backend, which chains to it
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330");
    PanelState panel;
    panel.gatherAvailable = renderer.gatherAvailable();
    float time = o.time.value_or(0.0f);
    auto last = std::chrono::steady_clock::now();
    auto lastCheck = last;
    auto watched = fileTimes(o.files);
    auto materialTime = [&] {
        std::error_code ec;
        return o.material.empty() ? std::filesystem::file_time_type{} : std::filesystem::last_write_time(o.material, ec);
    };
    auto watchedMaterial = materialTime();
    double mouseX = 0, mouseY = 0;
    glfwGetCursorPos(window, &mouseX, &mouseY);
    bool clickWasDown = false;
    for (int frame = 0; !glfwWindowShouldClose(window) && (o.frames == 0 || frame < o.frames); ++frame) {
        glfwPollEvents();
        const auto now = std::chrono::steady_clock::now();
        const float dt = std::chrono::duration<float>(now - last).count();
        last = now;
        if (!panel.paused) time += dt * panel.timeScale;

        // Reload what changed on disk: an artist saves, the water changes.
        if (now - lastCheck > std::chrono::milliseconds(500)) {
            lastCheck = now;
            // A rebuilt material: its textures, and its parameters (material.json changes only when
            // the build changed something in it).
            const auto materialNow = materialTime();
            if (materialNow != watchedMaterial) {
                watchedMaterial = materialNow;
                std::string note;
                if (Status s = applyMaterial(o.material, o.files, o.settings, note); !s) {
                    panel.reloadError = s.error().path + ": " + s.error().what;
                    std::fprintf(stderr, "heightpack-view: not reloaded: %s\n", panel.reloadError.c_str());
                } else
                    watched.clear();  // load the scene again below, whatever the textures' times say
            }
            const auto current = fileTimes(o.files);
            if (current != watched) {
                watched = current;
                auto reloaded = loadScene(o.files);
                if (reloaded) {
                    scene = std::move(*reloaded);
                    panel.reloadError = renderer.upload(scene);
                    if (panel.reloadError.empty())
                        std::fprintf(stderr, "heightpack-view: reloaded\n");
                    else
                        std::fprintf(stderr, "heightpack-view: not reloaded: %s\n", panel.reloadError.c_str());
                } else {
                    panel.reloadError = reloaded.error().path + ": " + reloaded.error().what;
                    std::fprintf(stderr, "heightpack-view: not reloaded: %s\n", panel.reloadError.c_str());
                }
            }
        }

        const ImGuiIO& io = ImGui::GetIO();
        double x = 0, y = 0;
        glfwGetCursorPos(window, &x, &y);
        int width = 0, height = 0;
        glfwGetFramebufferSize(window, &width, &height);
        if (!io.WantCaptureKeyboard) {
            auto key = [&](int k) { return glfwGetKey(window, k) == GLFW_PRESS ? 1.0f : 0.0f; };
            o.camera.fly({key(GLFW_KEY_W) - key(GLFW_KEY_S), key(GLFW_KEY_D) - key(GLFW_KEY_A),
                          key(GLFW_KEY_SPACE) - key(GLFW_KEY_LEFT_CONTROL)},
                         dt);
        }
        if (presses.togglePanel % 2) panel.showPanel = !panel.showPanel;
        presses.togglePanel = 0;
        if (presses.quit) glfwSetWindowShouldClose(window, 1);
        if (!io.WantCaptureMouse && glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS)
            o.camera.look(float(x - mouseX), float(y - mouseY));
        const bool click = !io.WantCaptureMouse && glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        const int explosions = presses.explode + (click && !clickWasDown ? 1 : 0);
        presses.explode = 0;
        clickWasDown = click;
        glm::vec2 hit;
        if (explosions > 0 && height > 0 && pickWater(o.camera, x, y, width, height, o.settings.waterLevel, hit)) {
            if (o.settings.explosions.size() >= 8) o.settings.explosions.erase(o.settings.explosions.begin());
            o.settings.explosions.push_back({hit, time, 40.0f});
        }
        mouseX = x;
        mouseY = y;

        if (width > 0 && height > 0) renderer.render(o.camera, o.settings, time, width, height, 0, true);
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        if (panel.showPanel) drawPanel(o.settings, panel, o.camera, scene, renderer.times(), time);
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        glfwSwapBuffers(window);
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwSetWindowUserPointer(window, nullptr);
    return 0;
}

// Builds the renderer in the current context and runs what the options ask; window is null headless.
// A gather lookup the context cannot draw falls back to the packed lookup of the same kind.
int draw(ViewerOptions& o, Scene& scene, const ContextInfo& context, GLFWwindow* window) {
    Renderer renderer;
    std::string error;
    if (!renderer.init(error, context.gather()))
        return fail("shader build failed: " + error, "please report this with the GL_RENDERER string", ExitCode::Internal);
    if (const std::string astc = astcPath(scene); !astc.empty() && !contextTakesAstc())
        return fail(astc + ": holds ASTC blocks and this " + context.platform + " context offers no "
                    "GL_KHR_texture_compression_astc_ldr",
                    "write it with heightpack as bc4 (heights) or bc5 (normals), or view it where the driver has ASTC",
                    ExitCode::NoOpenGL);
    if (const std::string hdr = astcHdrPath(scene); !hdr.empty() && !contextTakesAstcHdr())
        return fail(hdr + ": holds ASTC HDR blocks and this " + context.platform + " context offers no "
                    "GL_KHR_texture_compression_astc_hdr",
                    "write it with heightpack as astc-4x4/6x6/8x8 (LDR) or bc4, or view it where the driver has ASTC HDR",
                    ExitCode::NoOpenGL);
    if (const std::string problem = renderer.upload(scene); !problem.empty())
        return fail(problem, "use a sequence of fewer frames", ExitCode::BadInput);
    if (isGather(o.settings.lookup) && !renderer.gatherAvailable()) {
        const std::string why = context.gather() ? renderer.gatherProblem()
                                                 : "textureGather needs OpenGL 4.0 and this " + context.platform +
                                                       " context is " + std::to_string(context.major) + "." +
                                                       std::to_string(context.minor);
        std::fprintf(stderr, "heightpack-view: note: --lookup %s: %s; drawing with the packed lookup instead\n",
                     nameOf(o.settings.lookup), why.c_str());
        o.settings.lookup = o.settings.lookup == Lookup::GatherBilinear ? Lookup::PackedBilinear : Lookup::PackedTrilinear;
    }
    const bool offscreen = !o.screenshot.empty() || !o.gridHeights.empty() || o.bench > 0;
    return offscreen || !window ? renderOffscreen(o, scene, renderer, context) : interactive(window, o, scene, renderer);
}

// The window's context: 4.0 core first (textureGather; GLX then gives its newest), 3.3 core else.
GLFWwindow* createWindow(const ViewerOptions& o, bool offscreen) {
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, offscreen ? GLFW_FALSE : GLFW_TRUE);
    for (const auto& [major, minor] : {std::pair{4, 0}, std::pair{3, 3}}) {
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, major);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, minor);
        // A refused 4.0 is no error to report: 3.3 is tried next, and its failure is.
        glfwSetErrorCallback(major == 4 ? nullptr : onGlfwError);
        GLFWwindow* window = glfwCreateWindow(offscreen ? 64 : o.width, offscreen ? 64 : o.height, "heightpack-view",
                                              nullptr, nullptr);
        if (window) {
            glfwSetErrorCallback(onGlfwError);
            return window;
        }
    }
    return nullptr;
}

}  // namespace

int runViewer(ViewerOptions& o, Scene& scene) {
    const bool offscreen = !o.screenshot.empty() || !o.gridHeights.empty() || o.bench > 0;
    if (o.headless) {
        HeadlessContext context;
        std::string error;
        if (!context.create(error))
            return fail("cannot draw without a display: " + error,
                        "install Mesa's EGL, libegl-mesa0, or a GPU driver; or run under xvfb-run without --headless",
                        ExitCode::NoOpenGL);
        return draw(o, scene, currentContext(context.platform()), nullptr);
    }
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit()) return fail("cannot start GLFW", "is there a display? run headless under xvfb-run", ExitCode::NoOpenGL);
    GLFWwindow* window = createWindow(o, offscreen);
    if (!window) {
        glfwTerminate();
        return fail("cannot create an OpenGL 3.3 core context", "is there a display? run headless under xvfb-run",
                    ExitCode::NoOpenGL);
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(1);
    const int code = draw(o, scene, currentContext("GLX window"), window);
    glfwDestroyWindow(window);
    glfwTerminate();
    return code;
}

}  // namespace heightpack::view
