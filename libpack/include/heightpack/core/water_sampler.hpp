// The water height H(x, y, t) on the CPU, computed as heightpack-view's vertex shader computes it
// (viewer/shaders/common.glsl): a sum of scrolling layers, each read from its 4-neighbour packed chain
// with one texel per level, trilinear between levels in chapter 18's band (Listing 18-3), a sequence's
// frames blended in time. For an engine's buoyancy and collision queries: a floating object then rides
// the same waves the player sees. Coordinates and levels are computed in single precision in the
// shader's order, so the two agree to float rounding (micrometres near the camera), not merely in method.
#pragma once

#include <array>
#include <vector>

#include "heightpack/core/image.hpp"
#include "heightpack/core/names.hpp"
#include "heightpack/core/pack.hpp"

namespace heightpack {

// One height map of the sum: amplitude * (stored(uv) - midStored), uv = xy / tileSize + scroll * t.
struct SampledLayer {
    std::vector<std::vector<Image>> frames;  // each frame's neighbour4 packed chain (RGBA per level, level 0 first)
    Wrap wrap = Wrap::Periodic;
    float tileSize = 64.0f;                  // metres one tile spans
    std::array<float, 2> scroll{0.0f, 0.0f}; // tiles per second along u and v
    float amplitude = 1.0f;                  // metres per stored unit
    double loopPeriod = 0.0;                 // seconds the frames span; frame f covers [f, f+1) * period / frames
    float midStored = 0.0f;                  // subtracted so waves sit on the water level: the viewer's choice,
                                             // the first frame's 1x1 level (see midStoredOf)
};

// The viewer's height lookups on packed textures: one level, or chapter 18's banded blend of two.
enum class LevelFilter { Bilinear, Trilinear };
template <>
struct NameTable<LevelFilter> {
    static constexpr EnumName<LevelFilter> entries[] = {
        {LevelFilter::Bilinear, "bilinear", "level 0 only, as from close by"},
        {LevelFilter::Trilinear, "trilinear", "the level the footprint asks for, blended inside the band"},
    };
};

struct WaterSampler {
    std::vector<SampledLayer> layers;
    LevelFilter filter = LevelFilter::Trilinear;
    TrilinearBands bands;                    // Listing 18-3's blend band within a level's fraction
};

// The value a sampler subtracts from a layer whose frames are given: the first frame's coarsest texel
// (the mean of a periodic map, as the mip chain averages).
float midStoredOf(const std::vector<std::vector<Image>>& frames);

// The height in metres above the water level at world (x, y) and time t (seconds). footprint is how many
// metres the query stands for (the viewer's distance times the angle of a pixel); its log2 in texels
// picks each layer's level. 0 asks for the finest level: a point query.
float sampleWaterHeight(const WaterSampler& sampler, float x, float y, float t, float footprint = 0.0f);

// One layer's contribution to sampleWaterHeight, in metres.
float sampleLayerHeight(const WaterSampler& sampler, const SampledLayer& layer, float x, float y, float t, float footprint);

// The level of detail a footprint asks of a layer: log2(max(footprint * texels per metre, 1)).
float layerLevelOfDetail(const SampledLayer& layer, float footprint);

}  // namespace heightpack
