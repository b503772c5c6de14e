#include "foam_gl.hpp"

#include <cassert>

#include "gl_util.hpp"

namespace heightpack::view {

GLuint uploadFoamCoverage(const HeightLayer& layer) {
    if (!layer.foam) return 0;
    const std::vector<Image>& first = layer.frames[0].foam;
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D_ARRAY, texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    const GLsizei frames = static_cast<GLsizei>(layer.frames.size());
    std::vector<float> all;
    for (size_t level = 0; level < first.size(); ++level) {
        all.clear();
        for (const HeightFrame& frame : layer.frames) {
            assert(frame.foam.size() == first.size() && frame.foam[level].channels == 1);
            all.insert(all.end(), frame.foam[level].pixels.begin(), frame.foam[level].pixels.end());
        }
        glTexImage3D(GL_TEXTURE_2D_ARRAY, static_cast<GLint>(level), GL_R32F, first[level].width, first[level].height,
                     frames, 0, GL_RED, GL_FLOAT, all.data());
    }
    const GLint wrap = layer.wrap == Wrap::Clamp ? GL_CLAMP_TO_EDGE : GL_REPEAT;
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, wrap);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, wrap);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, static_cast<GLint>(first.size() - 1));
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, first.size() > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    checkGl("uploadFoamCoverage");
    return texture;
}

}  // namespace heightpack::view
