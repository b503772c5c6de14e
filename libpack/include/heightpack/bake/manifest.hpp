// A water material manifest (TOML, docs/manifest.md): which maps make the material, how each is
// packed, and the parameters that go into material.json. Parsed strictly: an unknown key, a missing
// one, a wrong type or a value out of range is an error naming the file, the line and the key.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "heightpack/bake/material.hpp"
#include "heightpack/core/sea/foam.hpp"
#include "heightpack/core/fresnel.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/normal.hpp"
#include "heightpack/core/sea/spectrum.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/pixel_type.hpp"
#include "heightpack/io/read.hpp"
#include "heightpack/io/texture_storage.hpp"

namespace heightpack {

inline constexpr int kManifestFormat = 1;

// How one source map becomes a texture: the settings every map has, from [defaults] or its own table.
struct MapSettings {
    Wrap wrap = Wrap::Periodic;
    Filter filter = Filter::Kaiser;
    bool resize = false;  // resample sides that are not powers of two up to the next ones
    ChannelSelect channel = ChannelSelect::Auto;
    // The container the output goes into; unset: the output's extension says (.exr when not given).
    std::optional<Container> container;
    // pixel_type (tolerance > 0: "auto", the fewest bytes within it, stored units) and compression; a
    // manifest names no supercompression.
    TextureStorage storage;
};

// What every asset built from a source file shares.
struct SourcedAsset {
    std::string source;               // resolved path (the manifest's folder joined with what it says)
    std::vector<std::string> frames;  // the files source names: itself, or NAME.0000.EXT ... for a sequence
    std::string output;               // relative to the output folder, normalised; frames get numbered names
    MapSettings settings;
    bool mustTile = true;             // the tileability check must pass (default: wrap is periodic)
    int line = 0;                     // the line of the asset's table in the manifest
};

// A sea the build synthesises instead of reading a file ([displacement.synth]): the spectrum (its tile
// size is the asset's tile_size, or with cascades this cascade's), how many frames of its loop to bake,
// whether Dx, Dy and the loop's foam are synthesised beside the heights, and which cascade of how many
// this map is.
struct SynthSource {
    SpectrumOptions spectrum;         // with cascades, cascadeOptions(sea, band): its tile size, band and seed
    int frames = 1;                   // more than one needs spectrum.loopPeriod
    bool shift = false;               // Dx, Dy too, as `synth --shift` (kept for an .exr output only)
    // Foam coverage too, as `synth --foam` (kept for an .exr output only): worked out over the whole loop,
    // where the surface moved by the asset's choppiness times D folds (synth's --choppiness).
    bool foam = false;
    FoamOptions foamOptions;
    double choppiness = 1.0;          // the lambda of x + lambda D whose Jacobian the foam follows
    int cascade = 0;                  // this map is cascade `cascade` of `cascades` (core/cascades.hpp)
    int cascades = 1;
};

struct DisplacementAsset : SourcedAsset {
    DisplacementLayer layer;          // name, tile size, scroll, amplitude, height scale and offset
    // Set: the map is synthesised, source is empty and frames are the intermediate files' names
    // (kSynthFolder/NAME.EXR inside the output's folder), one per frame. A table with cascades = N
    // becomes N assets, NAME_c0 ... (outputs NAME_c0.EXT ...), one per cascade.
    std::optional<SynthSource> synth;
    // The key foam (default true): keep the source's foam coverage (synth --foam's Foam channel) in an EXR
    // output; false leaves it out. A synthesised map keeps the foam its synth table asks for.
    bool keepFoam = true;
};

// Where a synthesised map is written, inside its output's folder, before it is packed: a hidden folder in
// the output, never beside the manifest (the manifest's folder may be read-only, or under version control).
inline constexpr const char* kSynthFolder = ".heightpack-synth";

struct NormalAsset : SourcedAsset {
    NormalLayer layer;                // name, octaves, tile size, height range, convention, alpha
    SlopeKernel kernel = SlopeKernel::Central;
};

struct FresnelAsset {
    FresnelLayer layer;
    FresnelOptions options;
    PixelType pixelType = PixelType::Float;  // no "auto": a ramp is a few hundred texels
    std::string output;
    int line = 0;
};

struct FoamAsset {
    FoamLayer layer;
    std::optional<SourcedAsset> texture;
    int line = 0;
};

struct Manifest {
    std::string path;                 // the manifest file, as given
    std::string name;                 // the material's name
    double threshold = 2.0;           // seam score that fails the tileability check
    std::vector<DisplacementAsset> displacement;
    std::optional<NormalAsset> normals;
    std::optional<FresnelAsset> fresnel;
    std::optional<FoamAsset> foam;
};

// Whether a source the manifest names must be there when it is read. MayBeAbsent is for an action that
// makes one output where only the files that output reads are (a Bazel sandbox): another asset's source
// may be missing (its asset keeps the path as given, one frame), and the output's own is read, so
// reported, when it is made.
enum class SourceCheck { MustExist, MayBeAbsent };

// Reads and validates the manifest at path: TOML syntax, keys, types, ranges, that every source exists
// (unless sources is MayBeAbsent), that output names are unique and stay inside the output folder.
// Errors are BadInput with path "FILE:LINE" and the key in the message.
Result<Manifest> parseManifest(const std::string& path, SourceCheck sources = SourceCheck::MustExist);

}  // namespace heightpack
