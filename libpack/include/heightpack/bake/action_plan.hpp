// The build as hermetic actions for an executor that runs them (Ninja, or a farm that runs Ninja files):
// one action per output file (per frame and per cascade of a synthesised sea), each a `heightpack build
// MANIFEST -o DIR --only OUTPUT` with every file it reads and writes, and per material a last action that
// writes the build state and material.json once every output is there. Ninja then decides what to run
// from timestamps and runs it on as many cores or machines as it has; heightpack needs no scheduler.
#pragma once

#include <string>
#include <vector>

#include "heightpack/bake/manifest.hpp"
#include "heightpack/core/names.hpp"

namespace heightpack {

enum class PlanFormat { Ninja, Json };

template <>
struct NameTable<PlanFormat> {
    static constexpr EnumName<PlanFormat> entries[] = {
        {PlanFormat::Ninja, "ninja", "a Ninja file: ninja -f PLAN -j N"},
        {PlanFormat::Json, "json", "the actions as JSON, for an executor of one's own"},
    };
};

struct BuildAction {
    // What the action makes: BuildOptions::only for `manifest` built into `folder` (an output's name, or
    // kMaterialFile for the last action). The shell words it as its command (the library names no flag).
    std::string manifest, folder, only;
    std::vector<std::string> command;  // argv, the program first: filled by the shell
    std::vector<std::string> inputs;   // every file the command reads (the program too)
    std::vector<std::string> outputs;  // every file it writes
    std::string description;           // "bake ocean: swell.exr"
};

// The actions that build `manifests` into `output` (as `heightpack build` would: one manifest into output
// itself, several into output/NAME) with the program `executable` (an input of every action). Paths are
// as given: an executor runs the actions from the folder the plan was made in.
std::vector<BuildAction> planActions(const std::vector<Manifest>& manifests, const std::string& output,
                                     const std::string& executable, const std::string& version);

// The actions as a Ninja file (one rule per action kind, paths escaped; `ninja -f FILE` runs them) and as
// JSON ({"actions": [{"command", "inputs", "outputs", "description"}]}).
std::string ninjaFile(const std::vector<BuildAction>& actions);
std::string actionsJson(const std::vector<BuildAction>& actions);

}  // namespace heightpack
