// heightpack-view's command line: every option, its help and the footer, declared once, for main (which
// checks and converts what was typed) and for the build's man page and completion (viewer/manual.cpp).
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "app.hpp"

namespace heightpack::view {

// What the command line fills: the options that go straight into ViewerOptions, and the words main
// checks and converts after parsing.
struct CommandLineValues {
    ViewerOptions options;
    std::string size = "1280x720", camera, tiled, explosion, lookup = "trilinear", view = "shaded", tileSizes, amplitudes,
                choppiness;
    bool frustumOff = false;
    bool noBakedFoam = false;
    bool headless = false;
    float time = -1.0f;  // negative: the clock runs
};

// --lookup gather: gather-trilinear, trilinear as the packed lookup's default.
inline constexpr const char* kGatherAlias = "gather";

// --lookup's choices: the Lookup table's names and kGatherAlias.
std::vector<std::string> lookupChoices();

// "a.png, b.tif or c.exr" of the formats a --screenshot is written in.
std::string screenshotFormats();

// "Exit codes:" and one line a code (kExitCodeMeanings), wrapped at 100 columns under the meaning: the
// end of --help's footer.
std::string exitCodesFooter();

// Declares the description, --version, every option (bound to values) and the footer on app.
void defineCommandLine(CLI::App& app, CommandLineValues& values);

}  // namespace heightpack::view
