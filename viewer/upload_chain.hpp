// A mip chain's texels as its file stored them (32-bit float, half, 16-bit normalised, BC4/BC5 blocks), so the viewer
// uploads them at that precision and the GPU memory shows what the pixel type costs. Also the two
// chains the viewer derives from a stored one, in the same type: the 4-neighbour packing of a plain
// chain, and the atlas that the textureGather lookup reads.
#pragma once

#include <cstdint>
#include <vector>

#include "heightpack/core/image.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/pixel_type.hpp"

namespace heightpack::view {

struct UploadChain {
    int channels = 1;  // 1 to 4, interleaved; a block chain: 1 (BC4, ASTC heights) or 2 (BC5, ASTC normals)
    ComponentKind kind = ComponentKind::Float32;  // Block: each level holds its blocks, not texels
    TexelFormat blockFormat = TexelFormat::Bc4Unorm;  // Block only: which blocks (RGTC or an ASTC size)
    int width = 0, height = 0;  // level 0
    std::vector<std::vector<std::uint8_t>> levels;  // level 0 first, rows tightly packed, little-endian
    // What a shader reads back (a normalised format samples u / 65535, an RGTC one its unit value) mapped to
    // the file's values: value = offset + scale * sampled. Identity except for normalised and block chains.
    Normalisation decode;

    bool isBlock() const { return kind == ComponentKind::Block; }
    bool isAstc() const { return isBlock() && isAstcFormat(blockFormat); }
    bool isAstcHdr() const { return isBlock() && isAstcHdrType(pixelTypeOf(blockFormat)); }
    // Texel chains only: a block chain has no bytes of its own per texel.
    int bytesPerTexel() const { return channels * (kind == ComponentKind::Float32 ? 4 : 2); }
    int levelWidth(int level) const { return width >> level > 0 ? width >> level : 1; }
    int levelHeight(int level) const { return height >> level > 0 ? height >> level : 1; }
};

// Float levels (all of one channel count) as 32-bit floats, or as halves when the file held halves
// (an EXR of half channels: every value is a half already, so nothing is rounded).
UploadChain storeFloats(const std::vector<Image>& levels, ComponentKind kind = ComponentKind::Float32);

// A KTX2 or DDS file's levels as they are (a block format's blocks too, to go up as RGTC or ASTC); its
// bytes move into the chain.
UploadChain storeGpuTexture(GpuTexture& texture);

// A block chain's decoded levels as 32-bit floats of the unit values its blocks hold ((value - offset) /
// scale), so they share its decode: for the lookups that read texel by texel (the 4-neighbour packing, the
// gather atlas), which a block chain cannot feed.
UploadChain unitFloats(const std::vector<Image>& decoded, const Normalisation& decode);

// Channel 0 of every texel (a texel chain): the plain height chain inside a 4-neighbour packed one (R = H(i, j)).
UploadChain firstChannel(const UploadChain& chain);

// The 4-neighbour packing (R = H(i,j), G = H(i+1,j), B = H(i,j+1), A = H(i+1,j+1), indices brought in by
// wrap) of a one-channel chain, texel by texel in its own type: the same as heightpack::packNeighbour4 on
// the decoded values, with nothing rounded twice.
UploadChain packStoredNeighbour4(const UploadChain& plain, Wrap wrap);

// textureGather reads only a texture's base level, so a chain it reads at every level is laid out as
// one level-less texture: level 0 at (0, 0), the others stacked in a column to its right. Each level
// carries one more column and row holding its wrapped neighbours H(w, j), H(i, h), H(w, h), so the 2x2
// footprint of a lookup never leaves its level (hardware wrap cannot work inside an atlas).
struct GatherAtlas {
    UploadChain texels;  // one channel, one level
    struct Origin {
        int x = 0, y = 0;
    };
    std::vector<Origin> origins;  // where each level's texel (0, 0) sits
};
GatherAtlas buildGatherAtlas(const UploadChain& plain, Wrap wrap);

}  // namespace heightpack::view
