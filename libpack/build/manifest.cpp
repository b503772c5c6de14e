#include "heightpack/build/manifest.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "heightpack/build/synth_job.hpp"
#include "heightpack/core/cascades.hpp"
#include "heightpack/core/tileable.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/read.hpp"

#include "manifest_section.hpp"
#include "manifest_synth.hpp"

namespace heightpack {

namespace fs = std::filesystem;

namespace {

using detail::Section;
using detail::shorten;

// The same limits as the command line's --tile-size and --height: a tile up to 100 km across, waves up
// to 1 km high. Anything larger is a typo, and would overflow float maths downstream.
constexpr double kMaxTileSize = 1e5;
constexpr double kMaxHeight = 1e3;
// Height maps in a material, a synthesised sea's cascades each counted.
constexpr size_t kMaxDisplacementMaps = 8;

bool validName(const std::string& name) {
    if (name.empty() || name.size() > 64) return false;
    return std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
    }) && name.front() != '.';
}

class ManifestParser {
public:
    explicit ManifestParser(std::string path) : path_(std::move(path)), folder_(fs::path(path_).parent_path()) {}

    Manifest parse(const toml::table& root) {
        Section top(root, "", path_);
        Manifest m;
        m.path = path_;
        const double format = top.number("format", std::nullopt, 1, 1e9);
        if (format != kManifestFormat)
            throw top.error("format", "is " + Section::formatNumber(format) + ", but this heightpack reads format " +
                                          std::to_string(kManifestFormat));
        m.name = top.requiredText("name");
        if (!validName(m.name)) throw top.error("name", "must be 1-64 letters, digits, '_', '-' or '.'");
        m.threshold = top.number("threshold", kDefaultSeamThreshold, 1.0, 1e6);
        if (const toml::table* d = top.table("defaults")) {
            Section s(*d, "defaults", path_);
            defaults_ = settings(s, MapSettings{});
            defaultsMustTile_ = s.boolean("tileable");
            s.finish();
        }

        const toml::array* array = top.require("displacement").as_array();
        if (!array || !array->is_array_of_tables() || array->empty())
            throw top.error("displacement", "must be one or more [[displacement]] tables");
        if (array->size() > kMaxDisplacementMaps)
            throw top.error("displacement", "has " + std::to_string(array->size()) + " maps; at most " +
                                                std::to_string(kMaxDisplacementMaps));
        for (size_t i = 0; i < array->size(); ++i) {
            Section s(*(*array)[i].as_table(), "displacement[" + std::to_string(i) + "]", path_);
            mapsBefore_ = m.displacement.size();
            for (DisplacementAsset& d : displacement(s)) m.displacement.push_back(std::move(d));
            if (m.displacement.size() > kMaxDisplacementMaps)  // the cascades of a sea above it fill the material
                throw s.error(s.line(), "[" + s.prefix() + "] is displacement map " + std::to_string(m.displacement.size()) +
                                            ", counting each cascade of a synthesised sea; at most " +
                                            std::to_string(kMaxDisplacementMaps),
                              "use fewer cascades, or fewer [[displacement]] maps");
        }
        if (const toml::table* t = top.table("normals")) {
            Section s(*t, "normals", path_);
            m.normals = normals(s);
        }
        if (const toml::table* t = top.table("fresnel")) {
            Section s(*t, "fresnel", path_);
            m.fresnel = fresnel(s);
        }
        if (const toml::table* t = top.table("foam")) {
            Section s(*t, "foam", path_);
            m.foam = foam(s);
        }
        top.finish();
        return m;
    }

private:
    MapSettings settings(Section& s, const MapSettings& base) {
        MapSettings out = base;
        out.wrap = s.choice("wrap", base.wrap);
        out.filter = s.choice("filter", base.filter);
        out.compression = s.choice("compression", base.compression);
        out.resize = s.boolean("resize").value_or(base.resize);
        if (const auto c = s.text("channel")) {
            const auto parsed = parseName<ChannelSelect>(*c);
            if (!parsed) throw s.error("channel", "is '" + shorten(*c) + "', but must be one of: " + joinedNames<ChannelSelect>());
            out.channel = *parsed;
        }
        if (s.find("container")) out.container = s.choice("container", Container::Exr);
        pixelType(s, out, true);
        return out;
    }

