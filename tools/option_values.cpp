#include "option_values.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "heightpack/io/files.hpp"
#include "heightpack/io/pixel_type.hpp"

#include "hints.hpp"

namespace heightpack::cli {

CLI::Option* addChannelOption(CLI::App& cmd, std::string& channel) {
    const std::string names = joinedNames<ChannelSelect>(", ");
    return cmd.add_option("--channel", channel,
                          "where the height is in a colour image: " + names +
                              ", or a channel's name as the file lists it (height.Y, Z, depth); default: the only grey "
                              "channel, or Y, or R of a packed heightpack texture")
        ->check(CLI::Validator(
            [names](std::string& text) { return text.empty() ? "give a channel: " + names + " or a name" : std::string(); },
            "CHANNEL"));
}

void applyChannel(const std::string& text, LoadOptions& load) {
    if (text.empty()) {
        load.channel = ChannelSelect::Auto;
    } else if (const auto select = parseChannelSelect(text)) {
        load.channel = *select;
    } else {
        load.channel = ChannelSelect::Named;
        load.channelName = text;
    }
}

std::optional<double> parseLength(const std::string& text) {
    const char* begin = text.c_str();
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    if (end == begin || !std::isfinite(value) || value <= 0) return std::nullopt;
    const std::string unit(end);
    if (unit.empty() || unit == "m") return value;
    if (unit == "cm") return value / 100;
    if (unit == "mm") return value / 1000;
    if (unit == "km") return value * 1000;
    return std::nullopt;
}

namespace {

std::string numberText(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

bool lengthUpTo(const std::string& text, double maxMetres) {
    const auto v = parseLength(text);
    return v && *v <= maxMetres;
}

}  // namespace

CLI::Validator lengthValidator(double maxMetres) {
    return CLI::Validator(
        [maxMetres](std::string& text) {
            return lengthUpTo(text, maxMetres) ? std::string()
                                               : "'" + text + "' is not a positive length up to " + numberText(maxMetres) +
                                                     " m, like 8m, 15cm or 2km";
        },
        "LENGTH");
}

CLI::Option* addLengthOption(CLI::App& cmd, const std::string& flags, double& metres, double maxMetres,
                             const std::string& description) {
    return cmd.add_option_function<std::string>(flags, [&metres](const std::string& text) { metres = *parseLength(text); },
                                                description)
        ->check(lengthValidator(maxMetres));
}

CLI::Validator lengthPairValidator(double maxMetres) {
    return CLI::Validator(
        [maxMetres](std::string& text) {
            const auto comma = text.find(',');
            const bool ok = comma == std::string::npos ? lengthUpTo(text, maxMetres)
                                                       : lengthUpTo(text.substr(0, comma), maxMetres) &&
                                                             lengthUpTo(text.substr(comma + 1), maxMetres);
            return ok ? std::string()
                      : "'" + text + "' is not a positive length up to " + numberText(maxMetres) +
                            " m like 8m, or a pair like 8m,4m";
        },
        "LENGTH[,LENGTH]");
}

CLI::Validator finiteRange(double lo, double hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            const bool ok = !text.empty() && end != text.c_str() && *end == '\0' && std::isfinite(v) && v >= lo && v <= hi;
            return ok ? std::string() : "'" + text + "' is not a number from " + numberText(lo) + " to " + numberText(hi);
        },
        "NUMBER in [" + numberText(lo) + ", " + numberText(hi) + "]");
}

std::optional<std::uint64_t> parseByteSize(const std::string& text) {
    size_t digits = 0;
    while (digits < text.size() && std::isdigit(static_cast<unsigned char>(text[digits]))) ++digits;
    if (digits == 0 || digits > 15) return std::nullopt;  // 15 digits of bytes is far past any disk, and no overflow
    std::string unit = text.substr(digits);
    for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    const std::uint64_t value = std::stoull(text.substr(0, digits));
    if (unit.empty() || unit == "B") return value;
    const std::string prefixes = "KMGT";
    const size_t at = prefixes.find(unit[0]);
    const std::string rest = unit.substr(1);
    if (at == std::string::npos || !(rest.empty() || rest == "B" || rest == "IB")) return std::nullopt;
    const int shift = 10 * static_cast<int>(at + 1);
    if (value >= (std::uint64_t(1) << (63 - shift))) return std::nullopt;
    return value << shift;
}

CLI::Validator byteSizeValidator() {
    return CLI::Validator(
        [](std::string& text) {
            return parseByteSize(text) ? std::string() : "'" + text + "' is not a size such as 500M, 2G or 10GiB";
        },
        "SIZE");
}

std::optional<std::array<double, 3>> parseColour(const std::string& text) {
    std::array<double, 3> rgb{};
    const char* p = text.c_str();
    for (int i = 0; i < 3; ++i) {
        char* end = nullptr;
        rgb[i] = std::strtod(p, &end);
        if (end == p || !std::isfinite(rgb[i]) || rgb[i] < 0 || rgb[i] > 1) return std::nullopt;
        p = end;
        if (i < 2) {
            if (*p != ',') return std::nullopt;
            ++p;
        }
    }
    if (*p != '\0') return std::nullopt;
    return rgb;
}

CLI::Validator colourValidator() {
    return CLI::Validator(
        [](std::string& text) {
            return parseColour(text) ? std::string() : "'" + text + "' is not a colour r,g,b with each in [0,1]";
        },
        "R,G,B");
}

std::string colourText(const std::array<double, 3>& colour) {
    char text[64];
    std::snprintf(text, sizeof text, "%.2f,%.2f,%.2f", colour[0], colour[1], colour[2]);
    return text;
}

}  // namespace heightpack::cli
