// heightpack's documented exit codes (README, "Exit codes"), with what each means: --help's footer and
// the man pages' EXIT STATUS are both made from this table.
#pragma once

#include <array>
#include <string>

namespace heightpack::cli {

enum class ExitCode : int {
    Ok = 0,
    CheckFailed = 1,  // a check ran and the input failed it
    Usage = 2,        // the command line is wrong
    BadInput = 3,     // unreadable, unsupported, corrupt, NaN, wrong size
    CannotWrite = 4,  // the output cannot be written
    Internal = 70,    // a bug
};

struct ExitCodeMeaning {
    ExitCode code;
    const char* brief;    // in --help's one line
    const char* meaning;  // in a man page
};

inline constexpr std::array<ExitCodeMeaning, 6> kExitCodeMeanings{{
    {ExitCode::Ok, "done", "done"},
    {ExitCode::CheckFailed, "a check failed",
     "a check ran and the input failed it (check; build when a map that must tile does not)"},
    {ExitCode::Usage, "usage error",
     "usage error: an unknown option, a value that is not a finite number in its range, an output whose extension "
     "the command does not write, an output that is one of the inputs, options that cannot go together"},
    {ExitCode::BadInput, "bad input",
     "bad input: a manifest error, a file missing, unreadable, truncated or damaged, a format heightpack does not "
     "read, colour without --channel, NaN or Inf, not a power of two, too large"},
    {ExitCode::CannotWrite, "cannot write output",
     "the output cannot be written: no such folder, read-only, disk full, or something already there that is not "
     "a regular file"},
    {ExitCode::Internal, "internal error",
     "internal error (an output that would hold a NaN or infinite texel is never written)"},
}};

// "Exit codes: 0 done, 1 a check failed, ..., 70 internal error."
inline std::string exitCodesLine() {
    std::string line = "Exit codes:";
    for (const ExitCodeMeaning& e : kExitCodeMeanings)
        line += std::string(&e == &kExitCodeMeanings.front() ? " " : ", ") + std::to_string(static_cast<int>(e.code)) +
                " " + e.brief;
    return line + ".";
}

}  // namespace heightpack::cli
