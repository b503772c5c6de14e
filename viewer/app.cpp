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
#include "heightpack/io/image_write.hpp"
#include "material_settings.hpp"
#include "panel.hpp"

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

// Draws the panel over what the bound framebuffer holds, for a screenshot: the same panel an artist sees.
void drawPanelOffscreen(ViewerOptions& o, const Scene& scene, const Renderer& renderer, float time) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(float(o.width), float(o.height));
    io.DeltaTime = 1.0f / 60.0f;
    ImGui_ImplOpenGL3_Init("#version 330");
    PanelState panel;
    for (int pass = 0; pass < 2; ++pass) {  // the first frame sizes the auto-resizing window
        ImGui_ImplOpenGL3_NewFrame();
        ImGui::NewFrame();
        drawPanel(o.settings, panel, o.camera, scene, renderer.times(), time);
        ImGui::Render();
    }
    glViewport(0, 0, o.width, o.height);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    ImGui_ImplOpenGL3_Shutdown();
    ImGui::DestroyContext();
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

// One two-pass frame, and the combine pass's heights with what places them: the camera, the grid's radii
// and the pixel angle, so a reader can put each vertex at its (x, y) and compare heights computed
// elsewhere (tests compare heightpack's CPU sampler with these).
int writeGridHeights(const ViewerOptions& o, Renderer& renderer, float time, GLuint framebuffer) {
    renderer.render(o.camera, o.settings, time, o.width, o.height, framebuffer, false);
    Image image(o.settings.segments, o.settings.rings, 1);
    image.pixels = renderer.gridHeights();  // row r is ring r
    const glm::vec2 radius = gridRadius(o.settings);
    auto number = [](const char* name, float value) { return attribute(AttributeKey<float>{name}, value); };
    FlatImageOptions flat;
    flat.bits = 32;
    flat.attributes = {attribute(attr::layout, "grid heights"), attribute(attr::time, time),
                       number("heightpack:cameraX", o.camera.position.x), number("heightpack:cameraY", o.camera.position.y),
                       number("heightpack:cameraZ", o.camera.position.z),
                       number("heightpack:pixelAngle", pixelAngle(o.camera, o.height)),
                       number("heightpack:gridInnerRadius", radius.x), number("heightpack:gridRingScale", radius.y),
                       number("heightpack:waterLevel", o.settings.waterLevel)};
    if (Status written = writeFlatImage(o.gridHeights, image, flat); !written) return fail(written.error());
    if (!o.json) std::printf("wrote %s: %d segments x %d rings at t = %.2f s\n", o.gridHeights.c_str(), image.width, image.height, time);
    return 0;
}

int renderOffscreen(ViewerOptions& o, const Scene& scene, Renderer& renderer) {
    RenderTarget target;
    if (!target.create(o.width, o.height, GL_RGBA8)) return fail("cannot create a " + std::to_string(o.width) + "x" +
                                                                     std::to_string(o.height) + " render target", "try a smaller --size",
                                                                 ExitCode::NoOpenGL);
    const float time = o.time.value_or(0.0f);
    if (o.bench > 0) {
        PassTimes total;
        renderer.render(o.camera, o.settings, time, o.width, o.height, target.framebuffer, true, true);  // warm up
        for (int i = 0; i < o.bench; ++i) {
            renderer.render(o.camera, o.settings, time + i / 60.0f, o.width, o.height, target.framebuffer, true, true);
            const PassTimes& t = renderer.times();
            total.water += t.water, total.combine += t.combine, total.tiled += t.tiled;
            total.waterWall += t.waterWall, total.combineWall += t.combineWall, total.tiledWall += t.tiledWall;
        }
        const double n = o.bench;
        const long long vertices = renderer.times().vertices;
        const char* gl = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        if (o.json)
            std::printf("{\"frames\": %d, \"waterMs\": %.4f, \"combineMs\": %.4f, \"tiledMs\": %.4f, "
                        "\"waterWallMs\": %.4f, \"combineWallMs\": %.4f, \"tiledWallMs\": %.4f, \"vertices\": %lld, "
                        "\"renderer\": \"%s\"}\n",
                        o.bench, total.water / n, total.combine / n, total.tiled / n, total.waterWall / n,
                        total.combineWall / n, total.tiledWall / n, vertices, gl);
        else
            std::printf("%d frames at %dx%d on %s, %lld grid vertices, ms per frame (timer query / wall with glFinish):\n"
                        "  water pass   %8.3f / %8.3f\n  combine pass %8.3f / %8.3f\n  tiled view   %8.3f / %8.3f\n",
                        o.bench, o.width, o.height, gl, vertices, total.water / n, total.waterWall / n,
                        total.combine / n, total.combineWall / n, total.tiled / n, total.tiledWall / n);
    }
    if (!o.gridHeights.empty()) {
        if (int code = writeGridHeights(o, renderer, time, target.framebuffer); code != 0) {
            target.destroy();
            return code;
        }
    }
    if (!o.screenshot.empty()) {
        renderer.render(o.camera, o.settings, time, o.width, o.height, target.framebuffer, false);
        if (o.panelInScreenshot) {
            glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
            drawPanelOffscreen(o, scene, renderer, time);
        }
        const std::vector<unsigned char> rgb = target.readRgb();
        Image image(o.width, o.height, 3);
        for (size_t i = 0; i < rgb.size(); ++i) image.pixels[i] = rgb[i] / 255.0f;
        FlatImageOptions flat;
        flat.bits = 8;
        flat.attributes = {attribute(attr::layout, "screenshot"), attribute(attr::time, time)};
        const Status written = writeFlatImage(o.screenshot, image, flat);
        target.destroy();
        if (!written)
            return fail(written.error());
        if (!o.json && o.bench == 0) std::printf("wrote %s: %dx%d at t = %.2f s\n", o.screenshot.c_str(), o.width, o.height, time);
    }
    target.destroy();
    return 0;
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
                    renderer.upload(scene);
                    panel.reloadError.clear();
                    std::fprintf(stderr, "heightpack-view: reloaded\n");
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

}  // namespace

int runViewer(ViewerOptions& o, Scene& scene) {
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit()) return fail("cannot start GLFW", "is there a display? run headless under xvfb-run", ExitCode::NoOpenGL);
    const bool offscreen = !o.screenshot.empty() || !o.gridHeights.empty() || o.bench > 0;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, offscreen ? GLFW_FALSE : GLFW_TRUE);
    GLFWwindow* window = glfwCreateWindow(offscreen ? 64 : o.width, offscreen ? 64 : o.height, "heightpack-view", nullptr, nullptr);
    if (!window) {
        glfwTerminate();
        return fail("cannot create an OpenGL 3.3 core context", "is there a display? run headless under xvfb-run",
                    ExitCode::NoOpenGL);
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(1);
    int code = 0;
    {
        Renderer renderer;
        std::string error;
        if (!renderer.init(error)) {
            code = fail("shader build failed: " + error, "please report this with the GL_RENDERER string",
                        ExitCode::Internal);
        } else {
            renderer.upload(scene);
            code = offscreen ? renderOffscreen(o, scene, renderer) : interactive(window, o, scene, renderer);
        }
    }
    glfwDestroyWindow(window);
    glfwTerminate();
    return code;
}

}  // namespace heightpack::view
