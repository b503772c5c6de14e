// The chapter 18 renderer: the radial grid displaced in the vertex shader from packed height maps, the
// optional render-to-texture combine pass, per-pixel water shading, and the flat tiled view.
#pragma once

#include <epoxy/gl.h>

#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "camera.hpp"
#include "heightpack/core/fresnel.hpp"
#include "heightpack/core/names.hpp"
#include "gl_util.hpp"
#include "scene.hpp"

namespace heightpack::view {

inline glm::vec3 toVec3(const Rgb& c) {
    return {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])};
}

// The vertex shader's height lookups (common.glsl): packed (one nearest RGBA fetch), reference (GL_LINEAR
// on the plain R chain) and gather (textureGather on the plain R chain, GL 4.0), each at level 0
// (bilinear) or between two levels (trilinear, Listing 18-3's bands).
enum class Lookup {
    PackedBilinear = 0, PackedTrilinear = 1, ReferenceBilinear = 2, ReferenceTrilinear = 3, GatherBilinear = 4,
    GatherTrilinear = 5
};
inline bool isGather(Lookup l) { return l == Lookup::GatherBilinear || l == Lookup::GatherTrilinear; }
enum class ViewMode { Shaded = 0, Height = 1, Lod = 2 };

}  // namespace heightpack::view

namespace heightpack {
// --lookup's names (in the enum's order: the panel's list follows it) and the panel's words for them.
template <>
struct NameTable<view::Lookup> {
    static constexpr EnumName<view::Lookup> entries[] = {
        {view::Lookup::PackedBilinear, "bilinear", "packed bilinear"},
        {view::Lookup::PackedTrilinear, "trilinear", "packed trilinear"},
        {view::Lookup::ReferenceBilinear, "reference-bilinear", "reference bilinear (GL_LINEAR)"},
        {view::Lookup::ReferenceTrilinear, "reference-trilinear", "reference trilinear (GL_LINEAR)"},
        {view::Lookup::GatherBilinear, "gather-bilinear", "gather bilinear (textureGather)"},
        {view::Lookup::GatherTrilinear, "gather-trilinear", "gather trilinear (textureGather)"},
    };
};
template <>
struct NameTable<view::ViewMode> {
    static constexpr EnumName<view::ViewMode> entries[] = {
        {view::ViewMode::Shaded, "shaded", "lit water"},
        {view::ViewMode::Height, "height", "grey by height"},
        {view::ViewMode::Lod, "lod", "a colour per mip level"},
    };
};
}  // namespace heightpack

