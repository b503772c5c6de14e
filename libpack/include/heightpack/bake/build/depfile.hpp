// Make-style dependency files, for a build system (CMake, Ninja, Make) that runs heightpack build.
#pragma once

#include <string>
#include <vector>

namespace heightpack {

// A Make-style depfile: "target: dep dep ...", one dependency per continued line, paths escaped for
// Make and Ninja (space, '#' and '\' with a backslash, '$' doubled).
std::string depfileText(const std::string& target, const std::vector<std::string>& dependencies);

}  // namespace heightpack
