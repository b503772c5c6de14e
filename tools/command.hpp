// What every subcommand shares: exit codes, the common options, error and JSON printing. The rest a
// command uses is one file per concern, included here: progress.hpp (the progress bar, held stdout),
// option_values.hpp (lengths, colours, ranges, --channel) and report_json.hpp (what a run reports).
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <array>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "heightpack/core/result.hpp"
#include "heightpack/core/tile/tileable.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/read.hpp"

#include "exit_codes.hpp"
#include "option_values.hpp"
#include "progress.hpp"
#include "report_json.hpp"

namespace heightpack::cli {

ExitCode exitCodeFor(ErrorKind kind);

// Prints the one-line error: "heightpack: error: <path>: <what> (<hint>)".
void printError(const Error& error);

// Options every command takes.
struct CommonOptions {
    bool json = false;
    bool quiet = false;
    int threads = 0;  // 0 = all cores
};

// A subcommand: attach() declares it and its options; run() is called when it was chosen.
class Command {
public:
    virtual ~Command() = default;
    virtual CLI::App* attach(CLI::App& app) = 0;
    virtual ExitCode run() = 0;

protected:
    // Adds --json, --quiet and --threads to cmd, bound to common_.
    void addCommonOptions(CLI::App& cmd);
    // Prints the error and returns its exit code.
    ExitCode fail(const Error& error) const;
    // Prints a usage error about this command ("... (see 'heightpack NAME --help')") and returns 2.
    ExitCode usage(const std::string& what) const;
    // An output a command is about to write, and what it may be called.
    struct OutputRule {
        std::string path;
        std::string option;                   // "-o", "--preview": named in messages
        std::vector<std::string> extensions;  // lower case, with the dot: {".exr", ".png"}
        // Written under a temporary name (StagedOutputs) that the job sees instead of this one.
        bool staged = false;
    };
    // Judges every output before any input is read or anything is written: the path is not empty
    // (exit 2); it is not the same file as any input (device and inode: links and other spellings count)
    // nor as another output, and its extension is one the command writes faithfully (exit 2, naming them).
    // Whether it can be written (nothing already there is a folder, link, device or read-only: exit 4) is
    // the job's to judge, before it reads its input; only a staged output, whose name the job never sees,
    // and a name refused here (so the error names what is really there) are judged with checkWritable
    // here. Prints the error and returns its code, or Ok when every output passes.
    ExitCode checkOutputs(const std::vector<std::string>& inputs, const std::vector<OutputRule>& outputs) const;
    // Prints a JSON document on stdout, one object, newline-terminated.
    static void printJson(const nlohmann::json& document);
    // Whether a human-readable summary should go to stdout.
    bool chatty() const { return !common_.quiet && !common_.json; }

    CommonOptions common_;
    std::string name_;  // the subcommand's name, for messages
};

std::unique_ptr<Command> makePackCommand();
std::unique_ptr<Command> makeInfoCommand();
std::unique_ptr<Command> makeNormalCommand();
std::unique_ptr<Command> makeFresnelCommand();
std::unique_ptr<Command> makeCheckCommand();
std::unique_ptr<Command> makeTileCommand();
std::unique_ptr<Command> makeSynthCommand();
std::unique_ptr<Command> makeBuildCommand();

}  // namespace heightpack::cli
