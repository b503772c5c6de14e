// The build's state file (.heightpack-build.json beside the outputs) and the hashes it records: for
// each output, the key it was made with, the output's own hash and the key of the check that passed.
#pragma once

#include <map>
#include <string>

#include "heightpack/core/result.hpp"

namespace heightpack {

inline constexpr int kBuildStateFormat = 1;

struct BuildStateEntry {
    std::string key;      // cache key the output was made with
    std::string hash;     // XXH3-128 of the output's bytes
    std::string checked;  // key of the tileability check that passed on its source; empty if none
    bool operator==(const BuildStateEntry&) const = default;
};
using BuildState = std::map<std::string, BuildStateEntry>;  // output (relative to the folder) -> entry

// The state from the text of a state file. Anything not exactly as buildStateText writes it (not JSON,
// truncated, a field of another type, another format) gives an empty state, never an error: a damaged
// state file only means everything is rebuilt.
BuildState parseBuildState(const std::string& text);
// parseBuildState of the file at path; empty when it is missing or unreadable.
BuildState readBuildState(const std::string& path);
// The state file's text: JSON, outputs in name order, ending with a newline.
std::string buildStateText(const BuildState& state);

// XXH3-128 of text, 32 lower-case hex digits.
std::string hashText(const std::string& text);
// XXH3-128 of a file's bytes, streamed; BadInput when it cannot be read (or is not a regular file).
Result<std::string> hashFile(const std::string& path);

}  // namespace heightpack
