// heightpack: dispatches to one subcommand, turns every failure into a one-line error and an exit code.
#include <csignal>
#include <iostream>
#include <vector>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "heightpack/io/files.hpp"
#include "heightpack/version.hpp"

#include "command.hpp"

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

    CLI::App app{"heightpack: water height maps to tileable, mip-chained, 4-neighbour packed RGBA32F textures"};
    app.name("heightpack");  // the usage lines say heightpack, not the path it was run by
    app.set_version_flag("--version", std::string("heightpack ") + heightpack::kVersion);
    app.require_subcommand(1);
    app.footer(
        "Examples:\n"
        "  heightpack pack examples/maps/swell.png -o out/swell.exr\n"
        "  heightpack normal examples/maps/ripple.png --tile-size 8m --height 0.15m -o out/ripple_n.exr\n"
        "  heightpack fresnel --ior 1.333 -o out/fresnel.exr\n"
        "  heightpack check examples/maps/painted_not_tileable.png --preview out/painted_check.png\n"
        "  heightpack tile examples/maps/painted_not_tileable.png -o out/painted_tiled.png\n"
        "  heightpack info out/swell.exr\n"
        "  heightpack build examples/ocean.toml -o out/ocean\n"
        "Run 'heightpack <command> --help' for a command's options.\n"
        "Exit codes: 0 done, 1 a check failed, 2 usage error, 3 bad input, 4 cannot write output, 70 internal error.\n");

    std::vector<std::unique_ptr<Command>> commands;
    commands.push_back(makePackCommand());
    commands.push_back(makeNormalCommand());
    commands.push_back(makeFresnelCommand());
    commands.push_back(makeCheckCommand());
    commands.push_back(makeTileCommand());
    commands.push_back(makeSynthCommand());
    commands.push_back(makeBuildCommand());
    commands.push_back(makeInfoCommand());
    std::vector<CLI::App*> subcommands;
    for (auto& command : commands) subcommands.push_back(command->attach(app));

    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);  // --help, --version: printed by CLI11 for the chosen subcommand
    } catch (const CLI::ParseError& e) {
        std::string where = "heightpack";
        for (CLI::App* sub : subcommands)
            if (sub->parsed()) where += " " + sub->get_name();
        printError({heightpack::ErrorKind::Internal, {}, e.what(), "see '" + where + " --help'"});
        return static_cast<int>(ExitCode::Usage);
    }

    try {
        for (size_t i = 0; i < commands.size(); ++i)
            if (subcommands[i]->parsed()) return static_cast<int>(commands[i]->run());
    } catch (const std::bad_alloc&) {
        printError({heightpack::ErrorKind::Internal, {}, "out of memory", "try a smaller map or fewer --threads"});
    } catch (const std::exception& e) {
        printError({heightpack::ErrorKind::Internal, {}, std::string("internal error: ") + e.what(),
                    "please report this with the command line"});
    }
    return static_cast<int>(ExitCode::Internal);
}
