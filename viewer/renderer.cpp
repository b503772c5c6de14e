#include "renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>
#include <glm/gtc/type_ptr.hpp>

#include "shift_gl.hpp"
#include "foam_gl.hpp"
#include "shaders.hpp"
#include "texture_upload.hpp"

namespace heightpack::view {

namespace {

// Texture units: per map its heights (the lookup's form of them), its Dx, Dy and its baked foam coverage,
// all array textures holding every frame; then the shading textures and the combine target. The vertex
// stage reads the heights, the shifts and the combine target (9 samplers), the fragment stage the heights,
// the shifts, the coverage and three shading textures (15): within the 16 every GL 3.3 implementation
// offers a stage (init checks). The units themselves run to 17, within GL 3.3's 48 combined.
enum Unit {
    kHeights0 = 0, kShifts0 = kHeights0 + kMaxLayers, kFoamCoverage0 = kShifts0 + kMaxLayers,
    kNormal = kFoamCoverage0 + kMaxLayers, kFresnel, kFoam, kCombined, kTiledMap
};

constexpr int kSamplersPerStage = 16;  // GL_MAX_TEXTURE_IMAGE_UNITS / GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS in GL 3.3

constexpr int kMaxGatherLevels = 16;  // common.glsl's kMaxLevels: a 32768-texel side

void set(GLuint p, const char* name, int v) { glUniform1i(glGetUniformLocation(p, name), v); }
void set(GLuint p, const char* name, float v) { glUniform1f(glGetUniformLocation(p, name), v); }
void set(GLuint p, const char* name, glm::vec2 v) { glUniform2fv(glGetUniformLocation(p, name), 1, glm::value_ptr(v)); }
void set(GLuint p, const char* name, glm::vec3 v) { glUniform3fv(glGetUniformLocation(p, name), 1, glm::value_ptr(v)); }
void set(GLuint p, const char* name, const glm::mat4& m) {
    glUniformMatrix4fv(glGetUniformLocation(p, name), 1, GL_FALSE, glm::value_ptr(m));
}

// "name[k]", without string concatenation (GCC 12 warns falsely about it at -O3).
std::string indexed(const char* name, int k) {
    char text[64];
    std::snprintf(text, sizeof text, "%s[%d]", name, k);
    return text;
}

// Wall time of a pass: everything before it finished first, everything in it finished after.
struct WallClock {
    bool on;
    std::chrono::steady_clock::time_point start;
    explicit WallClock(bool measure) : on(measure) {
        if (on) glFinish(), start = std::chrono::steady_clock::now();
    }
    double stop() const {
        if (!on) return 0.0;
        glFinish();
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
};

// The GPU time a finished GL_TIME_ELAPSED query measured, in milliseconds (waits for the result).
double queryMilliseconds(GLuint query) {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
    return ns / 1e6;
}

void bindTexture(int unit, GLuint texture) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, texture);
}

}  // namespace

bool Renderer::init(std::string& error, bool gather) {
    using namespace shaders;
    gather_ = gather;
    // textureGather is GLSL 4.00; a 3.3 context compiles the same shaders without it.
    const std::string preamble = gather ? "#version 400 core\n#define HEIGHTPACK_GATHER 1\n"
                                        : "#version 330 core\n#define HEIGHTPACK_GATHER 0\n";
    waterProgram_ = buildProgram("water", preamble, kCommonGlsl, kGridVert, kWaterFrag, error);
    if (!waterProgram_) return false;
    combineProgram_ = buildProgram("combine", preamble, kCommonGlsl, kCombineVert, kCombineFrag, error);
    if (!combineProgram_) return false;
    tiledProgram_ = buildProgram("tiled", preamble, kCommonGlsl, kCombineVert, kTiledFrag, error);
    if (!tiledProgram_) return false;
    skyProgram_ = buildProgram("sky", preamble, kCommonGlsl, kCombineVert, kSkyFrag, error);
    if (!skyProgram_) return false;
    glGenVertexArrays(1, &emptyVao_);
    glGenQueries(3, queries_);
    // Bound to unused samplers so every sampler has a complete texture.
    dummyTexture_ = uploadFloatChain({Image(1, 1, 4, 0.0f)}, false, Wrap::Periodic);
    const UploadChain dummy = storeFloats({Image(1, 1, 4, 0.0f)});
    dummyArray_ = uploadStoredArray({&dummy}, false, Wrap::Periodic);
    zeroShift_ = uploadZeroShift();
    HeightLayer none;  // a 1x1 one-frame array of no foam, bound to the samplers of maps without it
    none.foam = true;
    none.frames.resize(1);
    none.frames[0].foam = storeFloats({Image(1, 1, 1, 0.0f)});
    zeroCoverage_ = uploadFoamCoverage(none);
    glGetIntegerv(GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, &samplerLimits_.vertex);
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &samplerLimits_.fragment);
    for (auto [name, program] : {std::pair{"water", waterProgram_}, std::pair{"combine", combineProgram_},
                                 std::pair{"tiled", tiledProgram_}, std::pair{"sky", skyProgram_}}) {
        const StageSamplers s = activeSamplers(program);
        if (s.vertex > kSamplersPerStage || s.fragment > kSamplersPerStage) {
            error = std::string("program ") + name + " reads " + std::to_string(s.vertex) + " samplers in its vertex stage and " +
                    std::to_string(s.fragment) + " in its fragment stage, over the " + std::to_string(kSamplersPerStage) +
                    " OpenGL 3.3 guarantees a stage";
            return false;
        }
        if (std::string(name) == "water") waterSamplers_ = s;
    }
    checkGl("Renderer::init");
    return true;
}

