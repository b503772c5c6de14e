// The build as hermetic actions for an executor that runs them (Ninja, Bazel, or a farm that runs either):
// one action per output file (per frame and per cascade of a synthesised sea), each a `heightpack build
// MANIFEST -o DIR --only OUTPUT` with every file it reads and writes, and per material a last action that
// writes the build state and material.json once every output is there. Ninja then decides what to run
// from timestamps and runs it on as many cores or machines as it has; heightpack needs no scheduler.
#pragma once

#include <string>
#include <vector>

#include "heightpack/bake/manifest.hpp"
#include "heightpack/core/names.hpp"
#include "heightpack/core/result.hpp"

namespace heightpack {

enum class PlanFormat { Ninja, Json, Bazel, BazelWorkspace };

template <>
struct NameTable<PlanFormat> {
    static constexpr EnumName<PlanFormat> entries[] = {
        {PlanFormat::Ninja, "ninja", "a Ninja file: ninja -f PLAN -j N"},
        {PlanFormat::Json, "json", "the actions as JSON, for an executor of one's own"},
        {PlanFormat::Bazel, "bazel", "a BUILD.bazel: one genrule per action, for bazel build //..."},
        {PlanFormat::BazelWorkspace, "bazel-workspace", "the WORKSPACE rule that makes this heightpack Bazel's tool"},
    };
};

struct BuildAction {
    // What the action makes: BuildOptions::only for `manifest` built into `folder` (an output's name, or
    // kMaterialFile for the last action). The shell words it as its command (the library names no flag).
    std::string manifest, folder, only;
    std::string material;              // the manifest's material name
    std::vector<std::string> command;  // argv, the program first: filled by the shell
    std::vector<std::string> inputs;   // every file the command reads (the program too)
    std::vector<std::string> outputs;  // every file it writes
    std::string description;           // "bake ocean: swell.exr"
};

// The actions that build `manifests` into `output` (as `heightpack build` would: one manifest into output
// itself, several into output/NAME) with the program `executable` (an input of every action). Paths are
// as given: an executor runs the actions from the folder the plan was made in. sandboxed is for an
// executor that gives each action only the files it declares (Bazel): what several actions read (a
// synthesised sea's foam loop) is made by an action of its own, an input of each of them, and left in
// the output folder, and each frame of a painted sequence declares every frame (which frames are there
// names the outputs). Otherwise the first action that needs the loop makes it and the last removes it
// (Ninja, which judges by time), and a frame declares its own file.
std::vector<BuildAction> planActions(const std::vector<Manifest>& manifests, const std::string& output,
                                     const std::string& executable, const std::string& version,
                                     bool sandboxed = false);

// The actions as a Ninja file (one rule per action kind, paths escaped; `ninja -f FILE` runs them) and as
// JSON ({"actions": [{"command", "inputs", "outputs", "description"}]}).
std::string ninjaFile(const std::vector<BuildAction>& actions);
std::string actionsJson(const std::vector<BuildAction>& actions);

// The actions as a BUILD.bazel for the package in the folder the plan was made in: one genrule per
// action, its inputs as srcs (files of the package, or outputs of earlier genrules), its outputs as outs,
// the program as the tool kBazelTool (bazelWorkspace). In each command, the first word (the program)
// becomes the tool's $(location) and a word naming the action's folder that folder under $(RULEDIR),
// where Bazel wants outputs. Every path must be a label of the package: relative, normalised, inside
// the folder, in the characters labels and shells take as they are; else InconsistentOptions naming it.
Result<std::string> bazelBuildFile(const std::vector<BuildAction>& actions);

// The label of the program in a Bazel workspace, and the WORKSPACE rule that makes the program at
// `executable` that label: a new_local_repository over the program's folder.
inline constexpr const char* kBazelTool = "@heightpack//:heightpack";
std::string bazelWorkspace(const std::string& executable);

}  // namespace heightpack
