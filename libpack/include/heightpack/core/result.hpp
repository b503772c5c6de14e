// Errors as values: libpack never prints or exits; a failing call returns an Error that the caller
// (the CLI, the viewer, an engine) turns into text, an exit code or an exception of its own.
#pragma once

#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace heightpack {

// What kind of failure it was; the CLI maps each to its documented exit code.
enum class ErrorKind {
    BadInput,     // unreadable, unsupported, corrupt, NaN, wrong size: the input must change
    CannotWrite,  // the output cannot be written where asked
    // Options that cannot go together (or ask of a container what it cannot hold): the command line or
    // manifest must change, whatever the input. The library is the one judge of these; shells word them.
    InconsistentOptions,
    Internal,     // a bug or an unexpected library failure
};

// A remedy that the library knows but does not word: the library never names a command-line flag or a
// manifest key for it, each shell does (the CLI in its flags, the manifest build in its keys, the viewer
// in its own flags). Error::hint holds the library's neutral words for it; fixArgs the values the
// wording needs, as listed here.
enum class Fix {
    None,                   // the hint says it all
    ChooseChannel,          // a colour input: say which channel holds the heights (r, g, b, a, luma or a name)
    ChooseExistingChannel,  // the chosen channel is not in the file
    ResizeToPowerOfTwo,     // resample to power-of-two sides; fixArgs: {"WxH"}, the sides it would get
    ResizeOrLevelZeroOnly,  // as ResizeToPowerOfTwo, or write level 0 alone as an 8-bit PNG; fixArgs: {"WxH"}
    RenamePlainOutput,      // the unpacked chain's output is the packed output
    FewerJobs,              // out of memory: fewer jobs or threads at once
    WriteFloat,             // heights that integer samples cannot hold: write float samples
    MakeTileable,           // a map that must tile does not: make it tile with `heightpack tile`; fixArgs:
                            // {input, output, filter ("" for the default), threshold ("" for the default),
                            // channel ("" for none: the manifest's channel, r, g, b, a, luma or a name),
                            // the manifest's source for the tiled map (relative to the manifest),
                            // "sequence" when the input is one frame of a sequence (else "")}
    AddShift,               // shift asked of a map without it: make the map with its Dx, Dy
                            // channels (a synthesised EXR), or leave the shift out
    AddFoam,                // foam coverage asked of a map without it: make the map with its Foam channel
                            // (a synthesised EXR with foam), or leave the foam out
    OnePlainChain,          // a second plain chain asked beside a plain layout's output: ask for it once
    CompanionsNeedExr,      // shift or foam asked of synth's flat output that is no EXR (a PNG or
                            // TIFF has no further channels): write an EXR; fixArgs: {"shift" or "foam"}
    RgbNormalsInPng,        // xy normals asked of an 8-bit PNG, which has no mip levels: store rgb
    RgbNormalsForAlpha,     // xy normals asked with something in alpha, which two channels leave no room for
    VarianceNeedsLevels,    // slope variance in alpha asked of a one-level PNG: write a mip-mapped texture
    ManifestReference,      // a manifest key or value is wrong: the manifest reference (docs/manifest.md, installed
                            // with heightpack's documentation) lists every key; fixArgs: {what to do first, or ""}
};

struct Error {
    ErrorKind kind = ErrorKind::Internal;
    std::string path;  // the file it is about; may be empty
    std::string what;  // what is wrong, lower case, no trailing period
    std::string hint;  // what to do about it, in neutral words (no flags, no keys); may be empty
    Fix fix = Fix::None;               // the remedy, for a shell to word in its own terms
    std::vector<std::string> fixArgs{};  // what that wording needs (see Fix)
};

inline Error badInput(std::string path, std::string what, std::string hint = {}) {
    return {ErrorKind::BadInput, std::move(path), std::move(what), std::move(hint)};
}
inline Error cannotWrite(std::string path, std::string what, std::string hint = {}) {
    return {ErrorKind::CannotWrite, std::move(path), std::move(what), std::move(hint)};
}
inline Error inconsistentOptions(std::string path, std::string what, std::string hint = {}) {
    return {ErrorKind::InconsistentOptions, std::move(path), std::move(what), std::move(hint)};
}
// The error with a remedy a shell words (hint stays the neutral words).
inline Error withFix(Error error, Fix fix, std::vector<std::string> fixArgs = {}) {
    error.fix = fix;
    error.fixArgs = std::move(fixArgs);
    return error;
}

// Either a value or an Error, like C++23's std::expected.
template <class T>
class [[nodiscard]] Result {
public:
    Result(T value) : state_(std::move(value)) {}
    Result(Error error) : state_(std::move(error)) {}

    bool ok() const { return state_.index() == 0; }
    explicit operator bool() const { return ok(); }

    T& value() & { return std::get<0>(state_); }
    const T& value() const& { return std::get<0>(state_); }
    T&& value() && { return std::get<0>(std::move(state_)); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    T& operator*() { return value(); }
    const T& operator*() const { return value(); }

    const Error& error() const { return std::get<1>(state_); }

private:
    std::variant<T, Error> state_;
};

// The result of a call that returns nothing but may fail.
struct Done {};
using Status = Result<Done>;

}  // namespace heightpack
