// Running heightpack-view from the viewer tests: under its own virtual X server, with an environment
// that Mesa and the sanitizers agree on.
#pragma once

#include <string>
#include <vector>

#include "support/test_support.hpp"

namespace heightpack::test {

using ViewRun = ProcessResult;

// This process's environment for the viewer, less the variables named in `without`.
std::vector<std::string> viewerEnvironment(const std::vector<std::string>& without = {});

// Runs heightpack-view (HEIGHTPACK_VIEW_EXE) with args under xvfb-run.
ViewRun view(const std::vector<std::string>& args);

}  // namespace heightpack::test