Renderer::~Renderer() {
    releaseLayers();
    for (GLuint t : {normalTexture_, fresnelTexture_, foamTexture_, dummyTexture_, dummyArray_, zeroShift_, zeroCoverage_})
        if (t) glDeleteTextures(1, &t);
    combined_.destroy();
    if (gridVao_) glDeleteVertexArrays(1, &gridVao_);
    if (gridVbo_) glDeleteBuffers(1, &gridVbo_);
    if (gridIbo_) glDeleteBuffers(1, &gridIbo_);
    if (emptyVao_) glDeleteVertexArrays(1, &emptyVao_);
    glDeleteQueries(3, queries_);
    for (GLuint p : {waterProgram_, combineProgram_, tiledProgram_, skyProgram_})
        if (p) glDeleteProgram(p);
}

void Renderer::buildGrid(int rings, int segments) {
    if (rings == gridRings_ && segments == gridSegments_) return;
    gridRings_ = rings;
    gridSegments_ = segments;
    // Listing 18-1's vertex: (cos, sin, ring index); the shader makes r = a0 + a1 i^4.
    std::vector<float> vertices;
    vertices.reserve(static_cast<size_t>(rings) * segments * 3);
    for (int i = 0; i < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const double angle = 2.0 * 3.14159265358979323846 * j / segments;
            vertices.insert(vertices.end(), {float(std::cos(angle)), float(std::sin(angle)), float(i)});
        }
    }
    std::vector<GLuint> indices;
    for (int i = 0; i + 1 < rings; ++i) {
        for (int j = 0; j < segments; ++j) {
            const GLuint a = i * segments + j, b = i * segments + (j + 1) % segments;
            const GLuint c = a + segments, d = b + segments;
            indices.insert(indices.end(), {a, c, b, b, c, d});
        }
    }
    gridIndexCount_ = static_cast<GLsizei>(indices.size());
    if (!gridVao_) {
        glGenVertexArrays(1, &gridVao_);
        glGenBuffers(1, &gridVbo_);
        glGenBuffers(1, &gridIbo_);
    }
    glBindVertexArray(gridVao_);
    glBindBuffer(GL_ARRAY_BUFFER, gridVbo_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)), vertices.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, gridIbo_);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(GLuint)), indices.data(),
                 GL_STATIC_DRAW);
    glBindVertexArray(0);
    combined_.create(segments, rings, GL_RGBA32F);  // height, and the horizontal shift of choppy maps
    checkGl("Renderer::buildGrid");
}

GLuint Renderer::LayerTextures::heights(Lookup lookup) const {
    if (isGather(lookup)) return gather;
    return lookup == Lookup::ReferenceBilinear || lookup == Lookup::ReferenceTrilinear ? plain : packed;
}

