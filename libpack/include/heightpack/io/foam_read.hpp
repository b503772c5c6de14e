// Reading the foam coverage that rides beside a height map: channel Foam of a synthesised EXR (synth --foam),
// or the Foam layer of a texture heightpack packed with it (pack --foam).
#pragma once

#include <string>

#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/read.hpp"

namespace heightpack {

// Whether the file at path holds a foam coverage loadFoam can read, judged from its header alone. False for
// a file that cannot be opened: its reader reports why.
bool hasFoam(const std::string& path);

// Loads level 0 of the foam coverage at path as one channel, as stored (coverage 0..1: the heights' scale
// and offset do not apply). Where it is found: a channel named Foam; in a texture heightpack wrote with
// heightpack:foam, Foam.R of a neighbour4 file (F(i,j)) or Foam of a plain one. Fails with BadInput when
// the file has none, and as loadHeightMap does for a file that cannot be read or holds a non-finite value.
Result<Image> loadFoam(const std::string& path, const LoadOptions& options = {});

}  // namespace heightpack
