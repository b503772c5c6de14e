// Mirrors viewer/shaders/common.glsl: the level of detail and the texture coordinates in float, in the
// shader's order (their rounding is what separates the two at a distance), the lookups through the
// packed-chain mirrors of pack.hpp. The viewer test compares the two on rendered grid vertices.
#include "heightpack/core/water_sampler.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "heightpack/core/pack.hpp"

namespace heightpack {
namespace {

// Which frame of a sequence shows at time t, the next one, and how far between them (the viewer's
// Renderer::bindLayers, in double as there).
struct FramePick {
    size_t current = 0, next = 0;
    float blend = 0.0f;
};

FramePick pickFrames(const SampledLayer& layer, float t) {
    FramePick pick;
    if (layer.frames.size() < 2 || !(layer.loopPeriod > 0.0)) return pick;
    const double frames = static_cast<double>(layer.frames.size());
    double position = std::fmod(t / layer.loopPeriod * frames, frames);
    if (position < 0) position += frames;
    pick.current = static_cast<size_t>(position) % layer.frames.size();
    pick.next = (pick.current + 1) % layer.frames.size();
    pick.blend = static_cast<float>(position - std::floor(position));
    return pick;
}

}  // namespace

float midStoredOf(const std::vector<std::vector<Image>>& frames) {
    if (frames.empty() || frames[0].empty() || frames[0].back().empty()) return 0.0f;
    return frames[0].back().pixels[0];
}

float layerLevelOfDetail(const SampledLayer& layer, float footprint) {
    if (layer.frames.empty() || layer.frames[0].empty()) return 0.0f;
    const float texelsPerMetre = (1.0f / layer.tileSize) * static_cast<float>(layer.frames[0][0].width);
    return std::log2(std::max(footprint * texelsPerMetre, 1.0f));
}

namespace {

// A layer's texture coordinates and level for a query: the shader's layerUv and layerLod, in float.
struct LayerLookup {
    float u = 0.0f, v = 0.0f, lod = 0.0f;
    FramePick pick;
};

LayerLookup lookupOf(const SampledLayer& layer, float x, float y, float t, float footprint) {
    LayerLookup l;
    l.lod = layerLevelOfDetail(layer, footprint);
    const float scale = 1.0f / layer.tileSize;
    l.u = x * scale + layer.scroll[0] * t;
    l.v = y * scale + layer.scroll[1] * t;
    l.pick = pickFrames(layer, t);
    return l;
}

// One packed chain at the lookup's point: level 0 (bilinear) or the footprint's level and band.
float chainAt(const WaterSampler& sampler, const SampledLayer& layer, const std::vector<Image>& chain, const LayerLookup& l) {
    return sampler.filter == LevelFilter::Bilinear ? samplePackedBilinear(chain[0], l.u, l.v, layer.wrap)
                                                   : samplePackedTrilinear(chain, l.u, l.v, l.lod, layer.wrap, sampler.bands);
}

// A frame's value, blended into the next frame's as the viewer blends a sequence.
float blendedAt(const WaterSampler& sampler, const SampledLayer& layer, const std::vector<std::vector<Image>>& frames,
                const LayerLookup& l) {
    float value = chainAt(sampler, layer, frames[l.pick.current], l);
    if (l.pick.blend > 0.0f) value += (chainAt(sampler, layer, frames[l.pick.next], l) - value) * l.pick.blend;
    return value;
}

}  // namespace

float sampleLayerHeight(const WaterSampler& sampler, const SampledLayer& layer, float x, float y, float t, float footprint) {
    if (layer.frames.empty() || layer.frames[0].empty()) return 0.0f;
    const float stored = blendedAt(sampler, layer, layer.frames, lookupOf(layer, x, y, t, footprint));
    return layer.amplitude * (stored - layer.midStored);
}

std::array<float, 2> sampleLayerShift(const WaterSampler& sampler, const SampledLayer& layer, float x, float y, float t,
                                      float footprint) {
    if (!layer.choppy() || layer.frames.empty() || layer.frames[0].empty()) return {0.0f, 0.0f};
    const LayerLookup l = lookupOf(layer, x, y, t, footprint);
    const float scale = layer.choppiness * layer.amplitude;  // the shader's uLayerChop * uLayerXform.w
    return {scale * blendedAt(sampler, layer, layer.shiftX, l), scale * blendedAt(sampler, layer, layer.shiftY, l)};
}

float sampleWaterHeight(const WaterSampler& sampler, float x, float y, float t, float footprint) {
    float height = 0.0f;
    for (const SampledLayer& layer : sampler.layers) height += sampleLayerHeight(sampler, layer, x, y, t, footprint);
    return height;
}

std::array<float, 2> sampleWaterShift(const WaterSampler& sampler, float x, float y, float t, float footprint) {
    std::array<float, 2> shift{0.0f, 0.0f};
    for (const SampledLayer& layer : sampler.layers) {
        if (!layer.choppy()) continue;
        const std::array<float, 2> s = sampleLayerShift(sampler, layer, x, y, t, footprint);
        shift[0] += s[0];
        shift[1] += s[1];
    }
    return shift;
}

bool isChoppy(const WaterSampler& sampler) {
    return std::any_of(sampler.layers.begin(), sampler.layers.end(), [](const SampledLayer& l) { return l.choppy(); });
}

SurfaceHeight sampleSurfaceHeight(const WaterSampler& sampler, float x, float y, float t, float footprint,
                                  const SurfaceSearch& search) {
    SurfaceHeight result;
    result.origin = {x, y};
    if (!isChoppy(sampler)) {
        result.height = sampleWaterHeight(sampler, x, y, t, footprint);
        return result;
    }
    // p in double, the shift read at p in float as the shader reads it: the steps then stop at a float
    // fixed point rather than at the rounding of their own sums.
    const double tolerance = search.tolerance + FLT_EPSILON * std::max(std::abs(x), std::abs(y));
    double px = x, py = y;
    double bestX = px, bestY = py, bestResidual = INFINITY;
    result.converged = false;
    for (int i = 0; i < std::max(search.maxIterations, 1); ++i) {
        const std::array<float, 2> s = sampleWaterShift(sampler, float(px), float(py), t, footprint);
        result.iterations = i + 1;
        // The step p -> (x, y) - shift(p) is exactly the residual (x, y) - (p + shift(p)) at p.
        const double nextX = double(x) - s[0], nextY = double(y) - s[1];
        const double residual = std::hypot(nextX - px, nextY - py);
        if (residual < bestResidual) bestX = px, bestY = py, bestResidual = residual;
        if (residual <= tolerance) {
            result.converged = true;
            break;
        }
        if (!std::isfinite(nextX) || !std::isfinite(nextY)) break;
        px = nextX, py = nextY;
    }
    result.origin = {float(bestX), float(bestY)};
    result.residual = float(bestResidual);
    result.height = sampleWaterHeight(sampler, result.origin[0], result.origin[1], t, footprint);
    return result;
}

}  // namespace heightpack
