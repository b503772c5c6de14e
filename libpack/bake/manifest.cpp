#include "heightpack/bake/manifest.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <string_view>

#include "heightpack/bake/synth_job.hpp"
#include "heightpack/core/sea/cascades.hpp"
#include "heightpack/core/tile/tileable.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/read.hpp"

#include "manifest_keys.hpp"
#include "manifest_parser.hpp"
#include "manifest_synth.hpp"

namespace heightpack {

namespace fs = std::filesystem;

namespace detail {

bool validName(const std::string& name) {
    if (name.empty() || name.size() > 64) return false;
    return std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
    }) && name.front() != '.';
}

Manifest ManifestParser::parse(const toml::table& root) {
    Section top(root, "", path_, ManifestTable::Top);
    Manifest m;
    m.path = path_;
    const auto checkFormat = [&] {
        const double format = top.number("format", std::nullopt, 1, 1e9);
        if (format != kManifestFormat)
            throw top.error("format", "is " + Section::formatNumber(format) + ", but this heightpack reads format " +
                                          std::to_string(kManifestFormat));
    };
    // Another format's keys are not this one's: a manifest of another format is told so first. Then a
    // misspelt key anywhere is named before any key it leaves missing (or any value) is judged.
    if (root.get("format")) checkFormat();
    rejectUnknownKeys(root, path_);
    checkFormat();
    m.name = top.requiredText("name");
    if (!validName(m.name)) throw top.error("name", "must be 1-64 letters, digits, '_', '-' or '.'");
    m.threshold = top.number("threshold", kDefaultSeamThreshold, 1.0, 1e6);
    if (const toml::table* d = top.table("defaults")) {
        Section s(*d, "defaults", path_, ManifestTable::Defaults);
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
        Section s(*(*array)[i].as_table(), "displacement[" + std::to_string(i) + "]", path_, ManifestTable::Displacement);
        mapsBefore_ = m.displacement.size();
        for (DisplacementAsset& d : displacement(s)) m.displacement.push_back(std::move(d));
        if (m.displacement.size() > kMaxDisplacementMaps)  // the cascades of a sea above it fill the material
            throw s.error(s.line(), "[" + s.prefix() + "] is displacement map " + std::to_string(m.displacement.size()) +
                                        ", counting each cascade of a synthesised sea; at most " +
                                        std::to_string(kMaxDisplacementMaps),
                          "use fewer cascades, or fewer [[displacement]] maps");
    }
    if (const toml::table* t = top.table("normals")) {
        Section s(*t, "normals", path_, ManifestTable::Normals);
        m.normals = normals(s);
    }
    if (const toml::table* t = top.table("fresnel")) {
        Section s(*t, "fresnel", path_, ManifestTable::Fresnel);
        m.fresnel = fresnel(s);
    }
    if (const toml::table* t = top.table("foam")) {
        Section s(*t, "foam", path_, ManifestTable::Foam);
        m.foam = foam(s);
    }
    top.finish();
    return m;
}

