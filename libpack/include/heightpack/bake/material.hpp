// A built water material, as `heightpack build` describes it in material.json: every texture it wrote
// and the parameters a renderer needs to combine them (chapter 18's H(x, y, t) sum, the normal-map
// octaves, the Fresnel ramp, foam). The viewer and engines read it; docs/manifest.md gives the schema.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/core/fresnel.hpp"
#include "heightpack/core/image.hpp"
#include "heightpack/core/layout.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/normal.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/pixel_type.hpp"

namespace heightpack {

// Bumped whenever a field changes meaning or goes away; added fields keep the version.
inline constexpr int kMaterialSchemaVersion = 1;
inline constexpr const char* kMaterialSchemaName = "heightpack-material";

// One texture the build wrote. file is relative to the folder holding material.json; a sequence's
// frames are NAME.0000.EXT ... (see frameFileName) and file names the sequence.
struct MaterialTexture {
    std::string file;
    int width = 0;
    int height = 0;
    int levels = 0;
    int frames = 1;
    // What the texels are stored as, where the file says and it is not float (half, uint16, bc4, bc5,
    // astc-NxN): what a loader must upload them as, and what their recorded error budget belongs to.
    std::optional<PixelType> pixelType;
};

// One height map of the sum H(x, y, t) = sum_i amplitude_i * h_i(x / tileSize_i + scroll_i * t).
struct DisplacementLayer {
    std::string name;
    MaterialTexture texture;           // the heights, in layout
    // Neighbour4: each texel holds its height and three neighbours' (one fetch per lookup). Plain: one
    // channel, filtered in hardware; the one a block format (texture.pixelType bc4, astc-NxN) holds.
    Layout layout = Layout::Neighbour4;
    Wrap wrap = Wrap::Periodic;
    Filter filter = Filter::Kaiser;
    double heightScale = 1.0;          // stored = heightOffset + heightScale * painted value
    double heightOffset = 0.0;
    double tileSize = 64.0;            // metres one tile spans: A_i = 1 / tileSize
    std::array<double, 2> scroll{0.0, 0.0};  // B_i, tiles per second along u and v
    double amplitude = 1.0;            // metres per stored unit
    double loopPeriod = 0.0;           // seconds a sequence's frames span (0: one frame)
    // Tessendorf's choppy waves: the texture also holds Dx, Dy (layers Dx, Dy, packed as the heights), and a
    // renderer moves the point at x to x + choppiness * amplitude * D(x / tileSize + scroll * t).
    bool shift = false;
    double choppiness = 1.0;
    // Synth's looping foam coverage (0..1): the texture also holds layer Foam, packed as the heights, which a
    // renderer reads at x / tileSize + scroll * t, frames blended as the heights are.
    bool foam = false;
};

// One octave of the normal map's detail: the map sampled at its own scale and scroll, weighted.
struct NormalOctave {
    double tileSize = 8.0;             // metres
    std::array<double, 2> scroll{0.0, 0.0};  // tiles per second
    double strength = 1.0;
};

struct NormalLayer {
    std::string name;
    MaterialTexture texture;           // normals, one per mip level, in layout
    // Rgb: x, y, z (and alpha). Xy: x and y alone, z = sqrt(1 - x^2 - y^2) rebuilt by the shader; the one
    // a block format (bc5, astc-NxN) holds.
    Layout layout = Layout::Rgb;
    NormalConvention convention = NormalConvention::OpenGL;  // opengl or directx (green flipped)
    NormalAlpha alpha = NormalAlpha::None;                   // none, height or variance
    double tileSize = 8.0;             // metres the map spans when its slopes were measured
    double heightRange = 0.25;         // metres between a stored 0 and 1 when its slopes were measured
    std::vector<NormalOctave> octaves;
};

struct FresnelLayer {
    std::string name;
    MaterialTexture texture;           // RGBA ramp: rgb water colour, a reflectance
    double ior = 1.333;
    FresnelModel model = FresnelModel::Exact;
    FresnelIndex index = FresnelIndex::NdotV;  // nv: u = N.V; 2nv: u = saturate(2 N.V)
};

struct FoamLayer {
    std::string name;
    std::optional<MaterialTexture> texture;  // plain one-channel chain; none: the renderer's own pattern
    double h0 = 1.2;                   // metres: foam starts at this height
    double hmax = 2.2;                 // and is full at this one
    double tileSize = 4.0;             // metres the foam texture spans
};

struct MaterialDescription {
    std::string name;
    std::string generator;             // "heightpack 0.1.0"
    std::string manifest;              // the manifest's file name
    std::vector<DisplacementLayer> displacement;
    std::optional<NormalLayer> normals;
    std::optional<FresnelLayer> fresnel;
    std::optional<FoamLayer> foam;
};

// material.json's text: keys in a fixed order, numbers printed the shortest way that reads back
// exactly, no timestamps, so the same material always gives the same bytes.
std::string materialJson(const MaterialDescription& material);

// Reads a material.json. Every name (wrap, filter, convention, alpha, model, index) must be one its
// enum's table lists; any other is a damaged file. Texture files stay relative; resolve them against the file's folder.
Result<MaterialDescription> readMaterial(const std::string& path);

}  // namespace heightpack
