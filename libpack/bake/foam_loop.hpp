// Internal: the foam of a synthesised sea's whole loop, which every frame's step needs and none can work
// out alone (foam builds up where the surface folds and fades after, over the loop). The first step that
// needs it computes it for every frame and leaves it in the build's intermediates, kSynthFolder/NAME.foam
// in the output's folder; the other frames' steps, threads of the same build or a plan's processes, read
// their frame from there. The build removes it once every frame is packed.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "heightpack/bake/manifest.hpp"
#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"

#include "build/build_common.hpp"

namespace heightpack::detail {

// The time of frame f of a synthesised sea: f x loop / frames, or 0 for a single frame (as `synth`).
inline double synthFrameTime(const SynthSource& sea, int frame) {
    return sea.frames > 1 ? frame * sea.spectrum.loopPeriod / sea.frames : 0.0;
}

// One sea's foam loop: what it is made from, and the file it is kept in.
struct FoamLoop {
    SynthSource sea;   // spectrum, frames, foam options and the choppiness whose Jacobian foams
    std::string file;  // relative to the output's folder: kSynthFolder/NAME.foam
    std::string key;   // cacheKey of everything that shapes it: a file with another key is another loop
};

// The loop of sea (with foam), kept as kSynthFolder/NAME.foam; version is part of its key.
FoamLoop foamLoopOf(const SynthSource& sea, const std::string& name, const std::string& version);

// Frame `frame`'s foam coverage (one channel, 0..1), bit for bit the channel Foam `synth --foam` writes
// for it: read from the loop's file inside folder when the file holds this key and the frame's bytes hash
// to what it records; else, under a lock on the file, found there after all (another step made it while
// this one waited) or computed for every frame and written (atomically). progress gets stage "foam" only
// while the loop is computed. Fails with CannotWrite when the file cannot be written.
Result<Image> foamLoopFrame(const FoamLoop& loop, const std::filesystem::path& folder, int frame, int threads,
                            const ProgressFn& progress);

// Every frame of the loop, computed and written to path (atomically) whatever is there: a plan's action
// that makes the loop alone, for the frames' actions to declare and read (Bazel).
Status writeFoamLoop(const FoamLoop& loop, const std::filesystem::path& path, int threads, const ProgressFn& progress);

// The files foamLoopFrame may leave, relative to the output's folder: the loop and its lock.
std::vector<std::string> foamLoopFiles(const FoamLoop& loop);

}  // namespace heightpack::detail
