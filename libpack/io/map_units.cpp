#include "heightpack/io/map_units.hpp"

#include <cmath>
#include <cstdlib>

namespace heightpack {

namespace {

enum class Kind { Positive, Number };

// The recorded value of key, if any: the whole text one finite number (positive for a length or a loop period).
Result<std::optional<double>> recorded(const Attributes& attributes, AttributeKey<float> key, Kind kind,
                                       const std::string& path) {
    const std::string text = findAttribute(attributes, key);
    if (text.empty()) return std::optional<double>{};
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    const bool number = end != text.c_str() && *end == '\0' && std::isfinite(v) && std::abs(v) <= 1e30;
    if (!number || (kind == Kind::Positive && !(v > 0.0)))
        return badInput(path,
                        std::string("its ") + key.name + " metadata '" + text.substr(0, 64) + "' is not " +
                            (kind == Kind::Positive ? "a positive number" : "a finite number"),
                        "remove or correct that metadata in the file");
    return std::optional<double>{v};
}

}  // namespace

Result<MapUnits> readMapUnits(const Attributes& attributes, const std::string& path) {
    MapUnits units;
    struct Field {
        AttributeKey<float> key;
        Kind kind;
        std::optional<double>* to;
    };
    for (const Field& f : {Field{attr::tileWidth, Kind::Positive, &units.tileWidth},
                           Field{attr::tileHeight, Kind::Positive, &units.tileHeight},
                           Field{attr::heightRange, Kind::Positive, &units.heightRange},
                           Field{attr::loopPeriod, Kind::Positive, &units.loopPeriod},
                           Field{attr::time, Kind::Number, &units.time}}) {
        auto value = recorded(attributes, f.key, f.kind, path);
        if (!value) return value.error();
        *f.to = *value;
    }
    return units;
}

}  // namespace heightpack
