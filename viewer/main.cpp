// heightpack-view: loads what the tools wrote (or a painted map, packed in memory) and renders it on the
// chapter 18 radial grid. Everything is loaded before a window opens, so bad input never shows one.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "app.hpp"
#include "command_line.hpp"
#include "exit_codes.hpp"
#include "material_settings.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/image_write.hpp"

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

// Parses, loads and draws; every documented failure returns its code here.
int view(int argc, char** argv) {
    using namespace heightpack::view;
    CommandLineValues values;
    CLI::App app;
    defineCommandLine(app, values);
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        return fail(e.what(), "see 'heightpack-view --help'", ExitCode::Usage);
    }
    ViewerOptions& o = values.options;
    const std::string &size = values.size, &camera = values.camera, &tiled = values.tiled, &explosion = values.explosion,
                      &view = values.view, &tileSizes = values.tileSizes, &amplitudes = values.amplitudes,
                      &choppiness = values.choppiness;
    std::string& lookup = values.lookup;
    const bool frustumOff = values.frustumOff, noBakedFoam = values.noBakedFoam, headless = values.headless;
    const float time = values.time;
    auto usage = [](const std::string& what) { return fail(what, "see 'heightpack-view --help'", ExitCode::Usage); };
    if (std::sscanf(size.c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 16 || o.height < 16 ||
        o.width > 8192 || o.height > 8192)
        return usage("--size must be WxH between 16 and 8192, e.g. 1280x720");
    if (!o.screenshot.empty()) {
        const std::string ext = heightpack::lowerExtension(o.screenshot);
        const auto& formats = heightpack::kFlatImageExtensions;
        if (std::find(formats.begin(), formats.end(), ext) == formats.end())
            return fail(o.screenshot + ": is no screenshot format: the viewer writes " + screenshotFormats(),
                        "name it " + std::filesystem::path(o.screenshot).replace_extension(".png").string() +
                            ", or see 'heightpack-view --help'",
                        ExitCode::Usage);
    }
    // The folder heightpack build wrote: its material.json.
    for (std::string& map : o.files.heights) {
        std::error_code ec;
        if (!std::filesystem::is_directory(map, ec)) continue;
        const std::string inside = (std::filesystem::path(map) / "material.json").string();
        if (!std::filesystem::is_regular_file(inside, ec))
            return fail(map + ": is a folder, not a map, and holds no material.json",
                        "name a map, or the folder heightpack build wrote", ExitCode::BadInput);
        if (o.files.heights.size() > 1)
            return usage(map + " is a built material's folder: open its material.json alone, without other maps");
        std::fprintf(stderr, "heightpack-view: note: %s is a folder; opening its %s\n", map.c_str(), inside.c_str());
        map = inside;
    }
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
    // One number per map, in the maps' order; a single choppiness is every map's. Applied once the maps
    // are loaded, over what they record.
    const size_t most = size_t(kMaxLayers);
    std::vector<float> tileSizeFlags, amplitudeFlags, choppinessFlags;
    if (!tileSizes.empty() && (!parseFloats(tileSizes, tileSizeFlags) || tileSizeFlags.size() > most ||
                               std::any_of(tileSizeFlags.begin(), tileSizeFlags.end(), [](float x) { return x <= 0; })))
        return usage("--tile-size must be one to four positive lengths in metres, e.g. 64,16");
    if (!amplitudes.empty() && (!parseFloats(amplitudes, amplitudeFlags) || amplitudeFlags.size() > most))
        return usage("--amplitude must be one to four numbers, e.g. 1.5,0.4");
    if (!choppiness.empty() && (!parseFloats(choppiness, choppinessFlags) || choppinessFlags.size() > most ||
                                std::any_of(choppinessFlags.begin(), choppinessFlags.end(), [](float x) { return x < 0 || x > 10; })))
        return usage("--choppiness must be one to four numbers from 0 to 10, e.g. 1 or 1,0.5");
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
    // The names were checked when parsed (lookupChoices, allNames<ViewMode>).
    o.settings.lookup = lookup == kGatherAlias ? Lookup::GatherTrilinear : heightpack::parseName<Lookup>(lookup).value();
    o.settings.view = heightpack::parseName<ViewMode>(view).value();
    o.settings.frustumBranch = !frustumOff;
    o.settings.bakedFoam = !noBakedFoam;
    if (!o.gridHeights.empty()) {
        if (std::filesystem::path(o.gridHeights).extension() != ".exr") return usage("--grid-heights must name an .exr file");
        o.settings.twoPass = true;          // the heights come from the combine pass
        o.settings.frustumBranch = false;   // and every vertex gets one, seen or not
    }

    auto scene = loadScene(o.files);
    if (!scene) return fail(scene.error());
    // Each map's size and metres: the flags, else the material's, else what the map records, else the defaults.
    if (!material) applyRecordedUnits(*scene, o.settings);
    for (size_t k = 0; k < tileSizeFlags.size(); ++k) o.settings.layers[k].tileSize = tileSizeFlags[k];
    for (size_t k = 0; k < amplitudeFlags.size(); ++k) o.settings.layers[k].amplitude = amplitudeFlags[k];
    for (size_t k = 0; k < o.settings.layers.size() && !choppinessFlags.empty(); ++k)
        o.settings.layers[k].choppiness = choppinessFlags[std::min(k, choppinessFlags.size() - 1)];
    return runViewer(o, *scene);
}

}  // namespace

// What escapes (an exception from a library underneath, an allocation that fails) is a bug: one line and
// exit 70, as the command line does, never an abort with a core dump.
int main(int argc, char** argv) {
    using heightpack::view::ExitCode;
    try {
        return view(argc, argv);
    } catch (const std::exception& e) {
        return heightpack::view::fail(std::string("internal error: ") + e.what(), "please report this", ExitCode::Internal);
    } catch (...) {
        return heightpack::view::fail("internal error: an unknown exception", "please report this", ExitCode::Internal);
    }
}
