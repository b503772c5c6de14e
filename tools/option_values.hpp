// Option values a command reads beyond names: lengths with units, colours, finite ranges, the output
// format, and --channel.
#pragma once

#include <CLI/CLI.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "heightpack/io/files.hpp"
#include "heightpack/io/pixel_type.hpp"
#include "heightpack/io/read.hpp"

namespace heightpack::cli {

// --channel, as every command that reads heights takes it: r|g|b|a|luma, or a channel's name as the file
// lists it (height.Y, Z, depth).
CLI::Option* addChannelOption(CLI::App& cmd, std::string& channel);
// Sets load's channel choice from --channel's text; empty: automatic.
void applyChannel(const std::string& text, LoadOptions& load);

// Validators for option values; a bad value is a usage error (exit 2) naming the option.
// A positive length with an optional unit: "8m", "8" (metres), "15cm", "150mm", "2km".
std::optional<double> parseLength(const std::string& text);
// A length as parseLength reads it, at most maxMetres.
CLI::Validator lengthValidator(double maxMetres);
// --flag LENGTH bound to a field in metres: checked, and converted into the field once, while parsing; the
// field keeps its value when the option is not given.
CLI::Option* addLengthOption(CLI::App& cmd, const std::string& flags, double& metres, double maxMetres,
                             const std::string& description);
// One or two positive lengths up to maxMetres: "8m" or "8m,4m".
CLI::Validator lengthPairValidator(double maxMetres);
// A finite number in [lo, hi]; unlike CLI::Range it refuses NaN and infinities.
CLI::Validator finiteRange(double lo, double hi);
// A size in bytes: a whole number with an optional unit K, M, G or T (powers of 1024; "KiB", "KB", "k"
// read alike): "500M", "2G", "10GiB", "1048576".
std::optional<std::uint64_t> parseByteSize(const std::string& text);
CLI::Validator byteSizeValidator();
// A linear colour "r,g,b", each in [0,1].
std::optional<std::array<double, 3>> parseColour(const std::string& text);
CLI::Validator colourValidator();
// "0.02,0.10,0.16": a colour as parseColour reads it, two decimals.
std::string colourText(const std::array<double, 3>& colour);

// The format an output is written in (normal's NormalFormat, fresnel's RampFormat) from its extension,
// checked against --format when given (requested): .png is Png8; .exr, .ktx2 and .dds are the
// mip-mapped Exr, and a .ktx2 or .dds takes no --format. nullopt when the extension is none of these or
// the two disagree.
template <class Format>
std::optional<Format> outputFormat(std::optional<Format> requested, const std::string& output) {
    const std::optional<Container> container = containerForPath(output);
    if (requested && container && container != Container::Exr) return std::nullopt;
    const std::optional<Format> byName = container                          ? std::optional(Format::Exr)
                                         : lowerExtension(output) == ".png" ? std::optional(Format::Png8)
                                                                            : std::nullopt;
    return !requested || requested == byName ? byName : std::nullopt;
}

// The word a report gives for the format: png8, or the output's container (exr, ktx2, dds).
template <class Format>
const char* formatWord(Format format, const std::string& output) {
    return format == Format::Png8 ? nameOf(format) : containerName(containerForPath(output).value_or(Container::Exr));
}

}  // namespace heightpack::cli
