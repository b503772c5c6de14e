// A man(7) page of a command, in roff, from what its command line says of itself (cli_text.hpp).
#pragma once

#include <string>
#include <vector>

#include "cli_text.hpp"

namespace heightpack::manual {

struct ExitStatus {
    int code;
    std::string meaning;
};

// What every page of one program shares.
struct PageContext {
    std::string program;  // "heightpack": stripped from a description that starts "heightpack: "
    std::string version;  // "heightpack 0.1.0", in the page's header
    std::vector<ExitStatus> exits;
    std::vector<std::string> seeAlso;  // pages, "heightpack-view(1)"
};

// The page of command; a program with subcommands lists them, each with its own page.
std::string manPage(const CommandText& command, const std::vector<CommandText>& subcommands, const PageContext& context);

}  // namespace heightpack::manual