    // pixel_type (float, half, uint16, or auto with tolerance) into out, over what out holds already
    // (the defaults). A table that names a type of its own drops an inherited tolerance.
    void pixelType(Section& s, MapSettings& out, bool autoAllowed) {
        const std::string choices = joinedNames<PixelType>() + (autoAllowed ? ", auto" : "");
        if (const auto type = s.text("pixel_type")) {
            if (*type == "auto" && autoAllowed) {
                if (!s.find("tolerance"))
                    throw s.error("pixel_type", "is \"auto\", which needs a tolerance",
                                  "add tolerance = the worst lookup error allowed, in stored units (normal units "
                                  "for normals), such as 0.0005");
                out.tolerance = s.number("tolerance", std::nullopt, 0.0, 1e6, true);
                return;
            }
            const auto parsed = parseName<PixelType>(*type);
            if (!parsed) throw s.error("pixel_type", "is '" + shorten(*type) + "', but must be one of: " + choices);
            out.pixelType = *parsed;
            out.tolerance = 0.0;
        }
        if (s.find("tolerance")) {
            if (!(out.tolerance > 0.0))  // neither here nor in [defaults] is the type "auto"
                throw s.error("tolerance", "is given, but pixel_type is not \"auto\"",
                              "set pixel_type = \"auto\" beside it, or remove it");
            out.tolerance = s.number("tolerance", std::nullopt, 0.0, 1e6, true);
        }
    }

    // The name, source, output and map settings of an asset made from a file.
    // synthesised: the asset has no source file, only an output.
    SourcedAsset sourced(Section& s, const std::string& name, bool sourceRequired = true, bool synthesised = false) {
        SourcedAsset a;
        a.line = s.line();
        a.settings = settings(s, defaults_);
        a.mustTile = s.boolean("tileable").value_or(defaultsMustTile_.value_or(a.settings.wrap == Wrap::Periodic));
        if (synthesised) {
            a.output = output(s, name, a.settings);
            return a;
        }
        const std::optional<std::string> source = sourceRequired ? s.requiredText("source") : s.text("source");
        if (!source) {
            if (s.find("output")) throw s.error("output", "is given, but there is no 'source' to make it from");
            return a;
        }
        if (source->empty()) throw s.error("source", "is empty; give the map's path relative to the manifest");
        const fs::path given(*source);
        a.source = (given.is_absolute() ? given : folder_ / given).lexically_normal().string();
        if (a.source.empty()) a.source = ".";
        a.frames = expandSequence(a.source);
        std::error_code ec;
        if (!fs::is_regular_file(a.frames[0], ec))
            throw s.error("source", "names '" + shorten(*source) + "', which " +
                                        (fs::exists(a.frames[0], ec) ? "is not a file" : "does not exist") + " (looked for " +
                                        a.source + ")",
                          "paths are relative to the manifest's folder; a sequence NAME.EXT is NAME.0000.EXT, ...");
        a.output = output(s, name, a.settings);
        return a;
    }

    // The output's path inside the output folder: relative, normalised, never escaping it. Its container
    // is the one its extension names; without an output, NAME. the container settings names (from this
    // table or [defaults]; exr when none). A container in this table must agree with the output's
    // extension; [defaults]' gives way to an output named here. settings.container is set either way.
    std::string output(Section& s, const std::string& name, MapSettings& settings) {
        const bool own = s.find("container") != nullptr;
        if (!own && s.find("output")) settings.container.reset();
        const std::string ext0 = settings.container ? containerName(*settings.container) : "exr";
        const std::string given = s.text("output").value_or(name + "." + ext0);
        const fs::path p = fs::path(given).lexically_normal();
        if (given.empty() || p.is_absolute() || p.empty() || *p.begin() == ".." || p == "." || p.filename().empty())
            throw s.error("output", "is '" + shorten(given) + "', which is not a file inside the output folder",
                          "give a relative path such as textures/swell.exr, without '..'");
        const auto named = containerForPath(p.string());
        if (!named)
            throw s.error("output", "is '" + shorten(given) + "', but a texture is written as .exr, .ktx2 or .dds");
        if (settings.container && *named != *settings.container)
            throw s.error("output", "is '" + shorten(given) + "', but container is \"" +
                                        containerName(*settings.container) + "\"",
                          "name the output ." + std::string(containerName(*settings.container)) +
                              ", or set container to match it");
        settings.container = *named;
        if (*named == Container::Exr && settings.pixelType == PixelType::Uint16 && settings.tolerance == 0.0) {
            const std::string what = "writes '" + p.string() + "' in uint16, but an EXR has no 16-bit normalised channels";
            const std::string fix = "set container = \"ktx2\" or \"dds\", or pixel_type = \"half\"";
            if (s.find("pixel_type")) throw s.error("pixel_type", "is \"uint16\": [" + s.prefix() + "] " + what, fix);
            throw s.error(s.line(), "[" + s.prefix() + "] " + what + " (pixel_type from [defaults])", fix);
        }
        if (p.filename().string().front() == '.')
            throw s.error("output", "is '" + shorten(given) + "': names starting with '.' are heightpack's own temporary files");
        claim(s, p.string());
        return p.string();
    }

