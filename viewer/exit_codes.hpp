// heightpack-view's documented exit codes (--help, the man page, docs/viewer.md), and the one place that
// turns an error into its message and code. The codes agree with the CLI's contract where the meanings overlap.
#pragma once

#include <array>
#include <cstdio>
#include <string>

#include "heightpack/core/result.hpp"
#include "hints.hpp"

namespace heightpack::view {

enum class ExitCode : int {
    Ok = 0,
    Usage = 2,        // the command line is wrong
    BadInput = 3,     // a map, normal map, Fresnel ramp, foam texture or material.json cannot be used
    CannotWrite = 4,  // the --screenshot PNG cannot be written
    // No display, no OpenGL 3.3 core context or no render target of the asked size: the machine cannot
    // draw, the inputs and the viewer are fine. Apart from 70 so a script can tell "run it elsewhere"
    // (under xvfb-run, with Mesa) from a bug; the CLI never draws, so it has no such code.
    NoOpenGL = 5,
    Internal = 70,    // a bug: an embedded shader that does not build, or an unexpected library failure
};

// What each code means, for --help's footer and the man page's EXIT STATUS.
struct ExitCodeMeaning {
    ExitCode code;
    const char* meaning;
};
inline constexpr std::array<ExitCodeMeaning, 6> kExitCodeMeanings{{
    {ExitCode::Ok, "done"},
    {ExitCode::Usage, "usage error"},
    {ExitCode::BadInput, "bad input: a map, sequence frame, normal map, Fresnel ramp, foam texture or material.json"},
    {ExitCode::CannotWrite, "cannot write the screenshot or the grid heights"},
    {ExitCode::NoOpenGL, "no usable OpenGL: no display, no OpenGL 3.3 core context (window or EGL), no render target of "
                         "that --size, no ASTC in the context for an ASTC file (run it under xvfb-run, or --headless "
                         "with Mesa's EGL)"},
    {ExitCode::Internal, "internal: a shader that does not build, or a bug"},
}};

inline ExitCode exitCodeFor(ErrorKind kind) {
    switch (kind) {
        case ErrorKind::BadInput: return ExitCode::BadInput;
        case ErrorKind::CannotWrite: return ExitCode::CannotWrite;
        case ErrorKind::InconsistentOptions: return ExitCode::Usage;
        case ErrorKind::Internal: return ExitCode::Internal;
    }
    return ExitCode::Internal;
}

// Prints "heightpack-view: error: <what> (<hint>)" and returns code.
inline int fail(const std::string& what, const std::string& hint, ExitCode code) {
    if (hint.empty()) std::fprintf(stderr, "heightpack-view: error: %s\n", what.c_str());
    else std::fprintf(stderr, "heightpack-view: error: %s (%s)\n", what.c_str(), hint.c_str());
    return static_cast<int>(code);
}

// A library error: "heightpack-view: error: <path>: <what> (<hint>)", the hint in the viewer's own flags
// (viewerHint), with the code for its kind.
inline int fail(const Error& error) {
    return fail(error.path.empty() ? error.what : error.path + ": " + error.what, viewerHint(error),
                exitCodeFor(error.kind));
}

}  // namespace heightpack::view
