// What the viewer shows, loaded on the CPU with libpack before any window exists: height layers (packed
// textures, or painted maps packed in memory by the same code as `heightpack pack`), a normal map, a
// Fresnel ramp, a foam texture.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"

namespace heightpack::view {

// One map's mip chain, packed and plain.
struct HeightFrame {
    std::vector<Image> packed;    // RGBA per level
    std::vector<Image> plain;     // R per level, for the reference path
};

struct HeightLayer {
    std::string path;
    std::string source;           // "packed texture", "plain texture" or "painted map, packed in memory"
    std::vector<HeightFrame> frames;  // one, or a looping sequence (NAME.0000.EXT ...)
    double loopPeriod = 0.0;      // seconds the frames span (heightpack:loopPeriod), for sequences
    Wrap wrap = Wrap::Periodic;
    float midStored = 0.5f;       // the map's mean (its 1x1 level): subtracted so waves sit on the water level
    float minStored = 0.0f, maxStored = 1.0f;
};

struct NormalMap {
    std::string path;
    std::vector<Image> levels;    // xyz in [-1, 1] (and alpha, if any); the file's own mip chain, or level 0 only
    float greenSign = -1.0f;      // world +y runs down the stored image: an OpenGL map's green flips
};

struct FresnelRamp {
    std::string path;
    Image ramp;                   // linear rgb, reflectance in alpha
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

// Modification times of the files, to reload what changed on disk.
std::vector<std::filesystem::file_time_type> fileTimes(const SceneFiles& files);

}  // namespace heightpack::view
