// Synth's baked foam coverage of a height map, loaded beside its heights: from the Foam layer of a texture
// `heightpack pack --foam` wrote, or mip-mapped in memory from a synthesised EXR's Foam channel.
#pragma once

#include <string>

#include "heightpack/bake/pack_job.hpp"
#include "scene.hpp"
#include "texture_reader.hpp"

namespace heightpack::view {

// For a heightpack texture that records heightpack:foam: puts the coverage of each level (Foam.R of a
// neighbour4 file, F(i,j), or Foam of a plain one) into frame.foam: an array texture's layer Foam as
// stored; an EXR's channel as floats, leaving file's levels and channel names without any Foam channel,
// as a texture without foam has them (a half EXR's stored texels are dropped: the heights then upload as
// floats). Does nothing for any other file.
Status takeFoam(const std::string& path, ViewerTexture& file, HeightFrame& frame);

// For a map packed in memory: when the file at path has a Foam channel, mip-maps it as packHeights did the
// heights, into frame.foam.
Status foamChainOf(const std::string& path, const LoadOptions& load, const SourceInfo& source,
                   const PackOptions& pack, HeightFrame& frame);

}  // namespace heightpack::view
