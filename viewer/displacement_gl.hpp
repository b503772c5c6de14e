// Horizontal displacement on the GPU: every frame's packed Dx, Dy of a map as one array texture (layer
// 2f Dx, layer 2f + 1 Dy of frame f, RGBA per level as the heights), so a map's shift costs one sampler
// however many frames it has: the vertex stage of OpenGL 3.3 promises only 16.
#pragma once

#include <epoxy/gl.h>

#include <vector>

#include "heightpack/core/image.hpp"

namespace heightpack::view {

// One frame's packed Dx and Dy chains (the same levels).
struct ShiftFrame {
    const std::vector<Image>* x = nullptr;
    const std::vector<Image>* y = nullptr;
};

// A GL_TEXTURE_2D_ARRAY of RGBA32F layers, two per frame, nearest: the shader does the filtering from one
// texelFetch per layer, as for the heights. Every frame must hold the same levels.
GLuint uploadShiftArray(const std::vector<ShiftFrame>& frames);

// A 1x1 two-layer array of zeros, bound to the samplers of maps without Dx, Dy.
GLuint uploadZeroShift();

void bindArrayTexture(int unit, GLuint texture);

}  // namespace heightpack::view
