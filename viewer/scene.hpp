// What the viewer shows, loaded on the CPU with libpack before any window exists: height layers (packed
// or plain textures in EXR, KTX2 or DDS, or painted maps packed in memory by the same code as `heightpack
// pack`), a normal map, a Fresnel ramp, a foam texture. Texels stay in the type their file stored them in.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/map_units.hpp"
#include "upload_chain.hpp"

namespace heightpack::view {

// One map's mip chain, packed and plain, in the file's pixel type (both decode the same way).
struct HeightFrame {
    UploadChain packed;           // RGBA per level: the 4-neighbour packing
    UploadChain plain;            // R per level: the reference path, and the gather atlas is built from it
    float minStored = 0.0f, maxStored = 1.0f;  // over level 0, in the file's values
    float meanStored = 0.5f;      // the 1x1 level
    // Shift, packed as the heights (RGBA per level); no levels for a map without Dx, Dy.
    // From an array texture in its file's type (and decode); from an EXR or a painted map as floats.
    UploadChain shiftX, shiftY;
    // Baked foam coverage (0..1), one channel per level, unpacked; no levels for a map without it. Typed
    // as shiftX.
    UploadChain foam;
};

struct HeightLayer {
    std::string path;
    std::string source;           // "packed texture", "plain texture" or "painted map, packed in memory"
    std::vector<HeightFrame> frames;  // one, or a looping sequence (NAME.0000.EXT ...)
    double loopPeriod = 0.0;      // seconds the frames span (heightpack:loopPeriod), for sequences
    // What the first file records of the world: its tile's size in metres and the metres of one unit of
    // its values as the layer holds them (the renderer's amplitude), each absent where the file is silent.
    MapUnits units;
    Wrap wrap = Wrap::Periodic;
    float midStored = 0.5f;       // the map's mean (its 1x1 level): subtracted so waves sit on the water level
    float minStored = 0.0f, maxStored = 1.0f;
    bool horizontal = false;      // every frame carries Dx, Dy (Tessendorf's choppy waves)
    bool foam = false;            // every frame carries synth's foam coverage
};

struct NormalMap {
    std::string path;
    // xyz in [-1, 1] (and alpha, if any), or xy alone (the shading uses x and y only); the file's own
    // mip chain, or level 0 only
    UploadChain levels;
    float greenSign = -1.0f;      // world +y runs down the stored image: an OpenGL map's green flips
};

struct FresnelRamp {
    std::string path;
    UploadChain ramp;             // one level: linear rgb, reflectance in alpha
    float indexScale = 1.0f;      // 2 for a ramp indexed by saturate(2 N.V)
};

struct SceneFiles {
    std::vector<std::string> heights;
    std::string normals, fresnel, foam;
    std::string channel;  // --channel for painted colour maps: r, g, b, a, luma or a channel's name; empty: auto
};

struct Scene {
    std::vector<HeightLayer> layers;
    std::optional<NormalMap> normals;
    std::optional<FresnelRamp> fresnel;
    std::optional<Image> foam;
};

// Loads a map, or every frame of a sequence when path names one (see expandSequence).
// channel: see SceneFiles::channel.
Result<HeightLayer> loadHeightLayer(const std::string& path, const std::string& channel = {});
Result<NormalMap> loadNormalMap(const std::string& path);
Result<FresnelRamp> loadFresnelRamp(const std::string& path);
Result<Scene> loadScene(const SceneFiles& files);

// The first file of the scene that holds ASTC blocks (heights or normals), or empty: a context without
// ASTC cannot draw it.
std::string astcPath(const Scene& scene);
// The first layer whose chains hold ASTC HDR blocks, or "" (they also need the HDR profile).
std::string astcHdrPath(const Scene& scene);

// Modification times of the files, to reload what changed on disk.
std::vector<std::filesystem::file_time_type> fileTimes(const SceneFiles& files);

}  // namespace heightpack::view