namespace heightpack::view {

// The maps that displace the grid, common.glsl's kMaxLayers: the four tiles of synth --cascades 4 (the
// chapter displaces with two; a cascaded sea needs every tile to be the spectrum once).
constexpr int kMaxLayers = 4;

struct LayerSettings {
    float tileSize = 64.0f;       // metres a tile spans (scale A = 1 / tileSize)
    glm::vec2 scroll{0.01f, 0.004f};  // tiles per second (B)
    float amplitude = 1.0f;       // metres per stored unit
    // For a map with Dx, Dy: the grid point at x moves to x + choppiness * amplitude * D (Tessendorf's
    // x + lambda D; synth's D points toward the crests, so a positive choppiness sharpens them).
    float choppiness = 1.0f;
};

struct Explosion {
    glm::vec2 centre{0.0f};
    float start = 0.0f;
    float strength = 40.0f;
};

// Every parameter the panel edits; defaults are the chapter's where it gives them.
struct RenderSettings {
    // Grid (18.2.3)
    int rings = 256;
    int segments = 256;
    float innerRadius = 0.1f;     // r0 = 10 cm
    float outerRadius = 40000.0f; // r(N-1) = 40 km
    // Sampling (18.2.4)
    Lookup lookup = Lookup::PackedTrilinear;
    glm::vec2 bands{0.3f, 0.7f};
    bool frustumBranch = true;
    glm::vec2 guardBand{1.2f, 2.0f};  // C0, C1
    bool twoPass = false;         // combine into an fp32 texture first (render-to-texture)
    // Water model (18.2.1)
    std::array<LayerSettings, kMaxLayers> layers{LayerSettings{64.0f, {0.010f, 0.004f}, 1.5f},
                                                 LayerSettings{16.0f, {-0.006f, 0.011f}, 0.4f},
                                                 LayerSettings{4.0f, {0.015f, -0.008f}, 0.1f},
                                                 LayerSettings{1.0f, {-0.02f, -0.013f}, 0.025f}};
    float waterLevel = 0.0f;
    // Shading
    ViewMode view = ViewMode::Shaded;
    bool wireframe = false;
    std::array<glm::vec4, 4> normalOctaves{glm::vec4(1.0f / 8, 0.02f, 0.01f, 1.0f), glm::vec4(1.0f / 8, -0.015f, 0.02f, 1.0f),
                                           glm::vec4(1.0f / 2, 0.05f, -0.03f, 0.5f), glm::vec4(1.0f / 2, -0.04f, -0.05f, 0.5f)};
    float ior = 1.333f;
    // The ramp's own defaults (FresnelOptions), for shading without a ramp file.
    glm::vec3 deep = toVec3(FresnelOptions{}.deep), shallow = toVec3(FresnelOptions{}.shallow);
    glm::vec3 sunDirection{0.3f, 0.6f, 0.35f};
    float tilt = 0.08f;
    glm::vec2 foamRange{1.2f, 2.2f};  // H0, Hmax
    float foamTileSize = 4.0f;
    // Maps with synth's baked foam coverage (pack --foam) put foam where it says, instead of above H0;
    // false: every map's foam from the height threshold, as for maps without it.
    bool bakedFoam = true;
    // Perturbations (18.2.5)
    std::vector<Explosion> explosions;
    glm::vec3 explosionShape{1.2f, -6.0f, 0.35f};  // k, w, b of I0 sin(k r + w t) exp(-b t) / r^2
    // Checking aids
    bool tiledView = false;
    glm::ivec2 tiles{3, 3};
    bool seamLines = false;
    glm::vec2 heightRange{-2.0f, 2.0f};  // heights shown as grey in the height view
};

// Time per pass of the last frame measured, in milliseconds: GPU time from timer queries, and wall time
// with the pass bracketed by glFinish. A software renderer (llvmpipe) defers its work past the queries,
// so there only the wall times mean anything; on a GPU the two agree closely.
struct PassTimes {
    double combine = 0.0, water = 0.0, tiled = 0.0;
    double combineWall = 0.0, waterWall = 0.0, tiledWall = 0.0;
    long long vertices = 0;
};

// The angle one pixel row subtends (radians): the level of detail grows with distance times this.
inline float pixelAngle(const Camera& camera, int height) { return glm::radians(camera.fovY) / float(height); }
// Listing 18-1's ring radii r(i) = a0 + a1 i^4, as (a0, a1), from the inner and outer radius.
inline glm::vec2 gridRadius(const RenderSettings& s) {
    return {s.innerRadius, (s.outerRadius - s.innerRadius) / std::pow(float(s.rings - 1), 4.0f)};
}

// Bytes on the GPU of the loaded textures, as GL reports them (texture_upload.hpp), by what they hold.
struct TextureBytes {
    long long packed = 0;   // 4-neighbour RGBA chains, every frame of every map
    long long plain = 0;    // one-channel chains (the reference lookup)
    long long gather = 0;   // one-channel atlases (the gather lookup), with a 4.0 context only
    long long normals = 0, fresnel = 0, foam = 0;
    long long foamCoverage = 0;  // baked foam coverage (one-channel arrays, every frame of every map with it)
    long long shift = 0;    // packed Dx, Dy chains, every frame of every map with them
    long long total() const { return packed + plain + gather + normals + fresnel + foam + foamCoverage + shift; }
};

class Renderer {
public:
    // Compiles the programs, with the gather lookup where the context is OpenGL 4.0 or newer. Returns false
    // with a message (the shader log) on failure.
    // It also refuses programs whose stages would use more than the 16 samplers a GL 3.3 stage is
    // guaranteed (activeSamplers), so they cannot creep back over it.
    bool init(std::string& error, bool gather);
    // Puts the scene on the GPU. Returns why not (a sequence of more frames than an array texture holds
    // here, GL_MAX_ARRAY_TEXTURE_LAYERS), or empty.
    std::string upload(const Scene& scene);
    // Whether the gather lookup can draw: a 4.0 context, and atlases no larger than GL_MAX_TEXTURE_SIZE.
    // When not, gatherProblem() says why in a few words.
    bool gatherAvailable() const { return gather_ && gatherProblem_.empty(); }
    const std::string& gatherProblem() const { return gatherProblem_; }
    const TextureBytes& textureBytes() const { return bytes_; }
    // The samplers the water program's stages read (the most of any program): at most 16 each.
    const StageSamplers& samplers() const { return waterSamplers_; }
    // What this context allows a stage: GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, GL_MAX_TEXTURE_IMAGE_UNITS.
    const StageSamplers& samplerLimits() const { return samplerLimits_; }
    // measure: read timer queries into times(); wallClock: also bracket each pass with glFinish (for
    // --bench; it stalls the pipeline, so the interactive loop does not).
    void render(const Camera& camera, const RenderSettings& settings, float time, int width, int height,
                GLuint framebuffer, bool measure, bool wallClock = false);
    const PassTimes& times() const { return times_; }
    // The combine pass's last output: the height of every grid vertex and its horizontal shift (x, y),
    // three floats a vertex, segment along x, ring along y (ring 0 first), from its RGBA32F target.
    // Meaningless unless the last render was two-pass.
    std::vector<float> gridVertices() const { return combined_.readFloats(3); }
    const Scene* scene() const { return scene_; }
    ~Renderer();

private:
    void buildGrid(int rings, int segments);
    void setCommonUniforms(GLuint program, const Camera& camera, const RenderSettings& s, float time, int height);
    void bindLayers(GLuint program, const RenderSettings& s, float time);

