#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <iostream>

namespace heightpack::cli {

namespace {
Progress* activeProgress = nullptr;  // the bar on screen, if any: the CLI draws from one thread
}  // namespace

void clearProgressLine() {
    if (activeProgress) activeProgress->clear();
}

Progress::Progress(bool enabled, std::string label, std::vector<ProgressStage> stages)
    : enabled_(enabled && ::isatty(STDERR_FILENO)), label_(std::move(label)), stages_(std::move(stages)) {}

Progress::~Progress() {
    clear();
    if (activeProgress == this) activeProgress = nullptr;
}

void Progress::clear() {
    if (enabled_ && shownPercent_ >= 0) {
        std::fflush(stdout);
        std::fprintf(stderr, "\r\033[K");
        std::fflush(stderr);
    }
    shownPercent_ = -1;
    lastStage_.clear();
}

void Progress::update(std::string_view stage, double fraction) {
    if (!enabled_) return;
    fraction = std::clamp(fraction, 0.0, 1.0);
    if (!stages_.empty()) {
        double total = 0, before = 0, share = 0;
        bool found = false;
        // "tile: quilt 2 of 3" counts as the stage "tile" and is shown whole.
        const std::string_view name = stage.substr(0, stage.find(':'));
        for (const ProgressStage& s : stages_) {
            if (s.name == name) found = true, share = s.weight;
            if (!found) before += s.weight;
            total += s.weight;
        }
        if (!found) return;  // a stage this bar does not count
        fraction = (before + share * fraction) / total;
    }
    // Floor, so 100% means done; never below what was shown, whatever order the stages report in.
    const int percent = std::max(highestPercent_, static_cast<int>(fraction * 100.0));
    if (percent == shownPercent_ && stage == lastStage_) return;
    if (activeProgress && activeProgress != this) activeProgress->clear();
    activeProgress = this;
    highestPercent_ = percent;
    shownPercent_ = percent;
    lastStage_ = stage;
    std::fflush(stdout);
    constexpr int kBar = 24;
    const int filled = percent * kBar / 100;
    std::fprintf(stderr, "\r\033[K%s: %-5.*s [%.*s%*s] %3d%%", label_.c_str(), static_cast<int>(stage.size()),
                 stage.data(), filled, "########################", kBar - filled, "", percent);
    std::fflush(stderr);
}

HeldStdout::HeldStdout(bool hold) {
    if (hold) original_ = std::cout.rdbuf(held_.rdbuf());
}

HeldStdout::~HeldStdout() {
    if (original_) std::cout.rdbuf(original_);
}

void HeldStdout::release() {
    if (!original_) return;
    std::cout.rdbuf(original_);
    original_ = nullptr;
    std::cout << held_.str() << std::flush;
}

}  // namespace heightpack::cli
