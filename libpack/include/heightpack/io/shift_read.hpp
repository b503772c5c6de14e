// Reading Tessendorf's shift (Dx, Dy) that rides beside a height map: channels Dx, Dy of
// a synthesised EXR, or the Dx, Dy layers of a texture heightpack packed with them.
#pragma once

#include <string>

#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/read.hpp"

namespace heightpack {

// Whether the file at path holds a shift loadShift can read, judged from its
// header alone (no pixels are read). False for a file that cannot be opened: its reader reports why.
bool hasShift(const std::string& path);

// Loads level 0 of the shift at path as two channels (x, y), in the units of the heights
// loadHeightMap returns for the same file: metres per unit of choppiness for a synthesised EXR; a
// heightpack texture's values mapped back through its heightScale (D is linear in the heights, so its
// offset does not apply). Where it is found: channels named Dx and Dy; in a texture heightpack wrote with
// heightpack:displacement, the Dx.R and Dy.R of a neighbour4 file or the Dx and Dy of a plain one. Fails
// with BadInput (Fix::AddShift) when the file has none, and as loadHeightMap does for a file that
// cannot be read or holds a non-finite value.
Result<Image> loadShift(const std::string& path, const LoadOptions& options = {});

}  // namespace heightpack