    // Every file a manifest makes must have its own name (frames of a sequence included).
    void claim(Section& s, const std::string& output) {
        const auto [it, fresh] = outputs_.emplace(output, s.line());
        if (!fresh)
            throw s.error(s.line(), "[" + s.prefix() + "] writes '" + output + "', as does the asset on line " +
                                        std::to_string(it->second),
                          "give each asset its own name or output");
    }

    std::string assetName(Section& s, const std::string& fallback) {
        const std::string name = s.text("name").value_or(fallback);
        if (!validName(name)) throw s.error("name", "is '" + shorten(name) + "': use 1-64 letters, digits, '_', '-' or '.'");
        claimName(s, name, name);
        return name;
    }

    // Every asset of the material has its own name (cascades' NAME_cC included); given is what the
    // manifest wrote, which a cascade's name is made from.
    void claimName(Section& s, const std::string& name, const std::string& given) {
        const auto [it, fresh] = names_.emplace(name, s.line());
        if (!fresh)
            throw s.error("name", "is '" + given + "', " + (name == given ? "" : "so its cascade is '" + name + "', ") +
                                      "already the name of the asset on line " + std::to_string(it->second));
    }

    std::array<double, 2> scroll(Section& s) {
        const auto v = s.numbers("scroll", {0.0, 0.0}, 2, -1e3, 1e3);
        return {v[0], v[1]};
    }

    // One asset, or with [displacement.synth] cascades = N, N of them (synthesisedSea).
    std::vector<DisplacementAsset> displacement(Section& s) {
        DisplacementAsset d;
        d.layer.name = assetName(s, "");
        // A map comes from a file or from a spectrum, never both: which one would the output be?
        const toml::table* synth = s.table("synth");
        if (synth && s.find("source"))
            throw s.error("source", "is given beside a [" + s.prefix() + ".synth] table",
                          "keep one: source = a map's path, or the synth table to synthesise the sea");
        if (!synth && !s.find("source"))
            throw s.error(s.line(), "missing key '" + s.key("source") + "'",
                          "give source = a map's path, or a [displacement.synth] table to synthesise the sea; " +
                              std::string(detail::kHint));
        static_cast<SourcedAsset&>(d) = sourced(s, d.layer.name, true, synth != nullptr);
        d.layer.tileSize = s.number("tile_size", std::nullopt, 0, kMaxTileSize, true);
        if (synth) {
            Section t(*synth, s.prefix() + ".synth", path_);
            d.synth = detail::parseSynthSource(t, d.layer.tileSize);
            if (const size_t maps = mapsBefore_ + d.synth->cascades; maps > kMaxDisplacementMaps)
                throw t.error("cascades", "is " + std::to_string(d.synth->cascades) + ", which makes " +
                                              std::to_string(maps) + " displacement maps; at most " +
                                              std::to_string(kMaxDisplacementMaps),
                              "use fewer cascades, or fewer [[displacement]] maps before this one");
            // Periodic by construction (a sum of whole waves over the tile): nothing to check.
            d.mustTile = false;
        }
        d.layer.scroll = scroll(s);
        d.layer.amplitude = s.number("amplitude", 1.0, -1e6, 1e6);
        d.layer.heightScale = s.number("height_scale", 1.0, -1e6, 1e6);
        d.layer.heightOffset = s.number("height_offset", 0.0, -1e6, 1e6);
        d.layer.choppiness = s.number("choppiness", 1.0, 0.0, 10.0);
        d.keepFoam = s.boolean("foam").value_or(true);
        if (d.layer.heightScale == 0) throw s.error("height_scale", "is 0, which would flatten the map");
        d.layer.wrap = d.settings.wrap;
        d.layer.filter = d.settings.filter;
        if (d.synth) return synthesisedSea(s, d);
        claimFrames(s, d);
        s.finish();
        return {d};
    }

