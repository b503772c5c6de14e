// Shift on the GPU: every frame's packed Dx, Dy of a map as one array texture (layer
// 2f Dx, layer 2f + 1 Dy of frame f, RGBA per level as the heights), so a map's shift costs one sampler
// however many frames it has: the vertex stage of OpenGL 3.3 promises only 16.
#pragma once

#include <epoxy/gl.h>

#include "scene.hpp"

namespace heightpack::view {

// A GL_TEXTURE_2D_ARRAY of the frames' packed Dx, Dy in the type they were stored in (RGBA32F, RGBA16F or
// RGBA16: the shader applies each frame's shiftX.decode), two layers per frame, nearest: the shader does
// the filtering from one texelFetch per layer, as for the heights. 0 for a map without Dx, Dy.
GLuint uploadShiftArray(const HeightLayer& layer);

// A 1x1 two-layer array of zeros, bound to the samplers of maps without Dx, Dy.
GLuint uploadZeroShift();

void bindArrayTexture(int unit, GLuint texture);

}  // namespace heightpack::view
