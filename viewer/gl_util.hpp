// Small OpenGL helpers: programs with their logs, an offscreen target.
#pragma once

#include <epoxy/gl.h>

#include <string>
#include <vector>

#include "heightpack/core/image.hpp"

namespace heightpack::view {

// Compiles and links preamble (the #version line and defines) + common + each stage. Returns 0 and fills
// log on failure (the compile or link log, naming the program and stage).
GLuint buildProgram(const std::string& name, const std::string& preamble, const char* common, const char* vertex,
                    const char* fragment, std::string& log);

// Prints any pending GL errors with where they were noticed; compiled out of release builds.
void checkGl(const char* where);

// An offscreen colour + depth target.
struct RenderTarget {
    GLuint framebuffer = 0, colour = 0, depth = 0;
    int width = 0, height = 0;
    bool create(int w, int h, GLenum colourFormat);
    void destroy();
    // RGB 8-bit pixels, top row first.
    std::vector<unsigned char> readRgb() const;
    // The red channel as floats (an R32F or RGBA32F target), bottom row first, as GL stores it.
    std::vector<float> readRed() const;
};

}  // namespace heightpack::view
