// Internal: small text helpers for error messages.
#pragma once

#include <string>

namespace heightpack::detail {

// The first line of a library's message, without trailing spaces or periods: errors are one line.
inline std::string firstLine(std::string text) {
    const auto end = text.find('\n');
    if (end != std::string::npos) text.resize(end);
    while (!text.empty() && (text.back() == ' ' || text.back() == '.')) text.pop_back();
    return text;
}

}  // namespace heightpack::detail
