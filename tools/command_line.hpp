// heightpack's whole command line: the app with every command attached, and what is said about a command
// line CLI11 would refuse, in words a person can act on: the first word that names no command or option
// (with the one it was likely meant to be), an option given twice.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/core/result.hpp"

#include "command.hpp"

namespace heightpack::cli {

struct CommandLine {
    CLI::App app;
    std::vector<std::unique_ptr<Command>> commands;
    std::vector<CLI::App*> subcommands;  // subcommands[i] is commands[i]'s
};

// The app with pack, normal, fresnel, check, tile, synth, build and info attached (CLI::App does not move:
// hence the pointer).
std::unique_ptr<CommandLine> makeCommandLine();

// For --version --verbose: the formats heightpack decodes itself, and where the OpenImageIO module is and
// whether it loads (tested by loading it). The exit code: 0, or 70 when the module does not load.
int printFormatReport();

// The first word of args (the command line without the program's name) that names no command, or no
// option of the command chosen: a usage error "unknown command 'chek'" or "unknown option --tilesize"
// whose hint names the nearest command or option ("did you mean --tile-size?") when one is within two
// edits. Judged before CLI11 parses, so a misspelt option is not reported as the required one it was
// meant to be. nullopt when every word is known.
std::optional<Error> unknownWord(const CommandLine& line, const std::vector<std::string>& args);

// The usage error for what CLI11 refused (after unknownWord found nothing), in plain words where CLI11's
// are obscure: an option given twice is named with both values.
Error usageError(const CommandLine& line, const CLI::ParseError& e);

}  // namespace heightpack::cli