    GLuint waterProgram_ = 0, combineProgram_ = 0, tiledProgram_ = 0, skyProgram_ = 0;
    GLuint gridVao_ = 0, gridVbo_ = 0, gridIbo_ = 0, emptyVao_ = 0;
    GLsizei gridIndexCount_ = 0;
    int gridRings_ = 0, gridSegments_ = 0;
    // A map's textures: GL_TEXTURE_2D_ARRAYs holding frame f of a sequence in layer f, so the shader reads
    // this frame and the next through one sampler (common.glsl's uLayerFrame picks the layers).
    struct LayerTextures {
        GLuint packed = 0, plain = 0, gather = 0;
        GLuint shift = 0;                   // Dx, Dy, two layers a frame (shift_gl.hpp), or 0
        // Per frame: sampled texels to the file's values. heights: the same for the packed and plain
        // chains and the atlas; shift, foam: for Dx, Dy and the coverage (an array texture's layers share
        // its type and normalisation; an EXR's go up as floats).
        struct FrameDecode {
            Normalisation heights, shift, foam;
        };
        std::vector<FrameDecode> decode;
        int frames = 1;
        GLuint foamCoverage = 0;            // every frame's baked foam, one array layer each (foam_gl.hpp), or 0
        int levels = 0;
        double loopPeriod = 0.0;
        std::vector<GatherAtlas::Origin> gatherOrigins;  // the same for every frame: they share a size
        glm::vec2 gatherSize{1.0f};
        // The texture the shader's uHeights reads for this lookup: the packed chain, the plain chain or
        // the gather atlas (0 where the context has none).
        GLuint heights(Lookup lookup) const;
    };
    std::vector<LayerTextures> layers_;
    void releaseLayers();
    std::string uploadLayers(const Scene& scene);
    GLuint normalTexture_ = 0, fresnelTexture_ = 0, foamTexture_ = 0, dummyTexture_ = 0, dummyArray_ = 0, zeroShift_ = 0, zeroCoverage_ = 0;
    Normalisation normalDecode_, fresnelDecode_;
    bool gather_ = false;
    std::string gatherProblem_;
    TextureBytes bytes_;
    StageSamplers waterSamplers_, samplerLimits_;
    RenderTarget combined_;
    GLuint queries_[3] = {0, 0, 0};
    PassTimes times_;
    const Scene* scene_ = nullptr;
};

}  // namespace heightpack::view
