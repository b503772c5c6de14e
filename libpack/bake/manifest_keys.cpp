#include "manifest_keys.hpp"

#include <climits>
#include <optional>

#include "manifest_section.hpp"

namespace heightpack::detail {

namespace {

// The map settings: [defaults], and every table with a source.
std::vector<std::string_view> withSettings(std::vector<std::string_view> keys) {
    for (std::string_view k : {"wrap", "filter", "compression", "resize", "channel", "container", "pixel_type",
                               "tolerance", "allow_block_compression", "tileable"})
        keys.push_back(k);
    return keys;
}

}  // namespace

const std::vector<std::string_view>& keysOf(ManifestTable table) {
    static const std::vector<std::string_view> top = {"format",       "name",    "threshold", "defaults",
                                                      "displacement", "normals", "fresnel",   "foam"};
    static const std::vector<std::string_view> defaults = withSettings({});
    static const std::vector<std::string_view> displacement =
        withSettings({"name", "source", "synth", "output", "tile_size", "scroll", "amplitude", "height_scale",
                      "height_offset", "choppiness", "foam", "layout"});
    static const std::vector<std::string_view> synth = {
        "spectrum", "wind",  "direction", "fetch",  "gamma",        "spreading",      "spreading_s",
        "depth",    "swell", "size",      "seed",   "loop",         "frames",         "shift",
        "displacement", "foam",     "foam_threshold",     "foam_decay", "foam_build_up", "cascades"};
    static const std::vector<std::string_view> normals = withSettings(
        {"name", "source", "output", "tile_size", "height", "kernel", "convention", "alpha", "octave", "layout"});
    static const std::vector<std::string_view> octave = {"tile_size", "scroll", "strength"};
    static const std::vector<std::string_view> fresnel = {"name", "output", "container", "pixel_type", "tolerance", "ior",
                                                          "model", "index",  "size",      "deep",       "shallow"};
    static const std::vector<std::string_view> foam = withSettings({"name", "h0", "hmax", "tile_size", "source", "output"});
    switch (table) {
        case ManifestTable::Top: return top;
        case ManifestTable::Defaults: return defaults;
        case ManifestTable::Displacement: return displacement;
        case ManifestTable::Synth: return synth;
        case ManifestTable::Normals: return normals;
        case ManifestTable::Octave: return octave;
        case ManifestTable::Fresnel: return fresnel;
        case ManifestTable::Foam: return foam;
    }
    return top;
}

void rejectUnknownKeys(const toml::table& root, const std::string& file) {
    std::optional<Error> first;
    int firstLine = INT_MAX;
    const auto look = [&](const toml::node* node, const std::string& prefix, ManifestTable kind) {
        if (!node || !node->is_table()) return;
        if (auto unknown = Section(*node->as_table(), prefix, file, kind).firstUnknownKey();
            unknown && unknown->first < firstLine) {
            firstLine = unknown->first;
            first = std::move(unknown->second);
        }
    };
    // Each table of an array of tables, as name[i] (written piece by piece: GCC 12's -Wrestrict takes
    // "[" + std::to_string(i) for an overlapping copy).
    const auto eachTable = [](const toml::node* node, const std::string& name, const auto& visit) {
        if (const toml::array* a = node ? node->as_array() : nullptr)
            for (size_t i = 0; i < a->size(); ++i) {
                std::string prefix = name;
                prefix += '[';
                prefix += std::to_string(i);
                prefix += ']';
                visit((*a)[i], prefix);
            }
    };
    look(&root, "", ManifestTable::Top);
    look(root.get("defaults"), "defaults", ManifestTable::Defaults);
    eachTable(root.get("displacement"), "displacement", [&](const toml::node& d, const std::string& prefix) {
        look(&d, prefix, ManifestTable::Displacement);
        if (d.is_table()) look(d.as_table()->get("synth"), prefix + ".synth", ManifestTable::Synth);
    });
    if (const toml::node* normals = root.get("normals")) {
        look(normals, "normals", ManifestTable::Normals);
        if (normals->is_table())
            eachTable(normals->as_table()->get("octave"), "normals.octave",
                      [&](const toml::node& o, const std::string& prefix) { look(&o, prefix, ManifestTable::Octave); });
    }
    look(root.get("fresnel"), "fresnel", ManifestTable::Fresnel);
    look(root.get("foam"), "foam", ManifestTable::Foam);
    if (first) throw *first;
}

}  // namespace heightpack::detail
