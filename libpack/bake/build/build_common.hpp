// Internal: the small things every room of the build shares, so the rooms need not include each other.
#pragma once

#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <string_view>

namespace heightpack::detail {

// How a job reports progress: the stage and the fraction of it done.
using ProgressFn = std::function<void(std::string_view stage, double fraction)>;

// A number as key text: every digit a double holds, so two different values never print alike.
inline std::string number(double v) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", v);
    return text;
}

// The whole file at path; empty when it cannot be read (callers compare it with what they would write).
inline std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    if (in) text << in.rdbuf();
    return text.str();
}

}  // namespace heightpack::detail
