// heightpack-view: loads what the tools wrote (or a painted map, packed in memory) and renders it on the
// chapter 18 radial grid. Everything is loaded before a window opens, so bad input never shows one.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "app.hpp"
#include "exit_codes.hpp"
#include "material_settings.hpp"
#include "heightpack/version.hpp"

namespace {

bool parseFloats(const std::string& text, std::vector<float>& out) {
    out.clear();
    const char* p = text.c_str();
    while (*p) {
        char* end = nullptr;
        const float v = std::strtof(p, &end);
        if (end == p || !std::isfinite(v)) return false;
        out.push_back(v);
        p = end;
        if (*p == ',') ++p;
        else if (*p) return false;
    }
    return !out.empty();
}

}  // namespace

int main(int argc, char** argv) {
    using namespace heightpack::view;
    ViewerOptions o;
    std::string size = "1280x720", camera, tiled, explosion, lookup = "trilinear", view = "shaded", tileSizes, amplitudes,
                choppiness;
    bool frustumOff = false;
    float time = -1.0f;
    CLI::App app{"heightpack-view: water height maps on the GPU Gems 2 chapter 18 radial-grid renderer"};
    app.set_version_flag("--version", std::string("heightpack-view ") + heightpack::kVersion);
    app.add_option("maps", o.files.heights,
                   "height maps (packed or plain .exr, .ktx2 or .dds from heightpack pack, or painted images), or one "
                   "material.json from heightpack build")
        ->required();
    app.add_option("--normals", o.files.normals, "normal map from heightpack normal (else derived from the heights)");
    app.add_option("--fresnel", o.files.fresnel, "Fresnel ramp from heightpack fresnel (else Schlick and fixed colours)");
    app.add_option("--foam", o.files.foam, "foam texture, grey (else procedural)");
    bool noBakedFoam = false;
    app.add_flag("--no-baked-foam", noBakedFoam,
                 "ignore the foam coverage of maps that carry it (pack --foam): foam from the height threshold, as "
                 "for maps without it");
    app.add_option("--channel", o.files.channel,
                   "where the height is in a painted colour map: r, g, b, a, luma, or a channel's name (height.Y, Z)");
    app.add_option("--explosion", explosion, "drop an explosion at x,y (metres) at t = 0 [,start time s [,strength I0]]");
    app.add_flag("--panel", o.panelInScreenshot, "draw the panel into --screenshot too");
    app.add_option("--tiled", tiled, "flat view of the first map tiled NxM, to look for seams (e.g. 3x3)");
    app.add_flag("--seams", o.settings.seamLines, "draw the tile lines in the tiled view");
    app.add_option("--screenshot", o.screenshot, "render one frame offscreen to this PNG and exit (works under xvfb-run)");
    app.add_option("--grid-heights", o.gridHeights,
                   "render one frame two-pass, every grid vertex sampled, and write the vertices' heights (Y) and "
                   "horizontal shifts (Dx, Dy) to this EXR (x = segment, y = ring; camera and grid in its header) and exit");
    bool headless = false;
    app.add_flag("--headless", headless,
                 "draw --screenshot, --grid-heights or --bench with no display at all, through EGL (a GPU, or "
                 "Mesa's surfaceless platform); the default when DISPLAY is unset");
    app.add_option("--size", size, "window or screenshot size WxH")->capture_default_str();
    app.add_option("--time", time, "fix the animation clock at this many seconds");
    app.add_option("--camera", camera, "x,y,z,yaw,pitch (metres, degrees; z up)");
    app.add_option("--bench", o.bench,
                   "render N frames offscreen, print GPU time per pass drawn (timer queries), exit; on Mesa's "
                   "software renderer a 1280x720 frame takes about a second");
    app.add_flag("--compare-lookups", o.compareLookups,
                 "with --bench: time every other --lookup the context has too, on the same frames (each its own "
                 "shaders: a minute or more on a software renderer)");
    app.add_option("--lookup", lookup,
                   "height lookup in the vertex shader; gather (= gather-trilinear) uses textureGather, OpenGL 4.0")
        ->capture_default_str()
        ->check(CLI::IsMember({"bilinear", "trilinear", "reference-bilinear", "reference-trilinear", "gather",
                               "gather-bilinear", "gather-trilinear"}));
    app.add_option("--view", view, "shaded, height (grey), lod (colour per level)")
        ->capture_default_str()
        ->check(CLI::IsMember({"shaded", "height", "lod"}));
    app.add_flag("--two-pass", o.settings.twoPass, "combine the maps into an fp32 texture first (render-to-texture)");
    app.add_flag("--no-frustum-branch", frustumOff, "sample every vertex, even outside the guard-banded frustum");
    app.add_flag("--wireframe", o.settings.wireframe, "draw the grid as lines");
    app.add_option("--tile-size", tileSizes, "metres each map's tile spans, in the maps' order (up to 4), e.g. 64,16");
    app.add_option("--amplitude", amplitudes, "metres per stored unit for each map (up to 4), e.g. 1.5,0.4");
    app.add_option("--choppiness", choppiness,
                   "how far the Dx, Dy of each map that has them move the grid sideways (0: heights only), e.g. 1 "
                   "or 1,0.5 (up to 4); default the material's, else 1");
    app.add_option("--grid", o.settings.rings, "rings N of the radial grid (segments M follow --segments)");
    app.add_option("--segments", o.settings.segments, "segments M of the radial grid");
    app.add_flag("--json", o.json,
                 "print --bench figures as JSON (each pass's time, GPU bytes of the textures); with --screenshot "
                 "alone, what drew it and the GPU bytes");
    app.add_option("--frames", o.frames, "close the interactive window after N frames (smoke tests, recordings)")
        ->check(CLI::Range(1, 1000000000));
    app.footer(
        "Examples:\n"
        "  heightpack-view out/ocean/material.json\n"
        "  heightpack-view out/swell.exr out/choppy.exr --normals out/ripple_n.exr --fresnel out/fresnel.exr\n"
        "  heightpack-view out/swell.exr --tiled 3x3\n"
        "  heightpack-view out/swell.exr --screenshot shot.png --size 1280x720 --time 12.5 --camera 0,0,8,30,-10\n"
        "  heightpack-view out/swell.exr --bench 300 --headless --compare-lookups\n"
        "  heightpack-view out/swell_half.ktx2 --lookup gather --headless --screenshot shot.png\n"
        "  heightpack-view sea_packed.exr --choppiness 1.2      # a map packed with --displacement\n"
        "  heightpack-view sea_packed.exr                       # packed with --foam: its foam where synth put it\n"
        "Keys: WASD fly, Space/Ctrl up/down, right mouse look, E or left click drops an explosion, F1 panel, Esc quits.\n"
        "Exit codes:\n"
        "  0   done\n"
        "  2   usage error\n"
        "  3   bad input: a map, sequence frame, normal map, Fresnel ramp, foam texture or material.json\n"
        "  4   cannot write the screenshot or the grid heights\n"
        "  5   no usable OpenGL: no display, no OpenGL 3.3 core context (window or EGL), no render target of\n"
        "      that --size (run it under xvfb-run, or --headless with Mesa's EGL)\n"
        "  70  internal: a shader that does not build, or a bug\n");
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        return fail(e.what(), "see 'heightpack-view --help'", ExitCode::Usage);
    }
    auto usage = [](const std::string& what) { return fail(what, "see 'heightpack-view --help'", ExitCode::Usage); };
    if (std::sscanf(size.c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 16 || o.height < 16 ||
        o.width > 8192 || o.height > 8192)
        return usage("--size must be WxH between 16 and 8192, e.g. 1280x720");
    // A built material sets the files and parameters; options given as well override it.
    const bool material = o.files.heights.size() == 1 && std::filesystem::path(o.files.heights[0]).extension() == ".json";
    if (material) {
        if (!o.files.normals.empty() || !o.files.fresnel.empty() || !o.files.foam.empty())
            return usage("a material.json names its own textures; leave out --normals, --fresnel and --foam");
        std::string note;
        const std::string path = o.files.heights[0];  // a copy: applyMaterial replaces o.files
        if (heightpack::Status s = applyMaterial(path, o.files, o.settings, note); !s) return fail(s.error());
        if (!note.empty()) std::fprintf(stderr, "heightpack-view: note: %s\n", note.c_str());
        o.material = path;
    } else if (o.files.heights.size() > size_t(kMaxLayers)) {
        return usage("at most " + std::to_string(kMaxLayers) + " height maps displace the grid; " +
                     std::to_string(o.files.heights.size()) + " were given");
    }
    std::vector<float> v;
    if (!camera.empty()) {
        if (!parseFloats(camera, v) || v.size() != 5) return usage("--camera must be x,y,z,yaw,pitch");
        o.camera.position = {v[0], v[1], v[2]};
        o.camera.yaw = v[3];
        o.camera.pitch = v[4];
    }
    if (!tiled.empty()) {
        if (std::sscanf(tiled.c_str(), "%dx%d", &o.settings.tiles.x, &o.settings.tiles.y) != 2 || o.settings.tiles.x < 1 ||
            o.settings.tiles.y < 1 || o.settings.tiles.x > 64 || o.settings.tiles.y > 64)
            return usage("--tiled must be NxM, e.g. 3x3");
        o.settings.tiledView = true;
    }
    // One number per map, in the maps' order; a single choppiness is every map's.
    const size_t most = size_t(kMaxLayers);
    if (!tileSizes.empty()) {
        if (!parseFloats(tileSizes, v) || v.size() > most || std::any_of(v.begin(), v.end(), [](float x) { return x <= 0; }))
            return usage("--tile-size must be one to four positive lengths in metres, e.g. 64,16");
        for (size_t k = 0; k < v.size(); ++k) o.settings.layers[k].tileSize = v[k];
    }
    if (!amplitudes.empty()) {
        if (!parseFloats(amplitudes, v) || v.size() > most) return usage("--amplitude must be one to four numbers, e.g. 1.5,0.4");
        for (size_t k = 0; k < v.size(); ++k) o.settings.layers[k].amplitude = v[k];
    }
    if (!choppiness.empty()) {
        if (!parseFloats(choppiness, v) || v.size() > most || std::any_of(v.begin(), v.end(), [](float x) { return x < 0 || x > 10; }))
            return usage("--choppiness must be one to four numbers from 0 to 10, e.g. 1 or 1,0.5");
        for (size_t k = 0; k < o.settings.layers.size(); ++k) o.settings.layers[k].choppiness = v[std::min(k, v.size() - 1)];
    }
    if (o.settings.rings < 2 || o.settings.segments < 3 || o.settings.rings > 4096 || o.settings.segments > 4096)
        return usage("--grid and --segments must be 2..4096 and 3..4096");
    if (o.bench < 0) return usage("--bench takes a number of frames");
    if (o.compareLookups && o.bench == 0) return usage("--compare-lookups goes with --bench N");
    const bool offscreen = !o.screenshot.empty() || !o.gridHeights.empty() || o.bench > 0;
    if (headless && !offscreen)
        return usage("--headless draws only --screenshot, --grid-heights or --bench: there is no window to show");
    // No X display: a screenshot or a bench still draws, through EGL.
    const char* display = std::getenv("DISPLAY");
    o.headless = headless || (offscreen && (!display || !*display));
    if (!explosion.empty()) {
        if (!parseFloats(explosion, v) || v.size() < 2 || v.size() > 4)
            return usage("--explosion must be x,y or x,y,start or x,y,start,strength");
        o.settings.explosions.push_back({{v[0], v[1]}, v.size() > 2 ? v[2] : 0.0f, v.size() > 3 ? v[3] : 40.0f});
    }
    if (time >= 0) o.time = time;
    if (lookup == "gather") lookup = "gather-trilinear";  // trilinear, as the packed lookup's default
    for (int l = 0; l < 6; ++l)
        if (lookup == lookupName(static_cast<Lookup>(l))) o.settings.lookup = static_cast<Lookup>(l);
    o.settings.view = view == "height" ? ViewMode::Height : view == "lod" ? ViewMode::Lod : ViewMode::Shaded;
    o.settings.frustumBranch = !frustumOff;
    o.settings.bakedFoam = !noBakedFoam;
    if (!o.gridHeights.empty()) {
        if (std::filesystem::path(o.gridHeights).extension() != ".exr") return usage("--grid-heights must name an .exr file");
        o.settings.twoPass = true;          // the heights come from the combine pass
        o.settings.frustumBranch = false;   // and every vertex gets one, seen or not
    }

    auto scene = loadScene(o.files);
    if (!scene) return fail(scene.error());
    return runViewer(o, *scene);
}
