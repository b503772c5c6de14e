#include "displacement_gl.hpp"

#include <cassert>

#include "gl_util.hpp"

namespace heightpack::view {

GLuint uploadShiftArray(const std::vector<ShiftFrame>& frames) {
    assert(!frames.empty() && !frames[0].x->empty());
    const std::vector<Image>& first = *frames[0].x;
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D_ARRAY, texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    const GLsizei layers = static_cast<GLsizei>(2 * frames.size());
    for (size_t level = 0; level < first.size(); ++level) {
        const int w = first[level].width, h = first[level].height;
        glTexImage3D(GL_TEXTURE_2D_ARRAY, static_cast<GLint>(level), GL_RGBA32F, w, h, layers, 0, GL_RGBA, GL_FLOAT, nullptr);
        for (size_t f = 0; f < frames.size(); ++f) {
            for (int axis = 0; axis < 2; ++axis) {
                const Image& image = (*(axis == 0 ? frames[f].x : frames[f].y))[level];
                assert(image.channels == 4 && image.width == w && image.height == h);
                glTexSubImage3D(GL_TEXTURE_2D_ARRAY, static_cast<GLint>(level), 0, 0, static_cast<GLint>(2 * f + axis), w, h,
                                1, GL_RGBA, GL_FLOAT, image.pixels.data());
            }
        }
    }
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, static_cast<GLint>(first.size() - 1));
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, first.size() > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    checkGl("uploadShiftArray");
    return texture;
}

GLuint uploadZeroShift() {
    const std::vector<Image> zero{Image(1, 1, 4, 0.0f)};
    return uploadShiftArray({ShiftFrame{&zero, &zero}});
}

void bindArrayTexture(int unit, GLuint texture) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, texture);
}

}  // namespace heightpack::view
