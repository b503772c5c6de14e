// Internal: the build's plan, one Step per output file, translated from the manifest into the option
// structs of the jobs that make them.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/bake/build/build_report.hpp"
#include "heightpack/bake/check_job.hpp"
#include "heightpack/bake/manifest.hpp"

#include "build_common.hpp"

namespace heightpack::detail {

// One output file and how to make it.
struct Step {
    AssetReport report;
    bool mustTile = false;
    std::string optionsText;  // key text of every option that shapes the output
    std::string checkText;    // key text of every option that shapes the check
    CheckOptions check;
    std::function<Status(const std::string& output, int threads, const ProgressFn& progress)> make;
    // Files (relative to the material's output folder) that make may leave for other steps to read, such as a
    // synthesised sea's foam loop: removed once the whole build is done, never by one output's action.
    std::vector<std::string> intermediates;
    // Worked out while building:
    std::string checkKey;
    bool needBuild = false, needCheck = false;
    std::optional<Error> error;
};

// The steps of manifest m, in manifest order (a sequence gives one per frame); version is recorded in
// every output.
std::vector<Step> planSteps(const Manifest& m, const std::string& version);

// The files several of m's steps read and one may make for all (a synthesised sea's foam loop), as steps
// of their own for a plan that runs them as actions the others depend on: report.output is the file's
// path inside the output folder, as the steps that read it list it first among their intermediates.
std::vector<Step> planSharedSteps(const Manifest& m, const std::string& version);

// word as one word for /bin/sh, single-quoted, with '$' doubled for the executor that expands its own
// variables before the shell sees the command (Ninja's $var, Bazel's $(...)).
std::string quotedForExecutor(const std::string& word);

}  // namespace heightpack::detail
