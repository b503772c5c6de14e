// A bash completion script for a program, from what its command line says of itself (cli_text.hpp):
// its commands, each command's options, the names an option accepts where its validator lists them,
// nothing after an option that takes a number or a value of its own kind (LENGTH), file names everywhere
// else.
#pragma once

#include <string>
#include <vector>

#include "cli_text.hpp"

namespace heightpack::manual {

// program: the program's own options (and, without subcommands, its positionals); subcommands: its
// commands, each completed with its own options once typed.
std::string bashCompletion(const CommandText& program, const std::vector<CommandText>& subcommands);

}  // namespace heightpack::manual
