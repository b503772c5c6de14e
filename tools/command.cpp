#include "command.hpp"

#include <unistd.h>

#include <cstdio>
#include <iostream>

namespace heightpack::cli {

ExitCode exitCodeFor(ErrorKind kind) {
    switch (kind) {
        case ErrorKind::BadInput: return ExitCode::BadInput;
        case ErrorKind::CannotWrite: return ExitCode::CannotWrite;
        case ErrorKind::Internal: return ExitCode::Internal;
    }
    return ExitCode::Internal;
}

void printError(const Error& error) {
    std::string line = "heightpack: error: ";
    if (!error.path.empty()) line += error.path + ": ";
    line += error.what;
    if (!error.hint.empty()) line += " (" + error.hint + ")";
    // One line, whatever a library put in its message.
    for (char& c : line)
        if (c == '\n' || c == '\r') c = ' ';
    std::cerr << line << std::endl;
}

void Command::addCommonOptions(CLI::App& cmd) {
    cmd.add_flag("--json", common_.json, "print one JSON object on stdout instead of text");
    cmd.add_flag("-q,--quiet", common_.quiet, "print nothing but errors");
    cmd.add_option("--threads", common_.threads, "worker threads; 0 = all cores (output is identical either way)")
        ->check(CLI::Range(0, 1024));
}

ExitCode Command::fail(const Error& error) const {
    printError(error);
    return exitCodeFor(error.kind);
}

void Command::printJson(const nlohmann::json& document) { std::cout << document.dump(2) << std::endl; }

Progress::Progress(bool enabled, std::string label)
    : enabled_(enabled && ::isatty(STDERR_FILENO)), label_(std::move(label)) {}

Progress::~Progress() {
    if (enabled_ && lastPercent_ >= 0) std::fprintf(stderr, "\r\033[K");
}

void Progress::update(std::string_view stage, double fraction) {
    if (!enabled_) return;
    const int percent = static_cast<int>(fraction * 100.0 + 0.5);
    if (percent == lastPercent_ && stage == lastStage_) return;
    lastPercent_ = percent;
    lastStage_ = stage;
    constexpr int kBar = 24;
    const int filled = percent * kBar / 100;
    std::fprintf(stderr, "\r\033[K%s: %-5.*s [%.*s%*s] %3d%%", label_.c_str(), static_cast<int>(stage.size()),
                 stage.data(), filled, "########################", kBar - filled, "", percent);
    std::fflush(stderr);
}

std::string humanBytes(unsigned long long bytes) {
    char text[32];
    if (bytes >= (1ull << 20))
        std::snprintf(text, sizeof text, "%.1f MiB", bytes / double(1ull << 20));
    else if (bytes >= 1024)
        std::snprintf(text, sizeof text, "%.1f KiB", bytes / 1024.0);
    else
        std::snprintf(text, sizeof text, "%llu B", bytes);
    return text;
}

}  // namespace heightpack::cli
