// Errors as values: libpack never prints or exits; a failing call returns an Error that the caller
// (the CLI, the viewer, an engine) turns into text, an exit code or an exception of its own.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace heightpack {

// What kind of failure it was; the CLI maps each to its documented exit code.
enum class ErrorKind {
    BadInput,     // unreadable, unsupported, corrupt, NaN, wrong size: the input must change
    CannotWrite,  // the output cannot be written where asked
    Internal,     // a bug or an unexpected library failure
};

struct Error {
    ErrorKind kind = ErrorKind::Internal;
    std::string path;  // the file it is about; may be empty
    std::string what;  // what is wrong, lower case, no trailing period
    std::string hint;  // what to do about it; may be empty
};

inline Error badInput(std::string path, std::string what, std::string hint = {}) {
    return {ErrorKind::BadInput, std::move(path), std::move(what), std::move(hint)};
}
inline Error cannotWrite(std::string path, std::string what, std::string hint = {}) {
    return {ErrorKind::CannotWrite, std::move(path), std::move(what), std::move(hint)};
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