    // The assets of a synthesised sea: itself, or with cascades = N one per cascade, as
    // `heightpack synth --cascades` bakes them. Cascade c is named NAME_cC and written to the output's
    // NAME_cC.EXT (cascadeFileName); it spans its own tile (core's cascadeBands), scrolls at the same
    // metres per second as the first (scroll x tile_size / its tile size: the sea moves as one), and
    // only cascade 0 takes height_offset, so the summed sea is the spectrum once and the offset once.
    // Each map's frames are first written to kSynthFolder/ inside its output's folder.
    std::vector<DisplacementAsset> synthesisedSea(Section& s, const DisplacementAsset& sea) {
        const int count = sea.synth->cascades;
        std::vector<CascadeBand> bands = {{sea.layer.tileSize, 0.0, 0.0, sea.synth->spectrum.seed}};
        if (count > 1) bands = cascadeBands(sea.layer.tileSize, sea.synth->spectrum.size, count, sea.synth->spectrum.seed);
        std::vector<DisplacementAsset> out;
        for (int c = 0; c < count; ++c) {
            DisplacementAsset d = sea;
            if (count > 1) {
                d.synth->spectrum = cascadeOptions(sea.synth->spectrum, bands[c]);
                d.synth->cascade = c;
                d.layer.name = sea.layer.name + "_c" + std::to_string(c);
                if (!validName(d.layer.name))
                    throw s.error("name", "is '" + shorten(sea.layer.name) + "', too long for its cascades' names ('" +
                                              shorten(d.layer.name) + "')",
                                  "use at most 61 characters with cascades");
                claimName(s, d.layer.name, sea.layer.name);
                d.output = cascadeFileName(sea.output, c, count);
                claim(s, d.output);
                d.layer.tileSize = bands[c].tileSize;
                for (double& v : d.layer.scroll) v *= sea.layer.tileSize / bands[c].tileSize;
                if (c > 0) d.layer.heightOffset = 0.0;
            }
            const fs::path stem = fs::path(d.output).filename().replace_extension(".exr");
            for (int f = 0; f < d.synth->frames; ++f)
                d.frames.push_back((fs::path(kSynthFolder) / frameFileName(stem.string(), f, d.synth->frames)).string());
            claimFrames(s, d);
            out.push_back(std::move(d));
        }
        s.finish();
        return out;
    }

    // A sequence writes NAME.0000.exr ...: those names are claimed too.
    void claimFrames(Section& s, const SourcedAsset& a) {
        for (size_t f = 0; a.frames.size() > 1 && f < a.frames.size(); ++f)
            claim(s, frameFileName(a.output, static_cast<int>(f), static_cast<int>(a.frames.size())));
    }

    NormalAsset normals(Section& s) {
        NormalAsset n;
        n.layer.name = assetName(s, "normals");
        static_cast<SourcedAsset&>(n) = sourced(s, n.layer.name);
        n.layer.tileSize = s.number("tile_size", std::nullopt, 0, kMaxTileSize, true);
        n.layer.heightRange = s.number("height", std::nullopt, 0, kMaxHeight, true);
        n.kernel = s.choice("kernel", NormalOptions{}.kernel);
        n.layer.convention = s.choice("convention", NormalOptions{}.convention);
        n.layer.alpha = s.choice("alpha", NormalOptions{}.alpha);
        if (const toml::node* octaves = s.find("octave")) {
            const toml::array* a = octaves->as_array();
            if (!a || !a->is_array_of_tables() || a->empty() || a->size() > 4)
                throw s.error("octave", "must be one to four [[normals.octave]] tables");
            for (size_t i = 0; i < a->size(); ++i) {
                Section o(*(*a)[i].as_table(), "normals.octave[" + std::to_string(i) + "]", path_);
                NormalOctave octave;
                octave.tileSize = o.number("tile_size", std::nullopt, 0, kMaxTileSize, true);
                octave.scroll = scroll(o);
                octave.strength = o.number("strength", 1.0, 0, 100);
                o.finish();
                n.layer.octaves.push_back(octave);
            }
        } else {
            n.layer.octaves.push_back({n.layer.tileSize, {0.0, 0.0}, 1.0});
        }
        claimFrames(s, n);
        s.finish();
        return n;
    }

