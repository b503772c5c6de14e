// Internal: small text helpers for error messages and file names.
#pragma once

#include <cctype>
#include <filesystem>
#include <string>

namespace heightpack::detail {

// The first line of a library's message, without trailing spaces or periods: errors are one line.
inline std::string firstLine(std::string text) {
    const auto end = text.find('\n');
    if (end != std::string::npos) text.resize(end);
    while (!text.empty() && (text.back() == ' ' || text.back() == '.')) text.pop_back();
    return text;
}

// A file name's extension in lower case, with its dot (".exr"); empty when it has none. Formats are
// chosen and checked by it, and "MAP.EXR" is an EXR too.
inline std::string lowerExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

}  // namespace heightpack::detail
