// What the viewer tests share: running heightpack-view (under the test program's Xvfb, or with no display
// at all), reading its screenshots back, and comparing pictures.
#pragma once

#include <string>
#include <vector>

#include "support/test_support.hpp"

namespace heightpack::test {

using ViewRun = ProcessResult;

// This process's environment for the viewer, less the variables named in `without`, plus `with`.
std::vector<std::string> viewerEnvironment(const std::vector<std::string>& without = {},
                                           const std::vector<std::string>& with = {});

// Runs heightpack-view in a window of the test program's virtual X server (one Xvfb for all its runs),
// with `extraEnvironment` ("NAME=value") added.
ViewRun view(const std::vector<std::string>& args, const std::vector<std::string>& extraEnvironment = {});

// Runs heightpack-view with DISPLAY unset: no X server at all, so it draws through EGL.
ViewRun viewWithoutDisplay(const std::vector<std::string>& args, const std::vector<std::string>& extraEnvironment = {});

struct Picture {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
    int at(int x, int y, int c = 0) const { return rgb[(size_t(y) * width + x) * 3 + c]; }
};

Picture readPicture(const std::string& path);

// Runs the viewer with args + --screenshot dir/name (under Xvfb) and reads the picture back.
Picture screenshot(const ScratchDir& dir, const std::string& name, std::vector<std::string> args);

struct Difference {
    int max = 0;
    double fractionOver = 0.0;  // of pixels differing by more than `tolerance`
};

Difference compare(const Picture& a, const Picture& b, int tolerance);

// What --grid-heights writes: the height and horizontal shift of every grid vertex as the GPU computed them,
// with the camera, grid radii and time that place each vertex.
struct GridHeights {
    int segments = 0, rings = 0;
    std::vector<float> heights, shiftX, shiftY;  // ring-major: channels Y, Dx, Dy
    float cameraX = 0, cameraY = 0, cameraZ = 0, pixelAngle = 0, innerRadius = 0, ringScale = 0, waterLevel = 0, time = 0;
};

GridHeights readGridHeights(const std::string& path);

inline const std::string kExamples = std::string(HEIGHTPACK_SOURCE_DIR) + "/examples/maps/";

}  // namespace heightpack::test
