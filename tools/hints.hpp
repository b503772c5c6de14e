// The command line's words for a remedy the library reports (see Fix): its own flags.
#pragma once

#include <string>

#include "heightpack/core/result.hpp"

namespace heightpack::cli {

// Where the manifest reference (docs/manifest.md) is: installed beside this program (its documentation
// folder as seen from its program folder, wherever the installed tree was put), else in the source tree
// this program was built from.
std::string manifestReference();
// What to do about error, in heightpack's flags; the library's own hint when it has no Fix.
std::string cliHint(const Error& error);
// A report's note followed by the remedy it points at (fix), in heightpack's flags.
std::string cliNote(const std::string& note, Fix fix);

}  // namespace heightpack::cli
