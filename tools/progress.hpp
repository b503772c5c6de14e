// The progress bar on stderr and stdout held back until a run's outputs are in place.
#pragma once

#include <sstream>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

namespace heightpack::cli {

// A stage of a job and its share of the whole job's time, for Progress.
struct ProgressStage {
    std::string_view name;
    double weight;
};

// A one-line progress display on stderr, shown only on a terminal and never with --quiet. The bar
// shows the whole job: with stages, a stage's fraction counts toward the stages before it plus its own
// share; without, update's fraction is the whole. A stage named "NAME: what" counts as NAME, and the
// whole is shown (which attempt a long stage is at). The percentage shown never goes down. At most one
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

}  // namespace heightpack::cli
