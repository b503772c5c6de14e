// Renderer: putting a loaded Scene on the GPU, each chain in the type its file stored it in, with the
// gather atlases where the context can use them, and counting the bytes that takes.
#include <string>

#include "displacement_gl.hpp"
#include "renderer.hpp"
#include "texture_upload.hpp"

namespace heightpack::view {

namespace {

// Trilinear filtering for the bound texture: shading textures seen at a distance must not sparkle.
// The maximum level is raised first: glGenerateMipmap makes levels only up to it, and a texture whose
// filter wants levels that were never made is incomplete and samples as zero.
void enableMipmaps() {
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 1000);
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
}

}  // namespace

void Renderer::releaseLayers() {
    for (const LayerTextures& l : layers_) {
        for (const FrameTextures& f : l.frames) {
            for (GLuint t : {f.packed, f.plain, f.gather, f.shift})
                if (t) glDeleteTextures(1, &t);
        }
    }
    layers_.clear();
}

void Renderer::uploadLayers(const Scene& scene) {
    releaseLayers();
    gatherProblem_.clear();
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    for (const HeightLayer& layer : scene.layers) {
        LayerTextures t;
        for (const HeightFrame& frame : layer.frames) {
            // Packed and gather: nearest, since the shader filters. Plain: GL_LINEAR, the reference.
            FrameTextures f{uploadStoredChain(frame.packed, false, layer.wrap), uploadStoredChain(frame.plain, true, layer.wrap),
                            0, frame.plain.decode};
            if (!frame.shiftX.empty()) f.shift = uploadShiftChain(frame.shiftX, frame.shiftY);
            if (gather_ && gatherProblem_.empty()) {
                const GatherAtlas atlas = buildGatherAtlas(frame.plain, layer.wrap);
                if (atlas.texels.width > maxSize || atlas.texels.height > maxSize) {
                    gatherProblem_ = layer.path + " needs a " + std::to_string(atlas.texels.width) + "x" +
                                     std::to_string(atlas.texels.height) + " gather atlas, over GL_MAX_TEXTURE_SIZE " +
                                     std::to_string(maxSize);
                } else {
                    f.gather = uploadStoredChain(atlas.texels, false, Wrap::Clamp);
                    t.gatherOrigins = atlas.origins;
                    t.gatherSize = glm::vec2(atlas.texels.width, atlas.texels.height);
                }
            }
            t.frames.push_back(f);
        }
        t.levels = static_cast<int>(layer.frames[0].packed.levels.size());
        t.loopPeriod = layer.loopPeriod;
        layers_.push_back(t);
    }
}

void Renderer::upload(const Scene& scene) {
    scene_ = &scene;
    uploadLayers(scene);
    for (GLuint* t : {&normalTexture_, &fresnelTexture_, &foamTexture_})
        if (*t) glDeleteTextures(1, t), *t = 0;
    normalDecode_ = fresnelDecode_ = Normalisation{};
    if (scene.normals) {
        normalTexture_ = uploadStoredChain(scene.normals->levels, true, Wrap::Periodic);
        if (scene.normals->levels.levels.size() == 1) enableMipmaps();
        normalDecode_ = scene.normals->levels.decode;
    }
    if (scene.fresnel) {
        fresnelTexture_ = uploadStoredChain(scene.fresnel->ramp, true, Wrap::Clamp);
        fresnelDecode_ = scene.fresnel->ramp.decode;
    }
    if (scene.foam) {
        foamTexture_ = uploadFloatChain({*scene.foam}, true, Wrap::Periodic);
        enableMipmaps();
    }
    bytes_ = TextureBytes{};
    for (const LayerTextures& l : layers_) {
        for (const FrameTextures& f : l.frames) {
            bytes_.packed += view::textureBytes(f.packed);
            bytes_.plain += view::textureBytes(f.plain);
            bytes_.gather += view::textureBytes(f.gather);
        }
    }
    bytes_.normals = view::textureBytes(normalTexture_);
    bytes_.fresnel = view::textureBytes(fresnelTexture_);
    bytes_.foam = view::textureBytes(foamTexture_);
    checkGl("Renderer::upload");
}

}  // namespace heightpack::view
