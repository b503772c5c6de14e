// The viewer's words for a remedy the library reports (see heightpack::Fix): the viewer's own flags.
#pragma once

#include <string>

#include "heightpack/core/result.hpp"

namespace heightpack::view {

// What to do about error, in heightpack-view's flags; the library's own hint when no flag of the viewer's
// is the remedy.
std::string viewerHint(const Error& error);

}  // namespace heightpack::view