// Every per-map texture is bound here, and only here: map k's heights in the form the lookup reads, its
// Dx, Dy and its baked foam coverage, with the frames this time shows. A map that is absent, or lacks one
// of them, gets a stand-in of zeros, so every sampler has a complete texture.
void Renderer::bindLayers(GLuint program, const RenderSettings& s, float time) {
    GLint heights[kMaxLayers], shifts[kMaxLayers], coverage[kMaxLayers];
    float coverageOn[kMaxLayers];
    for (int k = 0; k < kMaxLayers; ++k) {
        const bool has = k < int(layers_.size());
        const LayerTextures* l = has ? &layers_[size_t(k)] : nullptr;
        heights[k] = kHeights0 + k, shifts[k] = kShifts0 + k, coverage[k] = kFoamCoverage0 + k;
        const GLuint lookupTexture = has ? l->heights(s.lookup) : 0;
        bindArrayTexture(heights[k], lookupTexture ? lookupTexture : dummyArray_);
        bindArrayTexture(shifts[k], has && l->shift ? l->shift : zeroShift_);
        const bool baked = has && l->foamCoverage && s.bakedFoam;
        bindArrayTexture(coverage[k], baked ? l->foamCoverage : zeroCoverage_);
        coverageOn[k] = baked ? 1.0f : 0.0f;
        // A sequence plays its loop: frame f covers [f, f+1) * period / frames, blended into the next.
        int current = 0, next = 0;
        float blend = 0.0f;
        if (has && l->frames > 1) {
            const double frames = double(l->frames);
            double position = std::fmod(time / l->loopPeriod * frames, frames);
            if (position < 0) position += frames;
            current = static_cast<int>(position) % l->frames;
            next = (current + 1) % l->frames;
            blend = static_cast<float>(position - std::floor(position));
        }
        glUniform2i(glGetUniformLocation(program, indexed("uLayerFrame", k).c_str()), current, next);
        glUniform1f(glGetUniformLocation(program, indexed("uLayerBlend", k).c_str()), blend);
        const LayerTextures::FrameDecode identity, &a = has ? l->decode[size_t(current)] : identity,
                                                   &b = has ? l->decode[size_t(next)] : identity;
        using D = LayerTextures::FrameDecode;
        for (auto [name, part] : {std::pair{"uLayerDecode", &D::heights}, {"uShiftDecode", &D::shift}, {"uCoverageDecode", &D::foam}})
            glUniform4f(glGetUniformLocation(program, indexed(name, k).c_str()), (a.*part).offset, (a.*part).scale,
                        (b.*part).offset, (b.*part).scale);
    }
    // A program without one of these arrays (the combine pass reads no coverage) finds location -1: a no-op.
    glUniform1iv(glGetUniformLocation(program, "uHeights"), kMaxLayers, heights);
    glUniform1iv(glGetUniformLocation(program, "uShifts"), kMaxLayers, shifts);
    glUniform1iv(glGetUniformLocation(program, "uFoamCoverage"), kMaxLayers, coverage);
    glUniform1fv(glGetUniformLocation(program, "uCoverageOn"), kMaxLayers, coverageOn);
}

void Renderer::setCommonUniforms(GLuint p, const Camera& camera, const RenderSettings& s, float time, int height) {
    const int count = std::min<int>(kMaxLayers, static_cast<int>(layers_.size()));
    set(p, "uLayerCount", count);
    for (int k = 0; k < kMaxLayers; ++k) {
        const LayerSettings& l = s.layers[k];
        const glm::vec4 xform(1.0f / l.tileSize, l.scroll.x, l.scroll.y, l.amplitude);
        glUniform4fv(glGetUniformLocation(p, indexed("uLayerXform", k).c_str()), 1, glm::value_ptr(xform));
        const bool has = k < count;
        const glm::vec2 stored(has ? scene_->layers[k].midStored : 0.0f,
                               has && scene_->layers[k].wrap == Wrap::Clamp ? 1.0f : 0.0f);
        glUniform2fv(glGetUniformLocation(p, indexed("uLayerStored", k).c_str()), 1, glm::value_ptr(stored));
        glUniform1i(glGetUniformLocation(p, indexed("uLayerLevels", k).c_str()), has ? layers_[k].levels : 1);
        const bool choppy = has && scene_->layers[k].horizontal;
        glUniform1f(glGetUniformLocation(p, indexed("uLayerChop", k).c_str()), choppy ? l.choppiness : 0.0f);
        glUniform2i(glGetUniformLocation(p, indexed("uLayerSize", k).c_str()), has ? scene_->layers[k].frames[0].packed.width : 1,
                    has ? scene_->layers[k].frames[0].packed.height : 1);
        if (!has) continue;
        set(p, indexed("uGatherSize", k).c_str(), layers_[k].gatherSize);
        const auto& origins = layers_[k].gatherOrigins;
        for (int l = 0; l < std::min<int>(kMaxGatherLevels, int(origins.size())); ++l)
            glUniform2i(glGetUniformLocation(p, indexed("uGatherOrigin", k * kMaxGatherLevels + l).c_str()), origins[l].x,
                        origins[l].y);
    }
    set(p, "uLookup", static_cast<int>(s.lookup));
    set(p, "uBands", s.bands);
    set(p, "uPixelAngle", pixelAngle(camera, height));
    set(p, "uTime", time);
    set(p, "uWaterLevel", s.waterLevel);
    set(p, "uGridRadius", gridRadius(s));
    set(p, "uCameraPos", camera.position);
    const int explosions = std::min<int>(8, static_cast<int>(s.explosions.size()));
    set(p, "uExplosionCount", explosions);
    for (int e = 0; e < explosions; ++e) {
        const Explosion& x = s.explosions[e];
        const glm::vec4 v(x.centre, x.start, x.strength);
        glUniform4fv(glGetUniformLocation(p, indexed("uExplosion", e).c_str()), 1, glm::value_ptr(v));
    }
    set(p, "uExplosionShape", s.explosionShape);
    bindLayers(p, s, time);
}

