// The manifest build's words for a remedy (see Fix): manifest keys, not command-line flags.
#pragma once

#include "heightpack/core/result.hpp"

namespace heightpack::detail {

// The error with its remedy said in manifest keys (channel = "r", resize = true) and Fix::None, when a
// manifest key is the remedy; otherwise unchanged, its Fix left for the shell that runs the build.
Error inManifestTerms(Error error);

}  // namespace heightpack::detail
