// Synth's looping foam coverage carried through `pack`: the same resize, mip filter and wrap as the heights
// (packed beside them by pack_shift.hpp's companions), so a shader finds a texel's foam at the
// texel and level where it finds its height.
#pragma once

#include <vector>

#include "heightpack/bake/pack_job.hpp"
#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"

namespace heightpack {

// The coverage foam (one channel, 0..1) as a one-channel mip chain, level 0 first: sides resampled to
// powers of two as the heights are (when options.resizeToPowerOfTwo, else refused with BadInput naming
// source.path), mip-mapped with options.mip. The heights' scale and offset do not apply: coverage is not
// a height.
Result<std::vector<Image>> foamChain(Image foam, const SourceInfo& source, const PackOptions& options);

}  // namespace heightpack
