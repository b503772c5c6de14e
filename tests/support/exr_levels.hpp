// The levels of an EXR as OpenImageIO reads them, every channel by name: what the end-to-end tests of
// packed textures (heights, Dx, Dy, Foam layers) compare texel by texel; and flat float EXRs of named
// channels written by OpenImageIO, as inputs shaped like synth's (Y, Dx, Dy, Foam).
#pragma once

#include <string>
#include <vector>

#include "heightpack/core/image.hpp"

namespace heightpack::test {

struct Level {
    int width = 0, height = 0;
    std::vector<std::string> names;
    std::vector<float> pixels;  // interleaved, names.size() a texel
    // The texel (x, y) of a channel; a channel the level lacks fails the test and reads NaN.
    float at(const std::string& channel, int x, int y) const;
};

// Mip level `mip` of the first subimage (an empty Level, and a failed expectation, when it is not there).
Level readLevel(const std::string& path, int mip);
// Every mip level of the first subimage.
std::vector<Level> readLevels(const std::string& path);

// Writes one-channel images of the same size as the channels `names` of a float EXR (fails the test on error).
void writeChannels(const std::string& path, const std::vector<std::string>& names, const std::vector<const Image*>& channels);

}  // namespace heightpack::test
