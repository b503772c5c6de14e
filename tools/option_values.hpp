// Option values a command reads beyond names: lengths with units, colours, finite ranges, the output
// format, and --channel.
#pragma once

#include <CLI/CLI.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <string>

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

// The output format the output's extension says ("exr" for .exr, "png8" for .png, "ktx2", "dds"), checked
// against an explicit --format value (exr or png8; none with a .ktx2 or .dds). Empty when the extension is
// none of these or the two disagree.
std::string outputFormat(const std::string& requested, const std::string& output);

}  // namespace heightpack::cli