void Renderer::render(const Camera& camera, const RenderSettings& s, float time, int width, int height,
                      GLuint framebuffer, bool measure, bool wallClock) {
    times_ = PassTimes{};
    const float aspect = float(width) / float(height);
    const glm::mat4 viewProj = camera.projection(aspect) * camera.view();
    if (!s.tiledView) buildGrid(s.rings, s.segments);  // first: it binds framebuffers of its own
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, width, height);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    if (s.tiledView) {
        if (layers_.empty()) return;
        const WallClock wall(measure && wallClock);
        if (measure) glBeginQuery(GL_TIME_ELAPSED, queries_[2]);
        glUseProgram(tiledProgram_);
        bindArrayTexture(kTiledMap, layers_[0].plain);  // frame 0
        set(tiledProgram_, "uMap", int(kTiledMap));
        set(tiledProgram_, "uTiles", glm::vec2(s.tiles));
        set(tiledProgram_, "uRange", glm::vec2(scene_->layers[0].minStored, scene_->layers[0].maxStored));
        const Normalisation d = layers_[0].decode[0].heights;
        set(tiledProgram_, "uDecode", glm::vec2(d.offset, d.scale));
        set(tiledProgram_, "uSeamLines", int(s.seamLines));
        // The N x M tiles as large as the window holds them with square texels, centred: a tile keeps its
        // map's shape whatever the window's.
        const UploadChain& map = scene_->layers[0].frames[0].plain;
        const glm::vec2 tile(map.width, map.height), block = glm::vec2(s.tiles) * tile;
        const float fit = std::min(float(width) / block.x, float(height) / block.y);
        set(tiledProgram_, "uTilePixels", tile * fit);
        set(tiledProgram_, "uOrigin", 0.5f * (glm::vec2(width, height) - block * fit));
        set(tiledProgram_, "uViewport", glm::vec2(width, height));
        glDisable(GL_DEPTH_TEST);
        glBindVertexArray(emptyVao_);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        if (measure) {
            glEndQuery(GL_TIME_ELAPSED);
            times_.tiled = queryMilliseconds(queries_[2]);
            times_.tiledWall = wall.stop();
        }
        return;
    }

    if (s.twoPass) {
        // Pass one: the height of every grid vertex into an fp32 texture.
        const WallClock wall(measure && wallClock);
        if (measure) glBeginQuery(GL_TIME_ELAPSED, queries_[0]);
        glBindFramebuffer(GL_FRAMEBUFFER, combined_.framebuffer);
        glViewport(0, 0, s.segments, s.rings);
        glDisable(GL_DEPTH_TEST);
        glUseProgram(combineProgram_);
        setCommonUniforms(combineProgram_, camera, s, time, height);
        set(combineProgram_, "uViewProj", viewProj);
        set(combineProgram_, "uFrustumBranch", int(s.frustumBranch));
        set(combineProgram_, "uGuardBand", s.guardBand);
        set(combineProgram_, "uSegments", s.segments);
        set(combineProgram_, "uRings", s.rings);
        glBindVertexArray(emptyVao_);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        if (measure) glEndQuery(GL_TIME_ELAPSED);
        times_.combineWall = wall.stop();
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        glViewport(0, 0, width, height);
    }

    const WallClock wall(measure && wallClock);
    if (measure) glBeginQuery(GL_TIME_ELAPSED, queries_[1]);
    const glm::vec3 sun = glm::normalize(s.sunDirection), sunColour(1.0f, 0.93f, 0.8f);
    if (s.view == ViewMode::Shaded) {
        glDisable(GL_DEPTH_TEST);
        glUseProgram(skyProgram_);
        set(skyProgram_, "uInverseViewProj", glm::inverse(viewProj));
        set(skyProgram_, "uSunDir", sun);
        set(skyProgram_, "uSunColour", sunColour);
        glBindVertexArray(emptyVao_);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glEnable(GL_DEPTH_TEST);
    glUseProgram(waterProgram_);
    setCommonUniforms(waterProgram_, camera, s, time, height);
    set(waterProgram_, "uViewProj", viewProj);
    set(waterProgram_, "uFrustumBranch", int(s.frustumBranch));
    set(waterProgram_, "uGuardBand", s.guardBand);
    set(waterProgram_, "uUseCombined", int(s.twoPass));
    set(waterProgram_, "uCombined", int(kCombined));
    bindTexture(kCombined, combined_.colour);
    set(waterProgram_, "uSegments", s.segments);
    set(waterProgram_, "uView", static_cast<int>(s.view));
    set(waterProgram_, "uHeightRange", s.heightRange);
    set(waterProgram_, "uHasNormalMap", int(normalTexture_ != 0));
    set(waterProgram_, "uNormalMap", int(kNormal));
    bindTexture(kNormal, normalTexture_ ? normalTexture_ : dummyTexture_);
    set(waterProgram_, "uNormalGreen", scene_ && scene_->normals ? scene_->normals->greenSign : 1.0f);
    set(waterProgram_, "uNormalDecode", glm::vec2(normalDecode_.offset, normalDecode_.scale));
    for (int k = 0; k < 4; ++k)
        glUniform4fv(glGetUniformLocation(waterProgram_, indexed("uNormalOctave", k).c_str()), 1,
                     glm::value_ptr(s.normalOctaves[k]));
    set(waterProgram_, "uHasFresnel", int(fresnelTexture_ != 0));
    set(waterProgram_, "uFresnel", int(kFresnel));
    bindTexture(kFresnel, fresnelTexture_ ? fresnelTexture_ : dummyTexture_);
    set(waterProgram_, "uFresnelIndexScale", scene_ && scene_->fresnel ? scene_->fresnel->indexScale : 1.0f);
    set(waterProgram_, "uFresnelDecode", glm::vec2(fresnelDecode_.offset, fresnelDecode_.scale));
    set(waterProgram_, "uIor", s.ior);
    set(waterProgram_, "uDeep", s.deep);
    set(waterProgram_, "uShallow", s.shallow);
    set(waterProgram_, "uSunDir", sun);
    set(waterProgram_, "uSunColour", sunColour);
    set(waterProgram_, "uTilt", s.tilt);
    set(waterProgram_, "uFoamRange", s.foamRange);
    set(waterProgram_, "uHasFoam", int(foamTexture_ != 0));
    set(waterProgram_, "uFoam", int(kFoam));
    bindTexture(kFoam, foamTexture_ ? foamTexture_ : dummyTexture_);
    set(waterProgram_, "uFoamScale", 1.0f / s.foamTileSize);
    glPolygonMode(GL_FRONT_AND_BACK, s.wireframe ? GL_LINE : GL_FILL);
    glBindVertexArray(gridVao_);
    glDrawElements(GL_TRIANGLES, gridIndexCount_, GL_UNSIGNED_INT, nullptr);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glBindVertexArray(0);
    times_.vertices = static_cast<long long>(s.rings) * s.segments;
    if (measure) {
        glEndQuery(GL_TIME_ELAPSED);
        times_.water = queryMilliseconds(queries_[1]);
        times_.waterWall = wall.stop();
        if (s.twoPass) times_.combine = queryMilliseconds(queries_[0]);
    }
    checkGl("Renderer::render");
}

}  // namespace heightpack::view
