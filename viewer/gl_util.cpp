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

bool isSampler(GLenum type) {
    switch (type) {
        case GL_SAMPLER_1D: case GL_SAMPLER_2D: case GL_SAMPLER_3D: case GL_SAMPLER_CUBE: case GL_SAMPLER_2D_ARRAY:
        case GL_SAMPLER_1D_ARRAY: case GL_SAMPLER_2D_SHADOW: case GL_SAMPLER_2D_ARRAY_SHADOW: case GL_SAMPLER_CUBE_SHADOW:
        case GL_SAMPLER_2D_RECT: case GL_SAMPLER_BUFFER: case GL_SAMPLER_2D_MULTISAMPLE: case GL_SAMPLER_2D_MULTISAMPLE_ARRAY:
        case GL_INT_SAMPLER_2D: case GL_INT_SAMPLER_2D_ARRAY: case GL_INT_SAMPLER_3D: case GL_UNSIGNED_INT_SAMPLER_2D:
        case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY: case GL_UNSIGNED_INT_SAMPLER_3D:
            return true;
        default:
            return false;
    }
}

}  // namespace

StageSamplers activeSamplers(GLuint program) {
    StageSamplers s;
    if (epoxy_gl_version() >= 43 || epoxy_has_gl_extension("GL_ARB_program_interface_query")) {
        GLint count = 0;
        glGetProgramInterfaceiv(program, GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
        for (GLint i = 0; i < count; ++i) {
            const GLenum props[] = {GL_TYPE, GL_ARRAY_SIZE, GL_REFERENCED_BY_VERTEX_SHADER, GL_REFERENCED_BY_FRAGMENT_SHADER};
            GLint values[4] = {0, 0, 0, 0};
            glGetProgramResourceiv(program, GL_UNIFORM, static_cast<GLuint>(i), 4, props, 4, nullptr, values);
            if (!isSampler(static_cast<GLenum>(values[0]))) continue;
            if (values[2]) s.vertex += values[1];
            if (values[3]) s.fragment += values[1];
        }
        return s;
    }
    GLint count = 0;
    glGetProgramiv(program, GL_ACTIVE_UNIFORMS, &count);
    for (GLint i = 0; i < count; ++i) {
        GLint size = 0;
        GLenum type = 0;
        char name[256];
        glGetActiveUniform(program, static_cast<GLuint>(i), sizeof name, nullptr, &size, &type, name);
        if (isSampler(type)) s.vertex += size;
    }
    s.fragment = s.vertex;
    return s;
}

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

std::vector<float> RenderTarget::readFloats(int channels) const {
    static const GLenum formats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
    std::vector<float> values(static_cast<size_t>(width) * height * channels);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, formats[channels - 1], GL_FLOAT, values.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return values;
}

}  // namespace heightpack::view
