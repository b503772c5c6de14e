#include "texture_upload.hpp"

#include <cassert>
#include <cstdint>
#include <string_view>

#include "gl_util.hpp"

namespace heightpack::view {

namespace {

struct GlFormat {
    GLenum internal, format, type;
};

// ASTC's GL formats (GL_KHR_texture_compression_astc_ldr): RGBA blocks of one size, LDR or HDR alike.
constexpr GLenum kAstc4x4 = 0x93B0, kAstc6x6 = 0x93B4, kAstc8x8 = 0x93B7;

GLenum blockInternalFormat(const UploadChain& chain) {
    switch (pixelTypeOf(chain.blockFormat)) {
        case PixelType::Astc4x4:
        case PixelType::AstcHdr4x4: return kAstc4x4;
        case PixelType::Astc6x6:
        case PixelType::AstcHdr6x6: return kAstc6x6;
        case PixelType::Astc8x8:
        case PixelType::AstcHdr8x8: return kAstc8x8;
        default: return chain.channels == 1 ? GLenum(GL_COMPRESSED_RED_RGTC1) : GLenum(GL_COMPRESSED_RG_RGTC2);
    }
}

GlFormat glFormatOf(const UploadChain& chain) {
    const int channels = chain.channels;
    const ComponentKind kind = chain.kind;
    static const GLenum formats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
    static const GLenum float32[] = {GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F};
    static const GLenum float16[] = {GL_R16F, GL_RG16F, GL_RGB16F, GL_RGBA16F};
    static const GLenum unorm16[] = {GL_R16, GL_RG16, GL_RGB16, GL_RGBA16};
    static const GLenum snorm16[] = {GL_R16_SNORM, GL_RG16_SNORM, GL_RGB16_SNORM, GL_RGBA16_SNORM};
    const int c = channels - 1;
    switch (kind) {
        case ComponentKind::Float16: return {float16[c], formats[c], GL_HALF_FLOAT};
        case ComponentKind::Unorm16: return {unorm16[c], formats[c], GL_UNSIGNED_SHORT};
        case ComponentKind::Snorm16: return {snorm16[c], formats[c], GL_SHORT};
        case ComponentKind::Block: return {blockInternalFormat(chain), formats[c], 0};
        case ComponentKind::Float32: break;
    }
    return {float32[c], formats[c], GL_FLOAT};
}

// Bytes of a block level: whole blocks, a level smaller than a block takes one (as the files store it).
GLsizei blockLevelBytes(const UploadChain& chain, int level) {
    const BlockShape b = blockShapeOf(chain.blockFormat);
    const long long blocks = static_cast<long long>((chain.levelWidth(level) + b.side - 1) / b.side) *
                             ((chain.levelHeight(level) + b.side - 1) / b.side);
    return static_cast<GLsizei>(blocks * b.bytes);
}

// ASTC normals hold y in alpha (x in R, G and B): the shaders read .rg, as from BC5.
void swizzleAstcNormals(const UploadChain& chain, GLenum target) {
    if (chain.isAstc() && chain.channels == 2) glTexParameteri(target, GL_TEXTURE_SWIZZLE_G, GL_ALPHA);
}

void setLevel(const UploadChain& chain, const GlFormat& f, int level) {
    const GLint internal = static_cast<GLint>(f.internal);
    const int w = chain.levelWidth(level), h = chain.levelHeight(level);
    const std::uint8_t* data = chain.levels[size_t(level)].data();
    if (chain.isBlock()) {
        assert(chain.levels[size_t(level)].size() == size_t(blockLevelBytes(chain, level)));
        glCompressedTexImage2D(GL_TEXTURE_2D, level, f.internal, w, h, 0, blockLevelBytes(chain, level), data);
    } else {
        glTexImage2D(GL_TEXTURE_2D, level, internal, w, h, 0, f.format, f.type, data);
    }
}

}  // namespace

GLuint uploadStoredChain(const UploadChain& chain, bool linear, Wrap wrap) {
    const GlFormat f = glFormatOf(chain);
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // rows are tightly packed: a one-channel 16-bit row may be 2 bytes
    for (size_t level = 0; level < chain.levels.size(); ++level) setLevel(chain, f, int(level));
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    const bool mips = chain.levels.size() > 1;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, static_cast<GLint>(chain.levels.size() - 1));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                    linear ? (mips ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR) : (mips ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, linear ? GL_LINEAR : GL_NEAREST);
    const GLint mode = wrap == Wrap::Periodic ? GL_REPEAT : GL_CLAMP_TO_EDGE;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, mode);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, mode);
    swizzleAstcNormals(chain, GL_TEXTURE_2D);
    checkGl("uploadStoredChain");
    return texture;
}

