// Tessendorf's shift (Dx, Dy) carried through `pack`: the same resize, scale, mip filter,
// wrap and 4-neighbour packing as the heights, so a vertex shader reads D at the texel and level where it
// reads the height, with the same two lerps.
#pragma once

#include <string>
#include <vector>

#include "heightpack/bake/pack_job.hpp"
#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/pixel_type.hpp"

namespace heightpack {

// Dx and Dy, each a one-channel mip chain (level 0 first), and the same levels packed (RGBA: R = D(i,j),
// G = D(i+1,j), B = D(i,j+1), A = D(i+1,j+1)) when asked for.
struct ShiftMaps {
    std::vector<Image> plainX, plainY;
    std::vector<Image> packedX, packedY;
};

// The shift d (two channels, x and y, in the source's units) as packHeights makes the heights of
// the same map: sides resampled to powers of two (when options.resizeToPowerOfTwo, else refused with
// BadInput naming source.path), times options.scale (D is linear in the heights; the offset does not
// apply), mip-mapped with options.mip, and packed when options.layout is Neighbour4.
Result<ShiftMaps> packShift(Image d, const SourceInfo& source, const PackOptions& options);

// A chain written beside the heights in the same file (an EXR's further channels, a KTX2's or DDS's
// further array layers): its layer name (Dx, Dy, Foam: see layerName in attributes.hpp) and its plain
// levels, one channel each, the sizes of the heights' levels.
struct CompanionChain {
    std::string name;
    const std::vector<Image>* levels = nullptr;
};

// Dx, Dy of d (when given), then foam (when given): the layers, in the order they are written.
std::vector<CompanionChain> companionsOf(const ShiftMaps* d, const std::vector<Image>* foam);

// The channel names of a packed texture with companions: the heights' R, G, B, A, then each companion's
// NAME.R, NAME.G, NAME.B, NAME.A, packed as the heights are.
std::vector<std::string> packedCompanionChannels(const std::vector<CompanionChain>& companions);

namespace detail {

// Makes content (channels, rows) the packed heights and their companions: the chains must share their sizes.
void fillPackedWithCompanions(ChainToWrite& content, const std::vector<Image>& heights,
                              std::vector<CompanionChain> companions, Wrap wrap);
// Makes content the plain chain with its companions: channels Y, then each companion's NAME.
void fillPlainWithCompanions(ChainToWrite& content, const std::vector<Image>& heights,
                             std::vector<CompanionChain> companions);
// Makes content an array texture (KTX2, DDS): layer "heights", then one layer per companion, each packed
// (or, when not packed, plain: channel Y) exactly as the EXR's layers are.
void fillArrayWithCompanions(ChainToWrite& content, const std::vector<Image>& heights,
                             std::vector<CompanionChain> companions, Wrap wrap, bool packed);
// The one of the three that container holds: an EXR's channels, a KTX2's or DDS's layers.
void fillWithCompanions(ChainToWrite& content, Container container, const std::vector<Image>& heights,
                        std::vector<CompanionChain> companions, Wrap wrap, bool packed);

}  // namespace detail

}  // namespace heightpack
