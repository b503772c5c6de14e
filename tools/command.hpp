// What every subcommand shares: exit codes, the common options, error and JSON printing, progress.
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
#include "heightpack/core/tileable.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/read.hpp"

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
    // Prints a usage error about this command ("... (see 'heightpack NAME --help')") and returns 2.
    ExitCode usage(const std::string& what) const;
    // An output a command is about to write, and what it may be called.
    struct OutputRule {
        std::string path;
        std::string option;                   // "-o", "--preview": named in messages
        std::vector<std::string> extensions;  // lower case, with the dot: {".exr", ".png"}
    };
    // Judges every output before any input is read or anything is written: the path is not empty
    // (exit 2); nothing already there is a folder, link, device or read-only (exit 4, from
    // checkWritable); its extension is one the command writes faithfully (exit 2, naming them); it is
    // not the same file as any input (device and inode: links and other spellings count) nor as another
    // output (exit 2). Prints the error and returns its code, or Ok when every output passes.
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

// A stage of a job and its share of the whole job's time, for Progress.
struct ProgressStage {
    std::string_view name;
    double weight;
};

// A one-line progress display on stderr, shown only on a terminal and never with --quiet. The bar
// shows the whole job: with stages, a stage's fraction counts toward the stages before it plus its own
// share; without, update's fraction is the whole. The percentage shown never goes down. At most one
// bar is on screen; printError, printJson and clearProgressLine() remove it before other output.
class Progress {
public:
    Progress(bool enabled, std::string label, std::vector<ProgressStage> stages = {});
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;
    void update(std::string_view stage, double fraction);
    // Removes the line, so ordinary output can follow; the next update draws it again.
    void clear();

private:
    bool enabled_;
    std::string label_;
    std::vector<ProgressStage> stages_;
    int shownPercent_ = -1;  // on screen now; -1 when the line is clear
    int highestPercent_ = 0;
    std::string lastStage_;
};

// Clears the progress line on stderr if one is shown: call before printing anything else.
void clearProgressLine();

// Holds what goes to stdout until release(): a run whose outputs are staged says "wrote X" only once
// X is in place. Destroyed unreleased (a later frame failed), it drops what it held.
class HeldStdout {
public:
    explicit HeldStdout(bool hold);
    ~HeldStdout();
    HeldStdout(const HeldStdout&) = delete;
    HeldStdout& operator=(const HeldStdout&) = delete;
    // Prints what was held and stops holding.
    void release();

private:
    std::ostringstream held_;
    std::streambuf* original_ = nullptr;  // std::cout's own buffer while holding
};

// --channel, as every command that reads heights takes it: r|g|b|a|luma, or a channel's name as the file
// lists it (height.Y, Z, depth).
CLI::Option* addChannelOption(CLI::App& cmd, std::string& channel);
// Sets load's channel choice from --channel's text; empty: automatic.
void applyChannel(const std::string& text, LoadOptions& load);
// Says which channel the heights came from when that may surprise: "  note: ..." on stdout.
void printChannelNote(const SourceInfo& source);
// {"used": name, "note": text or null}, for --json.
nlohmann::json channelJson(const SourceInfo& source);

// What --resize pow2 did to a width x height map: the new size, the change of aspect, and the nearest
// powers of two per side (the size to export at to keep the shape). One line, no newline.
std::string resizeNote(int fromWidth, int fromHeight, int toWidth, int toHeight);
nlohmann::json resizeJson(int fromWidth, int fromHeight, int toWidth, int toHeight);

// One edge pair's seam scores as JSON: measured, value, slope, pass. A score is a number, or the string
// "inf" when it is infinite (README, "Seam scores"); an unmeasured pair is {"measured": false}.
nlohmann::json seamScoreJson(const SeamScore& score, double threshold);
// A chain's per-level scores: [{level, width, height, leftRight, topBottom, pass}, ...].
nlohmann::json seamLevelsJson(const std::vector<LevelSeams>& levels, double threshold);
// The first failing edge: {level, width, height, edge, kind, score, text}, or null.
nlohmann::json seamFailureJson(const std::optional<SeamFailure>& failure, double threshold);

// "1.5 MiB", "312 KiB": a size for people.
std::string humanBytes(unsigned long long bytes);

// Validators for option values; a bad value is a usage error (exit 2) naming the option.
// A positive length with an optional unit: "8m", "8" (metres), "15cm", "150mm", "2km".
std::optional<double> parseLength(const std::string& text);
// A length as parseLength reads it, at most maxMetres.
CLI::Validator lengthValidator(double maxMetres);
// One or two positive lengths up to maxMetres: "8m" or "8m,4m".
CLI::Validator lengthPairValidator(double maxMetres);
// A finite number in [lo, hi]; unlike CLI::Range it refuses NaN and infinities.
CLI::Validator finiteRange(double lo, double hi);
// A linear colour "r,g,b", each in [0,1].
std::optional<std::array<double, 3>> parseColour(const std::string& text);
CLI::Validator colourValidator();
// "0.02,0.10,0.16": a colour as parseColour reads it, two decimals.
std::string colourText(const std::array<double, 3>& colour);

// The output format the output's extension says ("exr" for .exr, "png8" for .png, "ktx2", "dds"), checked
// against an explicit --format value (exr or png8; none with a .ktx2 or .dds). Empty when the extension is
// none of these or the two disagree.
std::string outputFormat(const std::string& requested, const std::string& output);

}  // namespace heightpack::cli
