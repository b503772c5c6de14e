// Mirrors viewer/shaders/common.glsl line by line, in float: the shader's fract, mod and mix are written
// out as GLSL defines them, so a change to one side shows up in the viewer test that compares the two.
#include "heightpack/core/water_sampler.hpp"

#include <algorithm>
#include <cmath>

namespace heightpack {
namespace {

float fract(float x) { return x - std::floor(x); }
float glslMod(float x, float y) { return x - y * std::floor(x / y); }
float mix(float a, float b, float t) { return a * (1.0f - t) + b * t; }

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

// layerHeight: one level below the band, the next above it, a blend inside it.
float chainHeight(const WaterSampler& sampler, const std::vector<Image>& chain, Wrap wrap, float u, float v, float lod) {
    const int last = static_cast<int>(chain.size()) - 1;
    if (sampler.filter == LevelFilter::Bilinear) return packedBilinear(chain[0], u, v, wrap);
    lod = std::clamp(lod, 0.0f, static_cast<float>(last));
    const int level = std::min(static_cast<int>(std::floor(lod)), last);
    const float fr = lod - static_cast<float>(level);
    const auto [low, high] = sampler.bands;
    if (level == last || fr < low) return packedBilinear(chain[level], u, v, wrap);
    const float coarse = packedBilinear(chain[level + 1], u, v, wrap);
    if (fr > high) return coarse;
    const float fine = packedBilinear(chain[level], u, v, wrap);
    return mix(fine, coarse, (fr - low) / (high - low));
}

}  // namespace

float midStoredOf(const std::vector<std::vector<Image>>& frames) {
    if (frames.empty() || frames[0].empty() || frames[0].back().empty()) return 0.0f;
    return frames[0].back().pixels[0];
}

float packedBilinear(const Image& level, float u, float v, Wrap wrap) {
    const bool clampMode = wrap == Wrap::Clamp;
    const float width = static_cast<float>(level.width), height = static_cast<float>(level.height);
    float px = (clampMode ? std::clamp(u, 0.0f, 1.0f) : fract(u)) * width - 0.5f;
    float py = (clampMode ? std::clamp(v, 0.0f, 1.0f) : fract(v)) * height - 0.5f;
    if (clampMode) {
        px = std::clamp(px, 0.0f, width - 1.0f);
        py = std::clamp(py, 0.0f, height - 1.0f);
    }
    const float ix = std::floor(px), iy = std::floor(py);
    const float fx = px - ix, fy = py - iy;
    const int x = static_cast<int>(glslMod(ix, width)), y = static_cast<int>(glslMod(iy, height));
    const float r = level.at(x, y, 0), g = level.at(x, y, 1), b = level.at(x, y, 2), a = level.at(x, y, 3);
    return mix(mix(r, g, fx), mix(b, a, fx), fy);
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
    float stored = chainHeight(sampler, layer.frames[pick.current], layer.wrap, u, v, lod);
    if (pick.blend > 0.0f) stored = mix(stored, chainHeight(sampler, layer.frames[pick.next], layer.wrap, u, v, lod), pick.blend);
    return layer.amplitude * (stored - layer.midStored);
}

float sampleWaterHeight(const WaterSampler& sampler, float x, float y, float t, float footprint) {
    float height = 0.0f;
    for (const SampledLayer& layer : sampler.layers) height += sampleLayerHeight(sampler, layer, x, y, t, footprint);
    return height;
}

}  // namespace heightpack
