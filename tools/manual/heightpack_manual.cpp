// heightpack_write_manual FOLDER: heightpack's man pages and bash completion, from the command line the
// program parses (makeCommandLine), so they say what --help says. Run by the build.
#include <iostream>

#include "heightpack/version.hpp"

#include "command_line.hpp"
#include "exit_codes.hpp"
#include "write_manual.hpp"

int main(int argc, char** argv) {
    using namespace heightpack;
    if (argc != 2) {
        std::cerr << "usage: heightpack_write_manual FOLDER\n";
        return 2;
    }
    const std::unique_ptr<cli::CommandLine> line = cli::makeCommandLine();
    manual::PageContext context{"heightpack", std::string("heightpack ") + kVersion, {}, {"heightpack-view(1)"}};
    for (const cli::ExitCodeMeaning& e : cli::kExitCodeMeanings)
        context.exits.push_back({static_cast<int>(e.code), e.meaning});
    std::vector<manual::CommandText> commands;
    for (const CLI::App* sub : manual::subcommandsOf(line->app))
        commands.push_back(manual::describe(*sub, "heightpack " + sub->get_name(), "heightpack-" + sub->get_name()));
    // The exit codes of --help's footer have the page's EXIT STATUS instead.
    const manual::CommandText program = manual::describe(line->app, "heightpack", "heightpack", cli::exitCodesLine());
    return manual::writeManual(argv[1], program, commands, context);
}
