// The asset tables of a manifest: [[displacement]] (from a file, or synthesised, its cascades each an
// asset), [normals], [fresnel] and [foam]. What they share (names, outputs, settings) is in manifest.cpp.
#include <filesystem>

#include "heightpack/bake/synth_job.hpp"
#include "heightpack/core/sea/cascades.hpp"
#include "heightpack/io/files.hpp"

#include "manifest_parser.hpp"
#include "manifest_synth.hpp"

namespace heightpack::detail {

namespace fs = std::filesystem;

// One asset, or with [displacement.synth] cascades = N, N of them (synthesisedSea).
std::vector<DisplacementAsset> ManifestParser::displacement(Section& s) {
    DisplacementAsset d;
    d.layer.name = assetName(s, "");
    // A map comes from a file or from a spectrum, never both: which one would the output be?
    const toml::table* synth = s.table("synth");
    if (synth && s.find("source"))
        throw s.error("source", "is given beside a [" + s.prefix() + ".synth] table",
                      "keep one: source = a map's path, or the synth table to synthesise the sea");
    if (!synth && !s.find("source"))
        throw s.missing("source", "give source = a map's path, or a [displacement.synth] table to synthesise the sea;");
    static_cast<SourcedAsset&>(d) = sourced(s, d.layer.name, true, synth != nullptr);
    d.layer.tileSize = s.number("tile_size", std::nullopt, 0, kMaxTileSize, true);
    d.layer.layout = layout(s, true);
    blockFits(s, d.settings, d.layer.layout);
    if (synth) {
        Section t(*synth, s.prefix() + ".synth", path_, ManifestTable::Synth);
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
    if (d.synth && d.synth->foam) {
        // A synthesised sea's foam is where the surface the viewer draws (moved by choppiness x D) folds.
        if (d.layer.choppiness == 0)
            throw s.error("choppiness", "is 0, but [" + s.prefix() + ".synth] asks for foam, which forms where the surface folds",
                          "give choppiness above 0, or remove foam = true");
        if (!d.keepFoam)
            throw s.error("foam", "is false, but [" + s.prefix() + ".synth] synthesises foam",
                          "remove one of them: foam = true in the synth table makes the foam this key would drop");
        d.synth->choppiness = d.layer.choppiness;
    }
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
std::vector<DisplacementAsset> ManifestParser::synthesisedSea(Section& s, const DisplacementAsset& sea) {
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

NormalAsset ManifestParser::normals(Section& s) {
    NormalAsset n;
    n.layer.name = assetName(s, "normals");
    static_cast<SourcedAsset&>(n) = sourced(s, n.layer.name);
    n.layer.tileSize = s.number("tile_size", std::nullopt, 0, kMaxTileSize, true);
    n.layer.heightRange = s.number("height", std::nullopt, 0, kMaxHeight, true);
    n.kernel = s.choice("kernel", NormalOptions{}.kernel);
    n.layer.convention = s.choice("convention", NormalOptions{}.convention);
    n.layer.alpha = s.choice("alpha", NormalOptions{}.alpha);
    n.layer.layout = layout(s, false);
    if (n.layer.layout == Layout::Xy && n.layer.alpha != NormalAlpha::None)
        throw s.error("layout", "is \"xy\", two channels, which leave no alpha for alpha = \"" +
                                    std::string(nameOf(n.layer.alpha)) + "\"",
                      "set alpha = \"none\", or layout = \"rgb\"");
    blockFits(s, n.settings, n.layer.layout);
    if (const toml::node* octaves = s.find("octave")) {
        const toml::array* a = octaves->as_array();
        if (!a || !a->is_array_of_tables() || a->empty() || a->size() > 4)
            throw s.error("octave", "must be one to four [[normals.octave]] tables");
        for (size_t i = 0; i < a->size(); ++i) {
            Section o(*(*a)[i].as_table(), "normals.octave[" + std::to_string(i) + "]", path_, ManifestTable::Octave);
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

FresnelAsset ManifestParser::fresnel(Section& s) {
    FresnelAsset f;
    f.line = s.line();
    f.layer.name = assetName(s, "fresnel");
    // A ramp takes the defaults' container and pixel type, or its own; "auto" and the block formats are
    // for mip chains, so a ramp under such defaults stays float.
    MapSettings ramp;
    ramp.container = defaults_.container;
    const bool chainOnly = defaults_.storage.tolerance > 0.0 || isBlockType(defaults_.storage.pixelType);
    ramp.storage.pixelType = chainOnly ? PixelType::Float : defaults_.storage.pixelType;
    if (s.find("container")) ramp.container = s.choice("container", Container::Exr);
    pixelType(s, ramp, false);
    f.output = output(s, f.layer.name, ramp);
    f.pixelType = ramp.storage.pixelType;
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

FoamAsset ManifestParser::foam(Section& s) {
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
        blockFits(s, texture.settings, Layout::Plain);  // a foam texture is a plain chain
        f.texture = std::move(texture);
    }
    s.finish();
    return f;
}

}  // namespace heightpack::detail
