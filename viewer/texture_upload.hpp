// Textures from stored chains, uploaded in the precision they were stored in (GL_RGBA16F for half,
// GL_R16 / GL_RG16 / GL_RGBA16 for 16-bit normalised, GL_RG16_SNORM for the two-channel normals of
// earlier versions, GL_COMPRESSED_RED_RGTC1 / GL_COMPRESSED_RG_RGTC2 for BC4 / BC5 blocks as they are, the
// ASTC LDR formats for ASTC blocks, normals' y swizzled from alpha into green), and the bytes each texture
// holds on the GPU as GL itself reports them.
#pragma once

#include <epoxy/gl.h>

#include <vector>

#include "heightpack/core/image.hpp"
#include "upload_chain.hpp"

namespace heightpack::view {

// A mip-mapped texture of the chain's levels (one level: no mip-maps). linear: GL_LINEAR filtering (the
// reference path, shading textures), else nearest (the packed and gather lookups filter in the shader).
// A normalised chain samples as u / 65535, a block chain as its unit value: the shader applies chain.decode.
GLuint uploadStoredChain(const UploadChain& chain, bool linear, Wrap wrap);

// The same for float levels, as 32-bit floats.
GLuint uploadFloatChain(const std::vector<Image>& levels, bool linear, Wrap wrap);

// Chains of one size, channel count and type (a sequence's frames) as one GL_TEXTURE_2D_ARRAY, chain i in
// layer i of every level, filtered and wrapped as uploadStoredChain's: a shader reads any frame through
// one sampler, so the vertex stage's samplers do not grow with the frames it blends.
GLuint uploadStoredArray(const std::vector<const UploadChain*>& chains, bool linear, Wrap wrap);

// Whether the current context takes ASTC blocks (GL_KHR_texture_compression_astc_ldr), and HDR ones
// (GL_KHR_texture_compression_astc_hdr: the same GL formats, whose HDR blocks an LDR-only decoder shows
// in its error colour).
bool contextTakesAstc();
bool contextTakesAstcHdr();

// Bytes of every level (and layer) of the texture, from the sizes and component bits GL reports for it
// (so a format a driver widened on upload would show here). target: GL_TEXTURE_2D or GL_TEXTURE_2D_ARRAY.
long long textureBytes(GLuint texture, GLenum target = GL_TEXTURE_2D);

}  // namespace heightpack::view
