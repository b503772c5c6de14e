// Writes a program's man pages and completion script into a folder, as `cmake --install` lays them out.
#pragma once

#include <string>
#include <vector>

#include "cli_text.hpp"
#include "man_page.hpp"

namespace heightpack::manual {

// Replaces folder with FOLDER/man1/PAGE.1 for the program and each subcommand, and
// FOLDER/completions/PROGRAM. The program's page sees also every command's, each command's the
// program's, and all context.seeAlso. Returns 0, or 1 after saying on stderr what could not be written.
int writeManual(const std::string& folder, const CommandText& program, const std::vector<CommandText>& subcommands,
                const PageContext& context);

}  // namespace heightpack::manual
