// Baked foam coverage on the GPU: every frame of a map's foam as one array texture (layer f = frame f), so a
// map costs one fragment sampler whatever its frame count, and the frame blend picks two layers of it. The
// fragment stage filters it in hardware (trilinear from its derivatives), unlike the vertex stage's packed
// heights: the coverage is shading, and a pixel should see the mean foam of its footprint.
#pragma once

#include <epoxy/gl.h>

#include "scene.hpp"

namespace heightpack::view {

// A GL_TEXTURE_2D_ARRAY, one channel in the type the frames' foam was stored in (R32F, R16F or R16: the
// shader applies each frame's foam.decode after filtering, which is linear in the texels), one layer per
// frame of layer (every frame's foam: the same levels and sizes), trilinear, repeating or clamped to the
// edge as the map's wrap says. 0 for a map without foam.
GLuint uploadFoamCoverage(const HeightLayer& layer);

}  // namespace heightpack::view
