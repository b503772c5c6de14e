// Metadata written into texture headers.
#pragma once

#include <string>
#include <variant>

namespace heightpack {

// A header attribute: a string or a float.
struct ExrAttribute {
    std::string name;
    std::variant<std::string, float> value;
};

}  // namespace heightpack
