// Mirrors viewer/shaders/common.glsl: the level of detail and the texture coordinates in float, in the
// shader's order (their rounding is what separates the two at a distance), the lookups through the
// packed-chain mirrors of pack.hpp. The viewer test compares the two on rendered grid vertices.
#include "heightpack/core/water_sampler.hpp"

#include <algorithm>
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

float sampleLayerHeight(const WaterSampler& sampler, const SampledLayer& layer, float x, float y, float t, float footprint) {
    if (layer.frames.empty() || layer.frames[0].empty()) return 0.0f;
    const float lod = layerLevelOfDetail(layer, footprint);
    const float scale = 1.0f / layer.tileSize;
    const float u = x * scale + layer.scroll[0] * t, v = y * scale + layer.scroll[1] * t;
    const FramePick pick = pickFrames(layer, t);
    auto chainHeight = [&](const std::vector<Image>& chain) {
        return sampler.filter == LevelFilter::Bilinear ? samplePackedBilinear(chain[0], u, v, layer.wrap)
                                                       : samplePackedTrilinear(chain, u, v, lod, layer.wrap, sampler.bands);
    };
    float stored = chainHeight(layer.frames[pick.current]);
    if (pick.blend > 0.0f) stored += (chainHeight(layer.frames[pick.next]) - stored) * pick.blend;
    return layer.amplitude * (stored - layer.midStored);
}

float sampleWaterHeight(const WaterSampler& sampler, float x, float y, float t, float footprint) {
    float height = 0.0f;
    for (const SampledLayer& layer : sampler.layers) height += sampleLayerHeight(sampler, layer, x, y, t, footprint);
    return height;
}

}  // namespace heightpack
