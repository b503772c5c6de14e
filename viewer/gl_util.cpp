#include "gl_util.hpp"

#include <cstdio>

namespace heightpack::view {

namespace {

GLuint compile(GLenum stage, const std::string& source, const std::string& name, std::string& log) {
    const GLuint shader = glCreateShader(stage);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::string text(static_cast<size_t>(std::max(length, 1)), '\0');
        glGetShaderInfoLog(shader, length, nullptr, text.data());
        log = name + (stage == GL_VERTEX_SHADER ? " vertex" : " fragment") + " shader: " + text;
        glDeleteShader(shader);
        return 0;
    }
    return shader;
}

}  // namespace

GLuint buildProgram(const std::string& name, const std::string& preamble, const char* common, const char* vertex,
                    const char* fragment, std::string& log) {
    const std::string header = preamble + common + "\n#line 1\n";
    const GLuint vs = compile(GL_VERTEX_SHADER, header + vertex, name, log);
    if (!vs) return 0;
    const GLuint fs = compile(GL_FRAGMENT_SHADER, header + fragment, name, log);
    if (!fs) {
        glDeleteShader(vs);
        return 0;
    }
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
        std::string text(static_cast<size_t>(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program, length, nullptr, text.data());
        log = name + " program link: " + text;
        glDeleteProgram(program);
        return 0;
    }
    return program;
}

void checkGl(const char* where) {
#ifndef NDEBUG
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) std::fprintf(stderr, "GL error 0x%04x at %s\n", e, where);
#else
    (void)where;
#endif
}

bool RenderTarget::create(int w, int h, GLenum colourFormat) {
    destroy();
    width = w;
    height = h;
    glGenTextures(1, &colour);
    glBindTexture(GL_TEXTURE_2D, colour);
    const bool isFloat = colourFormat == GL_R32F || colourFormat == GL_RGBA32F;
    glTexImage2D(GL_TEXTURE_2D, 0, colourFormat, w, h, 0, colourFormat == GL_R32F ? GL_RED : GL_RGBA,
                 isFloat ? GL_FLOAT : GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glGenFramebuffers(1, &framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colour, 0);
    if (!isFloat) {
        glGenRenderbuffers(1, &depth);
        glBindRenderbuffer(GL_RENDERBUFFER, depth);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    }
    const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return complete;
}

void RenderTarget::destroy() {
    if (framebuffer) glDeleteFramebuffers(1, &framebuffer);
    if (colour) glDeleteTextures(1, &colour);
    if (depth) glDeleteRenderbuffers(1, &depth);
    framebuffer = colour = depth = 0;
}

std::vector<unsigned char> RenderTarget::readRgb() const {
    std::vector<unsigned char> rows(static_cast<size_t>(width) * height * 3);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    // GL's first row is the bottom one.
    std::vector<unsigned char> flipped(rows.size());
    const size_t stride = static_cast<size_t>(width) * 3;
    for (int y = 0; y < height; ++y)
        std::copy(rows.begin() + static_cast<long>((height - 1 - y) * stride),
                  rows.begin() + static_cast<long>((height - y) * stride), flipped.begin() + static_cast<long>(y * stride));
    return flipped;
}

std::vector<float> RenderTarget::readRed() const {
    std::vector<float> values(static_cast<size_t>(width) * height);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RED, GL_FLOAT, values.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return values;
}

}  // namespace heightpack::view
