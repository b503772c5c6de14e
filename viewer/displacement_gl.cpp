#include "displacement_gl.hpp"

#include <cassert>

#include "gl_util.hpp"

namespace heightpack::view {

GLuint uploadShiftChain(const std::vector<Image>& x, const std::vector<Image>& y) {
    assert(x.size() == y.size() && !x.empty());
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D_ARRAY, texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    std::vector<float> both;
    for (size_t level = 0; level < x.size(); ++level) {
        assert(x[level].channels == 4 && y[level].channels == 4);
        both = x[level].pixels;
        both.insert(both.end(), y[level].pixels.begin(), y[level].pixels.end());
        glTexImage3D(GL_TEXTURE_2D_ARRAY, static_cast<GLint>(level), GL_RGBA32F, x[level].width, x[level].height, 2, 0,
                     GL_RGBA, GL_FLOAT, both.data());
    }
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, static_cast<GLint>(x.size() - 1));
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, x.size() > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    checkGl("uploadShiftChain");
    return texture;
}

GLuint uploadZeroShift() { return uploadShiftChain({Image(1, 1, 4, 0.0f)}, {Image(1, 1, 4, 0.0f)}); }

void bindArrayTexture(int unit, GLuint texture) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, texture);
}

}  // namespace heightpack::view
