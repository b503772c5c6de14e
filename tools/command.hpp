// What every subcommand shares: exit codes, the common options, error and JSON printing, progress.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <memory>
#include <string>
#include <string_view>

#include "heightpack/result.hpp"

namespace heightpack::cli {

// The documented exit codes (README, "Exit codes").
enum class ExitCode : int {
    Ok = 0,
    CheckFailed = 1,  // a check ran and the input failed it
    Usage = 2,        // the command line is wrong
    BadInput = 3,     // unreadable, unsupported, corrupt, NaN, wrong size
    CannotWrite = 4,  // the output cannot be written
    Internal = 70,    // a bug
};

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
    // Prints a JSON document on stdout, one object, newline-terminated.
    static void printJson(const nlohmann::json& document);
    // Whether a human-readable summary should go to stdout.
    bool chatty() const { return !common_.quiet && !common_.json; }

    CommonOptions common_;
};

std::unique_ptr<Command> makePackCommand();
std::unique_ptr<Command> makeInfoCommand();

// A one-line progress display on stderr, shown only on a terminal and never with --quiet.
class Progress {
public:
    Progress(bool enabled, std::string label);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;
    void update(std::string_view stage, double fraction);

private:
    bool enabled_;
    std::string label_;
    int lastPercent_ = -1;
    std::string lastStage_;
};

// "1.5 MiB", "312 KiB": a size for people.
std::string humanBytes(unsigned long long bytes);

}  // namespace heightpack::cli
