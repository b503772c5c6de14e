// Horizontal displacement on the GPU: a frame's packed Dx, Dy as one two-layer array texture (layer 0 Dx,
// layer 1 Dy, RGBA per level as the heights), so each layer costs one sampler, not two: the vertex stage
// of OpenGL 3.3 promises only 16 (heights, plain references and next frames already take 9).
#pragma once

#include <epoxy/gl.h>

#include <vector>

#include "heightpack/core/image.hpp"

namespace heightpack::view {

// A GL_TEXTURE_2D_ARRAY of two RGBA32F layers per level, nearest: the shader does the filtering from one
// texelFetch per layer, as for the heights. x and y must hold the same levels.
GLuint uploadShiftChain(const std::vector<Image>& x, const std::vector<Image>& y);

// A 1x1 two-layer array of zeros, bound to the samplers of maps without Dx, Dy.
GLuint uploadZeroShift();

void bindArrayTexture(int unit, GLuint texture);

}  // namespace heightpack::view
