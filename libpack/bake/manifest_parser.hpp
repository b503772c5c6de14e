// Internal: the manifest parser (manifest.cpp: the file, [defaults], and what every table shares: names,
// outputs, map settings; manifest_tables.cpp: the asset tables, [[displacement]] with its synthesised
// seas, [normals], [fresnel], [foam]). Every table is read through a Section (manifest_section.hpp), so an
// error names file:line and the key.
#pragma once

#include <toml++/toml.h>

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/bake/manifest.hpp"

#include "manifest_section.hpp"

namespace heightpack::detail {

// The same limits as the command line's --tile-size and --height: a tile up to 100 km across, waves up
// to 1 km high. Anything larger is a typo, and would overflow float maths downstream.
inline constexpr double kMaxTileSize = 1e5;
inline constexpr double kMaxHeight = 1e3;
// Height maps in a material, a synthesised sea's cascades each counted.
inline constexpr size_t kMaxDisplacementMaps = 8;

// 1-64 letters, digits, '_', '-' or '.', not starting with '.'.
bool validName(const std::string& name);

class ManifestParser {
public:
    ManifestParser(std::string path, SourceCheck sources)
        : path_(std::move(path)), folder_(std::filesystem::path(path_).parent_path()), sources_(sources) {}

    Manifest parse(const toml::table& root);

private:
    MapSettings settings(Section& s, const MapSettings& base);
    // pixel_type (float, half, uint16, a block format, or auto with tolerance and allow_block_compression)
    // into out, over what out holds already (the defaults). A table that names a type of its own drops an
    // inherited tolerance and allow_block_compression. mipChain: false for a ramp, which takes neither
    // auto nor a block format.
    void pixelType(Section& s, MapSettings& out, bool mipChain);
    void tolerance(Section& s, TextureStorage& storage);
    // The layout key of a [[displacement]] (heights: neighbour4, plain) or [normals] (rgb, xy) table.
    Layout layout(Section& s, bool heights);
    // Whether settings' pixel type (or, under auto, allow_block_compression) suits a map of this layout in
    // its container: a block format holds plain heights or xy normals (bc4 one channel, bc5 two), never
    // the neighbour4 layout, and goes into a KTX2 (ASTC) or a KTX2 or DDS (BC), never an EXR. Refused with
    // the key that asks for it, or the table's line when it comes from [defaults].
    void blockFits(Section& s, const MapSettings& settings, Layout layout);
    // The name, source, output and map settings of an asset made from a file.
    // synthesised: the asset has no source file, only an output.
    SourcedAsset sourced(Section& s, const std::string& name, bool sourceRequired = true, bool synthesised = false);
    // The output's path inside the output folder: relative, normalised, never escaping it. Its container
    // is the one its extension names; without an output, NAME. the container settings names (from this
    // table or [defaults]; exr when none). A container in this table must agree with the output's
    // extension; [defaults]' gives way to an output named here. settings.container is set either way.
    std::string output(Section& s, const std::string& name, MapSettings& settings);
    // Every file a manifest makes must have its own name (frames of a sequence included).
    void claim(Section& s, const std::string& output);
    std::string assetName(Section& s, const std::string& fallback);
    // Every asset of the material has its own name (cascades' NAME_cC included); given is what the
    // manifest wrote, which a cascade's name is made from.
    void claimName(Section& s, const std::string& name, const std::string& given);
    std::array<double, 2> scroll(Section& s);
    // A sequence writes NAME.0000.exr ...: those names are claimed too.
    void claimFrames(Section& s, const SourcedAsset& a);

    // One asset, or with [displacement.synth] cascades = N, N of them (synthesisedSea).
    std::vector<DisplacementAsset> displacement(Section& s);
    // The assets of a synthesised sea: itself, or with cascades = N one per cascade, as
    // `heightpack synth --cascades` bakes them. Cascade c is named NAME_cC and written to the output's
    // NAME_cC.EXT (cascadeFileName); it spans its own tile (core's cascadeBands), scrolls at the same
    // metres per second as the first (scroll x tile_size / its tile size: the sea moves as one), and
    // only cascade 0 takes height_offset, so the summed sea is the spectrum once and the offset once.
    // Each map's frames are first written to kSynthFolder/ inside its output's folder.
    std::vector<DisplacementAsset> synthesisedSea(Section& s, const DisplacementAsset& sea);
    NormalAsset normals(Section& s);
    FresnelAsset fresnel(Section& s);
    FoamAsset foam(Section& s);

    std::string path_;
    std::filesystem::path folder_;
    SourceCheck sources_;
    MapSettings defaults_;
    std::optional<bool> defaultsMustTile_;
    std::map<std::string, int> outputs_;  // output path -> line that claimed it
    std::map<std::string, int> names_;
    size_t mapsBefore_ = 0;  // displacement maps made by the tables before the one being read
};

}  // namespace heightpack::detail
