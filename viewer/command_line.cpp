#include "command_line.hpp"

#include <cstdio>

#include "exit_codes.hpp"
#include "heightpack/io/image_write.hpp"
#include "heightpack/version.hpp"

namespace heightpack::view {

namespace {

// One field of every map's defaults, "64,16,4,1", for --help.
std::string defaultsOf(float LayerSettings::*field) {
    std::string text;
    for (const auto& layer : RenderSettings{}.layers) {
        char number[32];
        std::snprintf(number, sizeof number, "%s%g", text.empty() ? "" : ",", double(layer.*field));
        text += number;
    }
    return text;
}

}  // namespace

std::vector<std::string> lookupChoices() {
    std::vector<std::string> names = allNames<Lookup>();
    names.insert(names.end() - 2, kGatherAlias);  // before the two it stands beside
    return names;
}

std::string screenshotFormats() {
    std::string text;
    const auto& formats = heightpack::kFlatImageExtensions;
    for (size_t i = 0; i < formats.size(); ++i)
        text += std::string(i == 0 ? "" : i + 1 == formats.size() ? " or " : ", ") + formats[i];
    return text;
}

std::string exitCodesFooter() {
    std::string text = "Exit codes:\n";
    for (const ExitCodeMeaning& e : kExitCodeMeanings) {
        char code[16];
        std::snprintf(code, sizeof code, "  %-4d", static_cast<int>(e.code));
        std::string line = code;
        const std::string meaning = e.meaning;
        for (size_t from = 0; from < meaning.size();) {
            size_t end = meaning.find(' ', from);
            if (end == std::string::npos) end = meaning.size();
            const std::string word = meaning.substr(from, end - from);
            if (line.size() + 1 + word.size() > 100 && line.size() > 6) {
                text += line + "\n";
                line = "      ";
            } else if (line.size() > 6) {
                line += " ";
            }
            line += word;
            from = end + 1;
        }
        text += line + "\n";
    }
    return text;
}

void defineCommandLine(CLI::App& app, CommandLineValues& values) {
    ViewerOptions& o = values.options;
    std::string &size = values.size, &camera = values.camera, &tiled = values.tiled, &explosion = values.explosion,
                &lookup = values.lookup, &view = values.view, &tileSizes = values.tileSizes, &amplitudes = values.amplitudes,
                &choppiness = values.choppiness;
    bool &frustumOff = values.frustumOff, &noBakedFoam = values.noBakedFoam, &headless = values.headless;
    float& time = values.time;
    app.description("heightpack-view: water height maps on the GPU Gems 2 chapter 18 radial-grid renderer");
    app.set_version_flag("--version", std::string("heightpack-view ") + kVersion);
    app.add_option("maps", o.files.heights,
                   "height maps (packed or plain .exr, .ktx2 or .dds from heightpack pack, or painted images), or one "
                   "material.json from heightpack build, or the folder holding it")
        ->required();
    app.add_option("--normals", o.files.normals, "normal map from heightpack normal (else derived from the heights)");
    app.add_option("--fresnel", o.files.fresnel, "Fresnel ramp from heightpack fresnel (else Schlick and fixed colours)");
    app.add_option("--foam", o.files.foam, "foam texture, grey (else procedural)");
    app.add_flag("--no-baked-foam", noBakedFoam,
                 "ignore the foam coverage of maps that carry it (pack --foam): foam from the height threshold, as "
                 "for maps without it");
    app.add_option("--channel", o.files.channel,
                   "where the height is in a painted colour map: r, g, b, a, luma, or a channel's name (height.Y, Z)");
    app.add_option("--explosion", explosion, "drop an explosion at x,y (metres) at t = 0 [,start time s [,strength I0]]");
    app.add_flag("--panel", o.panelInScreenshot, "draw the panel into --screenshot too");
    app.add_option("--tiled", tiled, "flat view of the first map tiled NxM, to look for seams (e.g. 3x3); the tiles keep the map's shape");
    app.add_flag("--seams", o.settings.seamLines, "draw the tile lines in the tiled view");
    app.add_option("--screenshot", o.screenshot,
                   "render one frame offscreen to this file and exit (works under xvfb-run, or --headless): " +
                       screenshotFormats());
    app.add_option("--grid-heights", o.gridHeights,
                   "render one frame two-pass, every grid vertex sampled, and write the vertices' heights (Y) and "
                   "horizontal shifts (Dx, Dy) to this EXR (x = segment, y = ring; camera and grid in its header) and exit");
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
        ->check(CLI::IsMember(lookupChoices()));
    app.add_option("--view", view, "shaded, height (grey), lod (colour per level)")
        ->capture_default_str()
        ->check(CLI::IsMember(allNames<ViewMode>()));
    app.add_flag("--two-pass", o.settings.twoPass, "combine the maps into an fp32 texture first (render-to-texture)");
    app.add_flag("--no-frustum-branch", frustumOff, "sample every vertex, even outside the guard-banded frustum");
    app.add_flag("--wireframe", o.settings.wireframe, "draw the grid as lines");
    app.add_option("--tile-size", tileSizes,
                   "metres each map's tile spans, in the maps' order (up to 4), e.g. 64,16; default: what the map "
                   "records (synth and pack write it), else " + defaultsOf(&LayerSettings::tileSize) +
                       "; a material.json's own");
    app.add_option("--amplitude", amplitudes,
                   "metres per stored unit for each map (up to 4), e.g. 1.5,0.4; default: the map's own metres (a "
                   "synthesised sea, or a map packed from one or with --height), else " +
                       defaultsOf(&LayerSettings::amplitude) + "; a material.json's own");
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
        "  heightpack-view out/ocean/material.json             # or out/ocean, the folder heightpack build wrote\n"
        "  heightpack-view out/swell.exr out/choppy.exr --normals out/ripple_n.exr --fresnel out/fresnel.exr\n"
        "  heightpack-view out/swell.exr --tiled 3x3\n"
        "  heightpack-view out/swell.exr --screenshot shot.png --size 1280x720 --time 12.5 --camera 0,0,8,30,-10\n"
        "  heightpack-view out/swell.exr --bench 300 --headless --compare-lookups\n"
        "  heightpack-view out/swell_half.ktx2 --lookup gather --headless --screenshot shot.png\n"
        "  heightpack-view sea_packed.exr --choppiness 1.2      # a map packed with --shift     \n"
        "  heightpack-view sea_packed.exr                       # packed with --foam: its foam where synth put it\n"
        "Keys: WASD fly, Space/Ctrl up/down, right mouse look, E or left click drops an explosion, F1 panel, Esc quits.\n" +
        exitCodesFooter());
}

}  // namespace heightpack::view
