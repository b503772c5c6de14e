// heightpack: dispatches to one subcommand, turns every failure into a one-line error and an exit code.
#include <algorithm>
#include <csignal>
#include <iostream>
#include <string_view>
#include <vector>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "heightpack/io/files.hpp"

#include "command_line.hpp"

namespace {

// An interrupted run leaves no temporary file behind; outputs are only ever renamed into place whole.
extern "C" void onSignal(int sig) {
    heightpack::removePendingTemporaryFiles();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

// glibc serves every block over 32 MiB with its own mmap and unmaps it on free, so each of the 64-268 MB
// fields a command makes and drops (tile makes dozens at 4096^2) is paid for again in page faults and
// zeroed pages: a quarter of `tile`'s time. Kept in the heap instead, a freed field's pages are reused by
// the next one; peak memory is the same within 3%.
void keepLargeBlocksInTheHeap() {
#if defined(__GLIBC__)
    mallopt(M_MMAP_MAX, 0);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace

int main(int argc, char** argv) {
    using namespace heightpack::cli;
    keepLargeBlocksInTheHeap();
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, onSignal);

    const std::unique_ptr<CommandLine> line = makeCommandLine();
    CLI::App& app = line->app;
    // A word that names no command or option is said first, as itself: CLI11 would report a misspelt
    // required option as missing, and a misspelt one with a value as two unexpected words.
    if (const auto error = unknownWord(*line, std::vector<std::string>(argv + std::min(argc, 1), argv + argc))) {
        printError(*error);
        return static_cast<int>(ExitCode::Usage);
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        const int code = app.exit(e);  // --help, --version: printed by CLI11 for the chosen subcommand
        const bool verbose = std::find(argv, argv + argc, std::string_view("--verbose")) != argv + argc;
        if (code == 0 && verbose && dynamic_cast<const CLI::CallForVersion*>(&e)) return printFormatReport();
        return code;
    } catch (const CLI::ParseError& e) {
        printError(usageError(*line, e));
        return static_cast<int>(ExitCode::Usage);
    }

    try {
        for (size_t i = 0; i < line->commands.size(); ++i)
            if (line->subcommands[i]->parsed()) return static_cast<int>(line->commands[i]->run());
    } catch (const std::bad_alloc&) {
        printError({heightpack::ErrorKind::Internal, {}, "out of memory", "try a smaller map or fewer --threads"});
    } catch (const std::exception& e) {
        printError({heightpack::ErrorKind::Internal, {}, std::string("internal error: ") + e.what(),
                    "please report this with the command line"});
    }
    return static_cast<int>(ExitCode::Internal);
}