MapSettings ManifestParser::settings(Section& s, const MapSettings& base) {
    MapSettings out = base;
    out.wrap = s.choice("wrap", base.wrap);
    out.filter = s.choice("filter", base.filter);
    out.storage.exrCompression = s.choice("compression", base.storage.exrCompression);
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

// pixel_type (float, half, uint16, a block format, or auto with tolerance and allow_block_compression)
// into out, over what out holds already (the defaults). A table that names a type of its own drops an
// inherited tolerance and allow_block_compression. Whether a block format suits the map's layout and
// container is judged once both are known (blockFits, manifest_blocks.cpp).
void ManifestParser::pixelType(Section& s, MapSettings& out, bool mipChain) {
    const std::string choices =
        mipChain ? joinedNames<PixelType>() + ", auto" : std::string("float, half, uint16");
    if (const auto type = s.text("pixel_type")) {
        out.storage.allowBlockCompression = false;
        if (*type == "auto" && mipChain) {
            if (!s.find("tolerance"))
                throw s.error("pixel_type", "is \"auto\", which needs a tolerance",
                              "add tolerance = the worst lookup error allowed, in stored units (normal units "
                              "for normals, or an angle such as \"2deg\"), such as 0.0005");
            tolerance(s, out.storage);
            out.storage.allowBlockCompression = s.boolean("allow_block_compression").value_or(false);
            return;
        }
        const auto parsed = parseName<PixelType>(*type);
        if (!parsed) throw s.error("pixel_type", "is '" + shorten(*type) + "', but must be one of: " + choices);
        // A ramp is one level of a few hundred texels, read at any angle: blocks would only blur it.
        if (isBlockType(*parsed) && !mipChain)
            throw s.error("pixel_type", "is '" + shorten(*type) + "', a block format, which is for mip-mapped maps",
                          "set one of: " + choices);
        out.storage.pixelType = *parsed;
        out.storage.tolerance = 0.0;
    }
    if (s.find("tolerance")) {
        if (!(out.storage.tolerance > 0.0))  // neither here nor in [defaults] is the type "auto"
            throw s.error("tolerance", "is given, but pixel_type is not \"auto\"",
                          "set pixel_type = \"auto\" beside it, or remove it");
        tolerance(s, out.storage);
    }
    if (!mipChain) return;
    if (const auto allow = s.boolean("allow_block_compression")) {
        if (!(out.storage.tolerance > 0.0))
            throw s.error("allow_block_compression", "is given, but pixel_type is not \"auto\"",
                          "set pixel_type = \"auto\" and a tolerance beside it, or remove it");
        out.storage.allowBlockCompression = *allow;
    }
}

// tolerance: a number in stored units; in [normals] also an angle, "2deg": the worst between a stored
// normal and its own (heightpack normal --tolerance 2deg).
void ManifestParser::tolerance(Section& s, TextureStorage& storage) {
    storage.toleranceInDegrees = false;
    const toml::node* n = s.find("tolerance");
    if (n && n->is_string() && s.kind() == ManifestTable::Normals) {
        const std::string text = n->value<std::string>().value_or("");
        char* end = nullptr;
        const double degrees = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || std::string_view(end) != "deg" || !(degrees > 0.0 && degrees < 180.0))
            throw s.error("tolerance", "is '" + shorten(text) + "', but must be a number (normal units) or an angle "
                                       "between 0 and 180 degrees such as \"2deg\"");
        storage.tolerance = degrees;
        storage.toleranceInDegrees = true;
        return;
    }
    storage.tolerance = s.number("tolerance", std::nullopt, 0.0, 1e6, true);
}

// The name, source, output and map settings of an asset made from a file.
// synthesised: the asset has no source file, only an output.
SourcedAsset ManifestParser::sourced(Section& s, const std::string& name, bool sourceRequired, bool synthesised) {
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
    if (sources_ == SourceCheck::MustExist && !fs::is_regular_file(a.frames[0], ec))
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
std::string ManifestParser::output(Section& s, const std::string& name, MapSettings& settings) {
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
    if (*named == Container::Exr && settings.storage.pixelType == PixelType::Uint16 && settings.storage.tolerance == 0.0) {
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
void ManifestParser::claim(Section& s, const std::string& output) {
    const auto [it, fresh] = outputs_.emplace(output, s.line());
    if (!fresh)
        throw s.error(s.line(), "[" + s.prefix() + "] writes '" + output + "', as does the asset on line " +
                                    std::to_string(it->second),
                      "give each asset its own name or output");
}

std::string ManifestParser::assetName(Section& s, const std::string& fallback) {
    const std::string name = s.text("name").value_or(fallback);
    if (!validName(name)) throw s.error("name", "is '" + shorten(name) + "': use 1-64 letters, digits, '_', '-' or '.'");
    claimName(s, name, name);
    return name;
}

// Every asset of the material has its own name (cascades' NAME_cC included); given is what the
// manifest wrote, which a cascade's name is made from.
void ManifestParser::claimName(Section& s, const std::string& name, const std::string& given) {
    const auto [it, fresh] = names_.emplace(name, s.line());
    if (!fresh)
        throw s.error("name", "is '" + given + "', " + (name == given ? "" : "so its cascade is '" + name + "', ") +
                                  "already the name of the asset on line " + std::to_string(it->second));
}

std::array<double, 2> ManifestParser::scroll(Section& s) {
    const auto v = s.numbers("scroll", {0.0, 0.0}, 2, -1e3, 1e3);
    return {v[0], v[1]};
}

// A sequence writes NAME.0000.exr ...: those names are claimed too.
void ManifestParser::claimFrames(Section& s, const SourcedAsset& a) {
    for (size_t f = 0; a.frames.size() > 1 && f < a.frames.size(); ++f)
        claim(s, frameFileName(a.output, static_cast<int>(f), static_cast<int>(a.frames.size())));
}

}  // namespace detail

Result<Manifest> parseManifest(const std::string& path, SourceCheck sources) {
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
        return detail::ManifestParser(path, sources).parse(root);
    } catch (const Error& e) {
        return e;
    }
}

}  // namespace heightpack
