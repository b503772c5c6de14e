// heightpack-view_write_manual FOLDER: heightpack-view's man page and bash completion, from the command line
// the viewer parses (defineCommandLine), so they say what --help says. Run by the build.
#include <iostream>

#include "command_line.hpp"
#include "exit_codes.hpp"
#include "heightpack/version.hpp"
#include "write_manual.hpp"

int main(int argc, char** argv) {
    using namespace heightpack;
    if (argc != 2) {
        std::cerr << "usage: heightpack-view_write_manual FOLDER\n";
        return 2;
    }
    view::CommandLineValues values;
    CLI::App app;
    view::defineCommandLine(app, values);
    app.name("heightpack-view");
    manual::PageContext context{"heightpack-view", std::string("heightpack ") + kVersion, {}, {"heightpack(1)"}};
    for (const view::ExitCodeMeaning& e : view::kExitCodeMeanings)
        context.exits.push_back({static_cast<int>(e.code), e.meaning});
    // The exit codes of --help's footer have the page's EXIT STATUS instead.
    const manual::CommandText program =
        manual::describe(app, "heightpack-view", "heightpack-view", view::exitCodesFooter());
    return manual::writeManual(argv[1], program, {}, context);
}
