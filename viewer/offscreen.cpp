#include "offscreen.hpp"

#include <imgui.h>
#include <backends/imgui_impl_opengl3.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "exit_codes.hpp"
#include "heightpack/io/image_write.hpp"
#include "panel.hpp"

namespace heightpack::view {

namespace {

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
    panel.gatherAvailable = renderer.gatherAvailable();
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

// Mean times per frame over `frames` frames drawn with settings, after one frame to warm up. On a terminal
// (and not --json) it shows which lookup and frame it is at: a software renderer takes seconds a frame.
PassTimes benchFrames(const ViewerOptions& o, const RenderSettings& settings, Renderer& renderer, GLuint framebuffer) {
    const float time = o.time.value_or(0.0f);
    const bool progress = !o.json && isatty(STDERR_FILENO);
    auto show = [&](int frame) {
        if (progress) std::fprintf(stderr, "\rbench: lookup %s, frame %d of %d ", nameOf(settings.lookup), frame, o.bench);
    };
    PassTimes total;
    show(0);
    renderer.render(o.camera, settings, time, o.width, o.height, framebuffer, true, true);
    for (int i = 0; i < o.bench; ++i) {
        show(i + 1);
        renderer.render(o.camera, settings, time + i / 60.0f, o.width, o.height, framebuffer, true, true);
        const PassTimes& t = renderer.times();
        total.water += t.water, total.combine += t.combine, total.tiled += t.tiled;
        total.waterWall += t.waterWall, total.combineWall += t.combineWall, total.tiledWall += t.tiledWall;
    }
    if (progress) std::fprintf(stderr, "\r\033[K");
    const double n = o.bench;
    for (double* v : {&total.water, &total.combine, &total.tiled, &total.waterWall, &total.combineWall, &total.tiledWall})
        *v /= n;
    total.vertices = renderer.times().vertices;
    return total;
}

nlohmann::ordered_json bytesJson(const TextureBytes& b) {
    return {{"packed", b.packed}, {"plain", b.plain}, {"gather", b.gather},          {"normals", b.normals},
            {"fresnel", b.fresnel}, {"foam", b.foam}, {"foamCoverage", b.foamCoverage}, {"shift", b.shift},
            {"total", b.total()}};
}

// The samplers the water program's vertex and fragment stages read (Renderer::samplers), each at most 16,
// and what this context allows each stage (GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, GL_MAX_TEXTURE_IMAGE_UNITS).
nlohmann::ordered_json samplersJson(const Renderer& renderer) {
    const StageSamplers& used = renderer.samplers();
    const StageSamplers& limit = renderer.samplerLimits();
    return {{"vertex", used.vertex}, {"fragment", used.fragment}, {"vertexLimit", limit.vertex}, {"fragmentLimit", limit.fragment}};
}

// Each map as drawn: its file, and the tile size, amplitude and choppiness the renderer took for it (the
// flags', else the material's, else what the map records, else the defaults).
nlohmann::ordered_json layersJson(const RenderSettings& s, const Scene& scene) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (size_t k = 0; k < std::min(scene.layers.size(), s.layers.size()); ++k)
        list.push_back({{"map", scene.layers[k].path}, {"tileSize", s.layers[k].tileSize},
                        {"amplitude", s.layers[k].amplitude}, {"choppiness", s.layers[k].choppiness}});
    return list;
}

void printBench(const ViewerOptions& o, const Scene& scene, const Renderer& renderer, const ContextInfo& context,
                const PassTimes& chosen, const std::vector<std::pair<Lookup, PassTimes>>& lookups) {
    const std::string gl = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    const TextureBytes& b = renderer.textureBytes();
    if (o.json) {
        nlohmann::ordered_json j = {{"frames", o.bench},
                                    {"waterMs", chosen.water},
                                    {"combineMs", chosen.combine},
                                    {"tiledMs", chosen.tiled},
                                    {"waterWallMs", chosen.waterWall},
                                    {"combineWallMs", chosen.combineWall},
                                    {"tiledWallMs", chosen.tiledWall},
                                    {"vertices", chosen.vertices},
                                    {"renderer", gl},
                                    {"glVersion", version},
                                    {"context", context.platform},
                                    {"lookup", nameOf(o.settings.lookup)}};
        nlohmann::ordered_json each = nlohmann::ordered_json::object();
        for (const auto& [lookup, t] : lookups)
            each[nameOf(lookup)] = {{"waterMs", t.water}, {"waterWallMs", t.waterWall}, {"combineMs", t.combine},
                                        {"combineWallMs", t.combineWall}};
        j["lookups"] = each;
        j["gpuBytes"] = bytesJson(b);
        j["samplers"] = samplersJson(renderer);
        j["layers"] = layersJson(o.settings, scene);
        std::printf("%s\n", j.dump().c_str());
        return;
    }
    std::printf("%d frames at %dx%d on %s (%s, OpenGL %s), %lld grid vertices, ms per frame (timer query / wall with "
                "glFinish):\n",
                o.bench, o.width, o.height, gl.c_str(), context.platform.c_str(), version.c_str(), chosen.vertices);
    // The passes drawn, and no others.
    if (o.settings.tiledView) {
        std::printf("  tiled view   %8.3f / %8.3f\n", chosen.tiled, chosen.tiledWall);
    } else {
        std::printf("  water pass   %8.3f / %8.3f   (lookup %s)\n", chosen.water, chosen.waterWall, nameOf(o.settings.lookup));
        if (o.settings.twoPass) std::printf("  combine pass %8.3f / %8.3f\n", chosen.combine, chosen.combineWall);
    }
    for (const auto& [lookup, t] : lookups)
        std::printf("  lookup %-20s water %8.3f / %8.3f   combine %8.3f / %8.3f\n", nameOf(lookup), t.water, t.waterWall,
                    t.combine, t.combineWall);
    std::printf("GPU bytes: packed %lld, plain %lld, gather %lld, normals %lld, Fresnel %lld, foam %lld, foam coverage %lld, "
                "Dx and Dy %lld, total %lld\n",
                b.packed, b.plain, b.gather, b.normals, b.fresnel, b.foam, b.foamCoverage, b.shift, b.total());
}

// One two-pass frame, and the combine pass's heights and horizontal shifts with what places them: the
// camera, the grid's radii and the pixel angle, so a reader can put each vertex at its (x, y) and compare
// heights computed elsewhere (tests compare heightpack's CPU sampler with these). Channels Y (height),
// Dx, Dy (the shift of choppy maps, 0 for others): the names a synthesised sea's EXR gives the same things.
int writeGridHeights(const ViewerOptions& o, Renderer& renderer, float time, GLuint framebuffer) {
    renderer.render(o.camera, o.settings, time, o.width, o.height, framebuffer, false);
    Image image(o.settings.segments, o.settings.rings, 3);
    image.pixels = renderer.gridVertices();  // row r is ring r
    const glm::vec2 radius = gridRadius(o.settings);
    auto number = [](const char* name, float value) { return attribute(AttributeKey<float>{name}, value); };
    FlatImageOptions flat;
    flat.bits = 32;
    flat.channelNames = {"Y", layerName::dx, layerName::dy};
    flat.attributes = {attribute(attr::layout, attr::gridHeights), attribute(attr::time, time),
                       number("heightpack:cameraX", o.camera.position.x), number("heightpack:cameraY", o.camera.position.y),
                       number("heightpack:cameraZ", o.camera.position.z),
                       number("heightpack:pixelAngle", pixelAngle(o.camera, o.height)),
                       number("heightpack:gridInnerRadius", radius.x), number("heightpack:gridRingScale", radius.y),
                       number("heightpack:waterLevel", o.settings.waterLevel)};
    if (Status written = writeFlatImage(o.gridHeights, image, flat); !written) return fail(written.error());
    if (!o.json) std::printf("wrote %s: %d segments x %d rings at t = %.2f s\n", o.gridHeights.c_str(), image.width, image.height, time);
    return 0;
}

}  // namespace

