// Synth's baked foam coverage of a height map, loaded beside its heights: from the Foam layer of a texture
// `heightpack pack --foam` wrote, or mip-mapped in memory from a synthesised EXR's Foam channel.
#pragma once

#include <string>

#include "heightpack/bake/pack_job.hpp"
#include "heightpack/io/height_sequence.hpp"
#include "scene.hpp"
#include "texture_reader.hpp"

namespace heightpack::view {

// For a heightpack height texture that holds foam: puts the coverage of each level (F(i,j)) into
// frame.foam: an array texture's layer Foam as stored; an EXR's as floats, from split (its levels split
// by splitHeightChains). Does nothing for any other file.
Status takeFoam(const std::string& path, const ViewerTexture& file, const HeightChains& split, HeightFrame& frame);

// For a map packed in memory: when the file at path has a Foam channel, mip-maps it as packHeights did the
// heights, into frame.foam.
Status foamChainOf(const std::string& path, const LoadOptions& load, const SourceInfo& source,
                   const PackOptions& pack, HeightFrame& frame);

}  // namespace heightpack::view
