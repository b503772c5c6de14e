// The whole `synth` operation: a sea from a spectrum, written as one map or a looping sequence of frames,
// optionally with shift, looping foam, several cascades and a sea-state report.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "heightpack/core/sea/foam.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/core/sea/spectrum.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/version.hpp"

namespace heightpack {

struct SynthOptions {
    SpectrumOptions spectrum;
    int frames = 1;  // more than one needs spectrum.loopPeriod: frame f is the sea at f * loopPeriod / frames
    bool shift = false;  // EXR only: add Tessendorf's shift (horizontal displacement) as channels Dx, Dy
    bool foam = false;          // EXR only, implies shift: a Foam channel (coverage 0..1) after Y, Dx, Dy
    FoamOptions foamOptions;
    // The lambda of x + lambda D that the Jacobian (foam, folds) and the shift bound assume. Dx and
    // Dy are written per unit of it, so an engine may choose another; foam is baked for this one.
    double choppiness = 1.0;
    bool report = false;  // measure shift and folds even when they are not written
    int cascades = 1;     // tiles of sizes tileSize * (17/61)^c with disjoint wavenumber bands: NAME_cC.EXT
    int threads = 0;      // 0 = all cores; the bytes are the same for any count
    // An .exr's: none, zip or zips. Deflate saves 3-4% of float wave heights and shift (noise) for
    // most of the write's time; with foam, whose zeros do compress, zip saves about a quarter.
    Compression compression = Compression::None;
    std::string version = kVersion;  // this library's (heightpack/version.hpp); recorded in outputs, part of cache keys
    // Reports progress: the stage ("synth", "write") and the fraction of it done; may be empty.
    std::function<void(std::string_view stage, double fraction)> progress;
};

// One tile's numbers (the whole sea without cascades, one cascade with them).
struct SynthTileReport {
    std::vector<std::string> outputs;            // one file, or NAME.0000.EXT ... for frames
    double tileSize = 0.0;                       // m
    double bandLow = 0.0, bandHigh = 0.0;        // rad/m, with cascades; 0 and 0 for a whole sea
    double significantWaveHeight = 0.0;          // 4 x the standard deviation of frame 0's heights (m)
    double expectedSignificantWaveHeight = 0.0;  // 4 sqrt(m0), m0 the variance the grid resolves
    double minHeight = 0.0, maxHeight = 0.0;     // over all frames (m)
    double peakPeriod = 0.0, peakWavelength = 0.0, steepness = 0.0;  // SeaStateSummary
    // With shift, foam or a report: the fraction of texels with J < 0 over all frames, the longest
    // horizontal move of any texel (choppiness * |D|) and a bound that no frame can exceed.
    std::optional<double> foldFraction, maxShift, shiftBound;
};

struct SynthReport {
    std::vector<std::string> outputs;  // every file written
    // The whole sea: one tile's numbers, or with cascades their sum (variances add: the bands are disjoint).
    double significantWaveHeight = 0.0, expectedSignificantWaveHeight = 0.0;
    double minHeight = 0.0, maxHeight = 0.0;
    std::vector<SynthTileReport> tiles;  // one per cascade; one without cascades
};

// Writes the sea at output: an .exr holds heights in metres (float); a .png or .tif holds them mapped
// onto [0,1] at 16 bits, with heightpack:heightScale and heightpack:heightOffset giving metres back
// (the same mapping for every frame of a sequence). With shift, an .exr holds channels Y (height),
// Dx and Dy (metres per unit of choppiness), and with foam a fourth, Foam. The sea-state numbers go into
// every file's header. With cascades, tile c goes to NAME_cC.EXT (and its frames). Every file is written
// atomically, and the files of a sequence or of cascades land together once all of them are written.
Result<SynthReport> synthesise(const std::string& output, const SynthOptions& options);

// The file cascade c of `count` goes to: NAME_cC.EXT; the output itself when count is 1.
std::string cascadeFileName(const std::string& output, int cascade, int count);

}  // namespace heightpack
