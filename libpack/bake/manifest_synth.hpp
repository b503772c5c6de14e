// Internal: a [displacement.synth] table read into the spectrum the build synthesises (manifest.cpp).
#pragma once

#include "heightpack/bake/manifest.hpp"

#include "manifest_section.hpp"

namespace heightpack::detail {

// The spectrum parameters of table t, with the asset's tile size; the same ranges as `heightpack synth`'s
// flags, in SI units (m/s, m, s, degrees), with shift, foam and the cascade count (cascade 0 of
// them: the manifest splits the asset into its cascades). Throws the manifest's errors (FILE:LINE, key), finishes t.
SynthSource parseSynthSource(Section& t, double tileSize);

}  // namespace heightpack::detail
