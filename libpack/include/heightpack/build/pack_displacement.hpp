// Tessendorf's horizontal displacement (Dx, Dy) carried through `pack`: the same resize, scale, mip filter,
// wrap and 4-neighbour packing as the heights, so a vertex shader reads D at the texel and level where it
// reads the height, with the same two lerps.
#pragma once

#include <vector>

#include "heightpack/build/pack_job.hpp"
#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/exr_write.hpp"

namespace heightpack {

// Dx and Dy, each a one-channel mip chain (level 0 first), and the same levels packed (RGBA: R = D(i,j),
// G = D(i+1,j), B = D(i,j+1), A = D(i+1,j+1)) when asked for.
struct DisplacementMaps {
    std::vector<Image> plainX, plainY;
    std::vector<Image> packedX, packedY;
};

// The displacement d (two channels, x and y, in the source's units) as packHeights makes the heights of
// the same map: sides resampled to powers of two (when options.resizeToPowerOfTwo, else refused with
// BadInput naming source.path), times options.scale (D is linear in the heights; the offset does not
// apply), mip-mapped with options.mip, and packed when options.layout is Neighbour4.
Result<DisplacementMaps> packDisplacement(Image d, const SourceInfo& source, const PackOptions& options);

// The channel names of a packed texture with its displacement: the heights' R, G, B, A, then the layers
// Dx and Dy, each R, G, B, A packed as the heights are.
std::vector<std::string> packedDisplacementChannels();

namespace detail {

// Makes content (channels, rows) the packed heights and displacement: the chains must share their sizes.
void fillPackedWithDisplacement(TiledExrContent& content, const std::vector<Image>& heights, const DisplacementMaps& d,
                                Wrap wrap);
// Makes content the plain chain with its displacement: channels Y, Dx, Dy.
void fillPlainWithDisplacement(TiledExrContent& content, const std::vector<Image>& heights, const DisplacementMaps& d);

}  // namespace detail

}  // namespace heightpack
