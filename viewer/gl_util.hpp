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

// How many samplers a linked program's vertex and fragment stages read (active sampler uniforms, arrays
// counted by their size). Per stage where the context has GL 4.3's program interface query; before it,
// both are the program's total, which bounds each stage.
struct StageSamplers {
    int vertex = 0, fragment = 0;
};
StageSamplers activeSamplers(GLuint program);

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
    // The first channels (1 to 4) of a float target as floats, interleaved, bottom row first, as GL
    // stores it.
    std::vector<float> readFloats(int channels) const;
};

}  // namespace heightpack::view
