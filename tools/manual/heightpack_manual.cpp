// heightpack_write_manual FOLDER: heightpack's man pages and bash completion, from the command line the
// program parses (makeCommandLine), so they say what --help says. Run by the build.
#include <iostream>

#include "heightpack/version.hpp"

#include "command_line.hpp"
#include "exit_codes.hpp"
#include "hints.hpp"
#include "write_manual.hpp"

namespace {

void replaceAll(std::string& text, const std::string& from, const std::string& to) {
    for (size_t at = text.find(from); !from.empty() && at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
}

}  // namespace

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
    // --help names the manifest reference where this program finds it (from the build folder: the source
    // tree's); the installed page names where `cmake --install` puts it.
    for (manual::CommandText& command : commands) {
        for (manual::OptionText& option : command.options)
            replaceAll(option.description, cli::manifestReference(), HEIGHTPACK_INSTALLED_MANIFEST);
        for (std::string& note : command.notes) replaceAll(note, cli::manifestReference(), HEIGHTPACK_INSTALLED_MANIFEST);
    }
    // The exit codes of --help's footer have the page's EXIT STATUS instead.
    const manual::CommandText program = manual::describe(line->app, "heightpack", "heightpack", cli::exitCodesLine());
    return manual::writeManual(argv[1], program, commands, context);
}