GLuint uploadFloatChain(const std::vector<Image>& levels, bool linear, Wrap wrap) {
    return uploadStoredChain(storeFloats(levels), linear, wrap);
}

GLuint uploadStoredArray(const std::vector<const UploadChain*>& chains, bool linear, Wrap wrap) {
    assert(!chains.empty());
    const UploadChain& first = *chains[0];
    const GlFormat f = glFormatOf(first);
    const GLsizei layers = static_cast<GLsizei>(chains.size());
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D_ARRAY, texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (size_t level = 0; level < first.levels.size(); ++level) {
        const int w = first.levelWidth(int(level)), h = first.levelHeight(int(level));
        const GLsizei blockBytes = first.isBlock() ? blockLevelBytes(first, int(level)) : 0;
        if (first.isBlock()) {
            // One compressed image of every layer, each layer's blocks in turn (GL's layout of a 3D image).
            std::vector<std::uint8_t> all;
            for (const UploadChain* c : chains) all.insert(all.end(), c->levels[level].begin(), c->levels[level].end());
            glCompressedTexImage3D(GL_TEXTURE_2D_ARRAY, static_cast<GLint>(level), f.internal, w, h, layers, 0,
                                   blockBytes * layers, all.data());
        } else {
            glTexImage3D(GL_TEXTURE_2D_ARRAY, static_cast<GLint>(level), static_cast<GLint>(f.internal), w, h, layers, 0,
                         f.format, f.type, nullptr);
        }
        for (GLsizei layer = 0; layer < layers && !first.isBlock(); ++layer) {
            const UploadChain& c = *chains[size_t(layer)];
            assert(c.kind == first.kind && c.channels == first.channels && c.levels.size() == first.levels.size() &&
                   c.width == first.width && c.height == first.height);
            glTexSubImage3D(GL_TEXTURE_2D_ARRAY, static_cast<GLint>(level), 0, 0, layer, w, h, 1, f.format, f.type,
                            c.levels[level].data());
        }
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    const bool mips = first.levels.size() > 1;
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, static_cast<GLint>(first.levels.size() - 1));
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER,
                    linear ? (mips ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR) : (mips ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST));
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, linear ? GL_LINEAR : GL_NEAREST);
    const GLint mode = wrap == Wrap::Periodic ? GL_REPEAT : GL_CLAMP_TO_EDGE;
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, mode);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, mode);
    swizzleAstcNormals(first, GL_TEXTURE_2D_ARRAY);
    checkGl("uploadStoredArray");
    return texture;
}

namespace {

bool contextHasExtension(std::string_view wanted) {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i) {
        const auto* name = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
        if (name && std::string_view(name) == wanted) return true;
    }
    return false;
}

}  // namespace

bool contextTakesAstc() { return contextHasExtension("GL_KHR_texture_compression_astc_ldr"); }
bool contextTakesAstcHdr() { return contextHasExtension("GL_KHR_texture_compression_astc_hdr"); }

long long textureBytes(GLuint texture, GLenum target) {
    if (!texture) return 0;
    glBindTexture(target, texture);
    GLint maxLevel = 0;
    glGetTexParameteriv(target, GL_TEXTURE_MAX_LEVEL, &maxLevel);
    long long bytes = 0;
    for (GLint level = 0; level <= maxLevel && level < 16; ++level) {  // 16: levels of the largest texture GL allows
        GLint w = 0, h = 0, layers = 1, bits = 0;
        glGetTexLevelParameteriv(target, level, GL_TEXTURE_WIDTH, &w);
        glGetTexLevelParameteriv(target, level, GL_TEXTURE_HEIGHT, &h);
        if (target == GL_TEXTURE_2D_ARRAY) glGetTexLevelParameteriv(target, level, GL_TEXTURE_DEPTH, &layers);
        if (w == 0 || h == 0) break;  // past the levels that exist (a shading texture's GL-made chain ends at 1x1)
        GLint compressed = GL_FALSE;
        glGetTexLevelParameteriv(target, level, GL_TEXTURE_COMPRESSED, &compressed);
        if (compressed) {  // its component sizes say nothing of its blocks: GL counts the image's bytes
            GLint size = 0;
            glGetTexLevelParameteriv(target, level, GL_TEXTURE_COMPRESSED_IMAGE_SIZE, &size);
            bytes += size;
            continue;
        }
        for (GLenum component : {GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE, GL_TEXTURE_BLUE_SIZE, GL_TEXTURE_ALPHA_SIZE}) {
            GLint b = 0;
            glGetTexLevelParameteriv(target, level, component, &b);
            bits += b;
        }
        bytes += static_cast<long long>(w) * h * layers * bits / 8;
    }
    return bytes;
}

}  // namespace heightpack::view