ContextInfo currentContext(const std::string& platform) {
    ContextInfo info;
    info.platform = platform;
    glGetIntegerv(GL_MAJOR_VERSION, &info.major);
    glGetIntegerv(GL_MINOR_VERSION, &info.minor);
    return info;
}

int renderOffscreen(ViewerOptions& o, const Scene& scene, Renderer& renderer, const ContextInfo& context) {
    RenderTarget target;
    if (!target.create(o.width, o.height, GL_RGBA8))
        return fail("cannot create a " + std::to_string(o.width) + "x" + std::to_string(o.height) + " render target",
                    "try a smaller --size", ExitCode::NoOpenGL);
    const float time = o.time.value_or(0.0f);
    if (o.bench > 0) {
        const PassTimes chosen = benchFrames(o, o.settings, renderer, target.framebuffer);
        // With --compare-lookups, each lookup on the same frames (the tiled view reads no lookup): the one
        // asked for is measured once.
        std::vector<std::pair<Lookup, PassTimes>> lookups;
        for (const EnumName<Lookup>& each : NameTable<Lookup>::entries) {
            if (!o.compareLookups || o.settings.tiledView) break;
            RenderSettings s = o.settings;
            s.lookup = each.value;
            if (isGather(s.lookup) && !renderer.gatherAvailable()) continue;
            lookups.emplace_back(s.lookup, s.lookup == o.settings.lookup ? chosen : benchFrames(o, s, renderer, target.framebuffer));
        }
        printBench(o, scene, renderer, context, chosen, lookups);
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
        flat.attributes = {attribute(attr::layout, attr::screenshot), attribute(attr::time, time)};
        const Status written = writeFlatImage(o.screenshot, image, flat);
        target.destroy();
        if (!written) return fail(written.error());
        if (o.bench == 0 && o.json) {  // what drew it, and what the textures cost, without a bench's frames
            const nlohmann::ordered_json j = {{"screenshot", o.screenshot},
                                              {"width", o.width},
                                              {"height", o.height},
                                              {"time", time},
                                              {"renderer", reinterpret_cast<const char*>(glGetString(GL_RENDERER))},
                                              {"glVersion", reinterpret_cast<const char*>(glGetString(GL_VERSION))},
                                              {"context", context.platform},
                                              {"lookup", nameOf(o.settings.lookup)},
                                              {"gpuBytes", bytesJson(renderer.textureBytes())},
                                              {"samplers", samplersJson(renderer)},
                                              {"layers", layersJson(o.settings, scene)}};
            std::printf("%s\n", j.dump().c_str());
        } else if (o.bench == 0) {
            std::printf("wrote %s: %dx%d at t = %.2f s\n", o.screenshot.c_str(), o.width, o.height, time);
        }
    }
    target.destroy();
    return 0;
}

}  // namespace heightpack::view
