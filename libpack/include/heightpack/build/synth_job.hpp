// The whole `synth` operation: a sea from a spectrum, written as one map or a looping sequence of frames.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "heightpack/core/result.hpp"
#include "heightpack/core/spectrum.hpp"

namespace heightpack {

struct SynthOptions {
    SpectrumOptions spectrum;
    int frames = 1;  // more than one needs spectrum.loopPeriod: frame f is the sea at f * loopPeriod / frames
    bool displacement = false;  // EXR only: add Tessendorf's horizontal displacement as channels Dx, Dy
    std::string version;
    // Reports progress: the stage ("synth", "write") and the fraction of it done; may be empty.
    std::function<void(std::string_view stage, double fraction)> progress;
};

struct SynthReport {
    std::vector<std::string> outputs;  // one file, or NAME.0000.EXT ... for frames
    double significantWaveHeight = 0.0;          // 4 x the standard deviation of frame 0's heights (m)
    double expectedSignificantWaveHeight = 0.0;  // 4 x sqrt(the resolved spectrum's variance)
    double minHeight = 0.0, maxHeight = 0.0;     // over all frames (m)
};

// Writes the sea at output: an .exr holds heights in metres (float); a .png or .tif holds them mapped
// onto [0,1] at 16 bits, with heightpack:heightScale and heightpack:heightOffset giving metres back
// (the same mapping for every frame of a sequence). With displacement, an .exr holds channels Y (height),
// Dx and Dy (metres per unit of choppiness). Every file is written atomically.
Result<SynthReport> synthesise(const std::string& output, const SynthOptions& options);

}  // namespace heightpack
