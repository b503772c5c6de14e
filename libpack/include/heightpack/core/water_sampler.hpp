// The water height H(x, y, t) on the CPU, computed as heightpack-view's vertex shader computes it
// (viewer/shaders/common.glsl): a sum of scrolling layers, each read from its 4-neighbour packed chain
// with one texel per level, trilinear between levels in chapter 18's band (Listing 18-3), a sequence's
// frames blended in time. For an engine's buoyancy and collision queries: a floating object then rides
// the same waves the player sees. Coordinates and levels are computed in single precision in the
// shader's order, so the two agree to float rounding (micrometres near the camera), not merely in method.
//
// Choppy maps (Tessendorf's shift, Dx and Dy beside the heights) move each point
// sideways too: the point that starts at p ends at p + shift(p), at height H(p). sampleWaterHeight and
// sampleWaterShift answer for the point that starts at (x, y), as the viewer's grid vertex at (x, y) moves;
// sampleSurfaceHeight answers what a buoy at (x, y) needs, the height of the surface over (x, y), by
// finding the p that lands there.
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
    // Tessendorf's choppy waves: each frame's packed Dx and Dy chains (as frames, level 0 first), empty for
    // a map without them. The point at xy moves to xy + choppiness * amplitude * D(uv), as the viewer's
    // grid point does (synth's D points toward the crests); choppiness 0 leaves it where it is.
    std::vector<std::vector<Image>> shiftX, shiftY;
    float choppiness = 0.0f;
    bool choppy() const { return choppiness != 0.0f && !shiftX.empty(); }
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

// The height in metres above the water level at world (x, y) and time t (seconds): of the surface over
// (x, y) when no layer is choppy, else of the point that starts at (x, y) and moves by sampleWaterShift
// (the viewer's grid vertex at (x, y)); sampleSurfaceHeight gives the height over (x, y) then. footprint
// is how many metres the query stands for (the viewer's distance times the angle of a pixel); its log2 in
// texels picks each layer's level. 0 asks for the finest level: a point query.
float sampleWaterHeight(const WaterSampler& sampler, float x, float y, float t, float footprint = 0.0f);

// One layer's contribution to sampleWaterHeight, in metres.
float sampleLayerHeight(const WaterSampler& sampler, const SampledLayer& layer, float x, float y, float t, float footprint);

// How far in metres (x, y) the point that starts at world (x, y) moves sideways at time t: the sum over
// choppy layers of choppiness * amplitude * D, read at the same level and band as its height (the
// viewer's waterShift). (0, 0) for a sampler without choppy layers.
std::array<float, 2> sampleWaterShift(const WaterSampler& sampler, float x, float y, float t, float footprint = 0.0f);

// One layer's contribution to sampleWaterShift, in metres; (0, 0) unless layer.choppy().
std::array<float, 2> sampleLayerShift(const WaterSampler& sampler, const SampledLayer& layer, float x, float y, float t,
                                      float footprint);

bool isChoppy(const WaterSampler& sampler);

// How sampleSurfaceHeight looks for the point that lands over (x, y).
struct SurfaceSearch {
    int maxIterations = 64;     // fixed-point steps; each costs one sampleWaterShift
    float tolerance = 1e-6f;    // metres: done when |p + shift(p) - (x, y)| is within this, plus float
                                // rounding at (x, y) (FLT_EPSILON * max(|x|, |y|): 1.2e-5 m at 100 m)
};

// The height of the displaced surface over world (x, y) at time t, and where its point started.
struct SurfaceHeight {
    float height = 0.0f;                 // metres above the water level: sampleWaterHeight at origin
    std::array<float, 2> origin{};       // p: the point whose displaced position is (x, y)
    float residual = 0.0f;               // |p + shift(p) - (x, y)| in metres
    int iterations = 0;                  // shifts evaluated
    bool converged = true;
};

// Solves p + shift(p) = (x, y) by fixed-point iteration from p = (x, y): p <- (x, y) - shift(p), and
// returns the height at p. Each step shrinks the error by the shift's slope (|d shift / d p|, below 1
// wherever the surface does not fold), so a sea with gentle chop converges in a few steps and a steep one
// in tens. Where the surface folds (J = det(I + d shift / d p) < 0), (x, y) lies under it more than once
// and the steps may settle on one of those points (converged, a true answer) or wander between them:
// after maxIterations the result has converged = false and holds the iterate whose residual was smallest,
// with its height and residual, never a NaN. A sampler without choppy layers returns sampleWaterHeight at
// (x, y) itself (origin (x, y), 0 iterations), bit for bit the unshifted answer.
SurfaceHeight sampleSurfaceHeight(const WaterSampler& sampler, float x, float y, float t, float footprint = 0.0f,
                                  const SurfaceSearch& search = {});

// The level of detail a footprint asks of a layer: log2(max(footprint * texels per metre, 1)).
float layerLevelOfDetail(const SampledLayer& layer, float footprint);

}  // namespace heightpack
