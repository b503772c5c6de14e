// The shift (Dx, Dy) of a height map, loaded beside its heights: from the Dx, Dy layers of
// a texture `heightpack pack --shift` wrote, or packed in memory from a synthesised EXR's Dx, Dy.
#pragma once

#include <string>

#include "heightpack/bake/pack_job.hpp"
#include "heightpack/io/height_sequence.hpp"
#include "scene.hpp"
#include "texture_reader.hpp"

namespace heightpack::view {

// For a heightpack height texture that holds Dx, Dy (its description's channels): puts them into
// frame.shiftX / shiftY (packed, per level). An array texture's layers Dx, Dy go as stored (a plain one's
// packed texel by texel); an EXR's go as floats, from split (its levels split by splitHeightChains).
// Does nothing for any other file.
Status takeShift(const std::string& path, const ViewerTexture& file, const HeightChains& split, Wrap wrap,
                        HeightFrame& frame);

// For a map packed in memory: when the file at path has Dx, Dy channels, packs them as packHeights packed
// its heights with the same options, into frame.shiftX / shiftY.
Status packShiftOf(const std::string& path, const LoadOptions& load, const SourceInfo& source,
                          const PackOptions& pack, HeightFrame& frame);

}  // namespace heightpack::view
