#include "heightpack/bake/build/depfile.hpp"

namespace heightpack {

std::string depfileText(const std::string& target, const std::vector<std::string>& dependencies) {
    auto escape = [](const std::string& path) {
        std::string out;
        for (char c : path) {
            if (c == ' ' || c == '#' || c == '\\') out += '\\';
            if (c == '$') out += '$';
            out += c;
        }
        return out;
    };
    std::string text = escape(target) + ":";
    for (const std::string& d : dependencies) text.append(" \\\n  ").append(escape(d));
    return text + "\n";
}

}  // namespace heightpack
