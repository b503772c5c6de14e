// Renderer: putting a loaded Scene on the GPU, each chain in the type its file stored it in, a sequence's
// frames as the layers of one array texture, with the gather atlases where the context can use them, and
// counting the bytes that takes.
#include <string>

#include "shift_gl.hpp"
#include "foam_gl.hpp"
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
    for (const LayerTextures& l : layers_)
        for (GLuint t : {l.packed, l.plain, l.gather, l.shift, l.foamCoverage})
            if (t) glDeleteTextures(1, &t);
    layers_.clear();
}

std::string Renderer::uploadLayers(const Scene& scene) {
    releaseLayers();
    gatherProblem_.clear();
    GLint maxSize = 0, maxLayers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    for (const HeightLayer& layer : scene.layers) {
        // Every frame of a map in one array texture (and Dx, Dy in two layers a frame of another).
        const long long layersNeeded = static_cast<long long>(layer.frames.size()) * (layer.horizontal ? 2 : 1);
        if (layersNeeded > maxLayers)
            return layer.path + ": " + std::to_string(layer.frames.size()) + " frames need " + std::to_string(layersNeeded) +
                   " array layers, over GL_MAX_ARRAY_TEXTURE_LAYERS " + std::to_string(maxLayers) + " here";
        LayerTextures t;
        std::vector<const UploadChain*> packed, plain;
        for (const HeightFrame& frame : layer.frames) {
            packed.push_back(&frame.packed);
            plain.push_back(&frame.plain);
            // Dx and Dy of one file share a decode: an EXR's are floats, an array's layers one normalisation.
            t.decode.push_back({frame.plain.decode, frame.shiftX.decode, frame.foam.decode});
        }
        // Packed and gather: nearest, since the shader filters. Plain: GL_LINEAR, the reference.
        t.packed = uploadStoredArray(packed, false, layer.wrap);
        t.plain = uploadStoredArray(plain, true, layer.wrap);
        t.shift = uploadShiftArray(layer);
        if (gather_ && gatherProblem_.empty()) {
            std::vector<GatherAtlas> atlases;
            // A block chain's texels are the packing's R (its decoded unit values, the same decode).
            for (const HeightFrame& frame : layer.frames)
                atlases.push_back(buildGatherAtlas(frame.plain.isBlock() ? firstChannel(frame.packed) : frame.plain, layer.wrap));
            const UploadChain& texels = atlases[0].texels;
            if (texels.width > maxSize || texels.height > maxSize) {
                gatherProblem_ = layer.path + " needs a " + std::to_string(texels.width) + "x" + std::to_string(texels.height) +
                                 " gather atlas, over GL_MAX_TEXTURE_SIZE " + std::to_string(maxSize);
            } else {
                std::vector<const UploadChain*> chains;
                for (const GatherAtlas& a : atlases) chains.push_back(&a.texels);
                t.gather = uploadStoredArray(chains, false, Wrap::Clamp);
                t.gatherOrigins = atlases[0].origins;  // the same for every frame: they share a size
                t.gatherSize = glm::vec2(texels.width, texels.height);
            }
        }
        t.frames = static_cast<int>(layer.frames.size());
        t.foamCoverage = uploadFoamCoverage(layer);
        t.levels = static_cast<int>(layer.frames[0].packed.levels.size());
        t.loopPeriod = layer.loopPeriod;
        layers_.push_back(t);
    }
    return {};
}

std::string Renderer::upload(const Scene& scene) {
    scene_ = &scene;
    if (std::string problem = uploadLayers(scene); !problem.empty()) {
        releaseLayers();
        return problem;
    }
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
        bytes_.packed += view::textureBytes(l.packed, GL_TEXTURE_2D_ARRAY);
        bytes_.plain += view::textureBytes(l.plain, GL_TEXTURE_2D_ARRAY);
        bytes_.gather += view::textureBytes(l.gather, GL_TEXTURE_2D_ARRAY);
    }
    bytes_.normals = view::textureBytes(normalTexture_);
    bytes_.fresnel = view::textureBytes(fresnelTexture_);
    bytes_.foam = view::textureBytes(foamTexture_);
    for (const LayerTextures& l : layers_) {
        bytes_.foamCoverage += view::textureBytes(l.foamCoverage, GL_TEXTURE_2D_ARRAY);
        bytes_.shift += view::textureBytes(l.shift, GL_TEXTURE_2D_ARRAY);
    }
    checkGl("Renderer::upload");
    return {};
}

}  // namespace heightpack::view