    FresnelAsset fresnel(Section& s) {
        FresnelAsset f;
        f.line = s.line();
        f.layer.name = assetName(s, "fresnel");
        // A ramp takes the defaults' container and pixel type, or its own; "auto" is for mip chains, so
        // a ramp under auto defaults stays float.
        MapSettings ramp;
        ramp.container = defaults_.container;
        ramp.pixelType = defaults_.tolerance > 0.0 ? PixelType::Float : defaults_.pixelType;
        if (s.find("container")) ramp.container = s.choice("container", Container::Exr);
        pixelType(s, ramp, false);
        f.output = output(s, f.layer.name, ramp);
        f.pixelType = ramp.pixelType;
        const FresnelOptions defaults;
        f.options.ior = s.number("ior", defaults.ior, 1.0, 4.0);
        f.options.model = s.choice("model", defaults.model);
        f.options.index = s.choice("index", defaults.index);
        f.options.size = s.integer("size", defaults.size, 2, 65536);
        const auto deep = s.numbers("deep", {defaults.deep.begin(), defaults.deep.end()}, 3, 0.0, 1.0);
        const auto shallow = s.numbers("shallow", {defaults.shallow.begin(), defaults.shallow.end()}, 3, 0.0, 1.0);
        f.options.deep = {deep[0], deep[1], deep[2]};
        f.options.shallow = {shallow[0], shallow[1], shallow[2]};
        f.layer.ior = f.options.ior;
        f.layer.model = f.options.model;
        f.layer.index = f.options.index;
        s.finish();
        return f;
    }

    FoamAsset foam(Section& s) {
        FoamAsset f;
        f.line = s.line();
        f.layer.name = assetName(s, "foam");
        f.layer.h0 = s.number("h0", std::nullopt, -1e4, 1e4);
        f.layer.hmax = s.number("hmax", std::nullopt, -1e4, 1e4);
        if (f.layer.hmax <= f.layer.h0)
            throw s.error("hmax", "is " + Section::formatNumber(f.layer.hmax) + ", but must be above h0 (" +
                                      Section::formatNumber(f.layer.h0) + ")");
        f.layer.tileSize = s.number("tile_size", 4.0, 0, kMaxTileSize, true);
        SourcedAsset texture = sourced(s, f.layer.name, false);
        if (!texture.source.empty()) {
            if (texture.frames.size() > 1) throw s.error("source", "names a sequence; foam is one texture");
            f.texture = std::move(texture);
        }
        s.finish();
        return f;
    }

    std::string path_;
    fs::path folder_;
    MapSettings defaults_;
    std::optional<bool> defaultsMustTile_;
    std::map<std::string, int> outputs_;  // output path -> line that claimed it
    std::map<std::string, int> names_;
    size_t mapsBefore_ = 0;  // displacement maps made by the tables before the one being read
};

}  // namespace

Result<Manifest> parseManifest(const std::string& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        return badInput(path, fs::exists(path, ec) ? "is not a file" : "does not exist", "give a manifest .toml file");
    toml::table root;
    try {
        root = toml::parse_file(path);
    } catch (const toml::parse_error& e) {
        return badInput(path + ":" + std::to_string(e.source().begin.line),
                        "TOML syntax error: " + std::string(e.description()), "fix the manifest's syntax");
    }
    try {
        return ManifestParser(path).parse(root);
    } catch (const Error& e) {
        return e;
    }
}

}  // namespace heightpack
