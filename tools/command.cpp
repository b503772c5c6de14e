#include "command.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "heightpack/io/files.hpp"
#include "heightpack/io/pixel_type.hpp"
#include "heightpack/io/read.hpp"

#include "hints.hpp"

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
    clearProgressLine();
    std::string line = "heightpack: error: ";
    if (!error.path.empty()) line += error.path + ": ";
    line += error.what;
    if (const std::string hint = cliHint(error); !hint.empty()) line += " (" + hint + ")";
    // One line, whatever a library put in its message.
    for (char& c : line)
        if (c == '\n' || c == '\r') c = ' ';
    std::cerr << line << std::endl;
}

void Command::addCommonOptions(CLI::App& cmd) {
    name_ = cmd.get_name();
    cmd.add_flag("--json", common_.json, "print one JSON object on stdout instead of text");
    cmd.add_flag("-q,--quiet", common_.quiet, "print nothing but errors");
    cmd.add_option("--threads", common_.threads, "worker threads; 0 = all cores (output is identical either way)")
        ->check(CLI::Range(0, 1024));
}

ExitCode Command::fail(const Error& error) const {
    printError(error);
    return exitCodeFor(error.kind);
}

ExitCode Command::usage(const std::string& what) const {
    printError({ErrorKind::Internal, {}, what, "see 'heightpack " + name_ + " --help'"});
    return ExitCode::Usage;
}

ExitCode Command::checkOutputs(const std::vector<std::string>& inputs, const std::vector<OutputRule>& outputs) const {
    namespace fs = std::filesystem;
    const std::string help = "see 'heightpack " + name_ + " --help'";
    auto refuse = [&](const std::string& path, const std::string& what, const std::string& hint) {
        printError({ErrorKind::Internal, path, what, hint + "; " + help});
        return ExitCode::Usage;
    };
    for (size_t i = 0; i < outputs.size(); ++i) {
        const OutputRule& o = outputs[i];
        if (o.path.empty()) return refuse(o.option + " ''", "the output path is empty", "give an output file name");
        for (const std::string& input : inputs)
            if (sameFile(input, o.path))
                return refuse(o.path, "is the input" + (input == o.path ? std::string() : " " + input + " (the same file)") +
                                          ": writing it would destroy the input",
                              "give " + o.option + " another file name");
        if (Status s = checkWritable(o.path); !s) return fail(s.error());
        const std::string ext = lowerExtension(o.path);
        if (std::find(o.extensions.begin(), o.extensions.end(), ext) == o.extensions.end()) {
            std::string list;
            for (const std::string& e : o.extensions) list += (list.empty() ? "" : ", ") + e;
            return refuse(o.path,
                          "'" + name_ + "' cannot write " + (ext.empty() ? "a file without an extension" : ext + " files") +
                              " faithfully",
                          o.option + " must end in " + list);
        }
        std::error_code ec;
        for (size_t j = 0; j < i; ++j)
            if (sameFile(outputs[j].path, o.path) ||
                fs::weakly_canonical(outputs[j].path, ec) == fs::weakly_canonical(o.path, ec))
                return refuse(o.path, "is also the " + outputs[j].option + " output", "give each output its own name");
    }
    return ExitCode::Ok;
}

void Command::printJson(const nlohmann::json& document) {
    clearProgressLine();
    std::cout << document.dump(2) << std::endl;
}

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

namespace {
nlohmann::json scoreNumber(double v) { return std::isinf(v) ? nlohmann::json(v > 0 ? "inf" : "-inf") : nlohmann::json(v); }
}  // namespace

nlohmann::json seamScoreJson(const SeamScore& s, double threshold) {
    if (!s.measured) return {{"measured", false}};
    return {{"measured", true}, {"value", scoreNumber(s.value)}, {"slope", scoreNumber(s.slope)},
            {"pass", seamPasses(s, threshold)}};
}

nlohmann::json seamLevelsJson(const std::vector<LevelSeams>& levels, double threshold) {
    nlohmann::json out = nlohmann::json::array();
    for (size_t i = 0; i < levels.size(); ++i)
        out.push_back({{"level", i}, {"width", levels[i].width}, {"height", levels[i].height},
                       {"leftRight", seamScoreJson(levels[i].leftRight, threshold)},
                       {"topBottom", seamScoreJson(levels[i].topBottom, threshold)},
                       {"pass", levelTiles(levels[i], threshold)}});
    return out;
}

nlohmann::json seamFailureJson(const std::optional<SeamFailure>& f, double threshold) {
    if (!f) return nullptr;
    return {{"level", f->level}, {"width", f->width}, {"height", f->height}, {"edge", seamEdgeName(f->edge)},
            {"kind", f->kind == SeamKind::Jump ? "jump" : "kink"}, {"score", scoreNumber(f->score)},
            {"text", describeSeamFailure(*f, threshold)}};
}

void Progress::update(std::string_view stage, double fraction) {
    if (!enabled_) return;
    fraction = std::clamp(fraction, 0.0, 1.0);
    if (!stages_.empty()) {
        double total = 0, before = 0, share = 0;
        bool found = false;
        for (const ProgressStage& s : stages_) {
            if (s.name == stage) found = true, share = s.weight;
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

CLI::Option* addChannelOption(CLI::App& cmd, std::string& channel) {
    return cmd.add_option("--channel", channel,
                          "where the height is in a colour image: r, g, b, a, luma, or a channel's name as the file "
                          "lists it (height.Y, Z, depth); default: the only grey channel, or Y, or R of a packed "
                          "heightpack texture")
        ->check(CLI::Validator(
            [](std::string& text) { return text.empty() ? std::string("give a channel: r, g, b, a, luma or a name") : ""; },
            "CHANNEL"));
}

void applyChannel(const std::string& text, LoadOptions& load) {
    if (text.empty()) {
        load.channel = ChannelSelect::Auto;
    } else if (const auto select = parseChannelSelect(text)) {
        load.channel = *select;
    } else {
        load.channel = ChannelSelect::Named;
        load.channelName = text;
    }
}

void printChannelNote(const SourceInfo& source) {
    if (!source.channelNote.empty()) std::cout << "  note: " << source.channelNote << "\n";
}

nlohmann::json channelJson(const SourceInfo& source) {
    return {{"used", source.channelUsed},
            {"note", source.channelNote.empty() ? nlohmann::json(nullptr) : nlohmann::json(source.channelNote)}};
}

namespace {
int nearestPowerOfTwo(int n) {
    int below = 1;
    while (below * 2 <= n) below *= 2;
    return n - below <= 2 * below - n ? below : 2 * below;
}
}  // namespace

std::string resizeNote(int w0, int h0, int w, int h) {
    char text[256];
    const int nw = nearestPowerOfTwo(w0), nh = nearestPowerOfTwo(h0);
    std::snprintf(text, sizeof text, "resized %dx%d to %dx%d, aspect %.3g -> %.3g%s; the nearest powers of two are %dx%d",
                  w0, h0, w, h, double(w0) / h0, double(w) / h,
                  std::abs(double(w0) / h0 - double(w) / h) > 1e-3 ? " (stretched)" : "", nw, nh);
    std::string note = text;
    if (nw != w || nh != h) note += ": export the map at that size to change it less";
    return note;
}

nlohmann::json resizeJson(int w0, int h0, int w, int h) {
    return {{"from", {{"width", w0}, {"height", h0}}},
            {"to", {{"width", w}, {"height", h}}},
            {"aspectFrom", double(w0) / h0},
            {"aspectTo", double(w) / h},
            {"nearestPowerOfTwo", {{"width", nearestPowerOfTwo(w0)}, {"height", nearestPowerOfTwo(h0)}}}};
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

std::optional<double> parseLength(const std::string& text) {
    const char* begin = text.c_str();
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    if (end == begin || !std::isfinite(value) || value <= 0) return std::nullopt;
    const std::string unit(end);
    if (unit.empty() || unit == "m") return value;
    if (unit == "cm") return value / 100;
    if (unit == "mm") return value / 1000;
    if (unit == "km") return value * 1000;
    return std::nullopt;
}

namespace {

std::string numberText(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

bool lengthUpTo(const std::string& text, double maxMetres) {
    const auto v = parseLength(text);
    return v && *v <= maxMetres;
}

}  // namespace

CLI::Validator lengthValidator(double maxMetres) {
    return CLI::Validator(
        [maxMetres](std::string& text) {
            return lengthUpTo(text, maxMetres) ? std::string()
                                               : "'" + text + "' is not a positive length up to " + numberText(maxMetres) +
                                                     " m, like 8m, 15cm or 2km";
        },
        "LENGTH");
}

CLI::Validator lengthPairValidator(double maxMetres) {
    return CLI::Validator(
        [maxMetres](std::string& text) {
            const auto comma = text.find(',');
            const bool ok = comma == std::string::npos ? lengthUpTo(text, maxMetres)
                                                       : lengthUpTo(text.substr(0, comma), maxMetres) &&
                                                             lengthUpTo(text.substr(comma + 1), maxMetres);
            return ok ? std::string()
                      : "'" + text + "' is not a positive length up to " + numberText(maxMetres) +
                            " m like 8m, or a pair like 8m,4m";
        },
        "LENGTH[,LENGTH]");
}

CLI::Validator finiteRange(double lo, double hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            const bool ok = !text.empty() && end != text.c_str() && *end == '\0' && std::isfinite(v) && v >= lo && v <= hi;
            return ok ? std::string() : "'" + text + "' is not a number from " + numberText(lo) + " to " + numberText(hi);
        },
        "NUMBER in [" + numberText(lo) + ", " + numberText(hi) + "]");
}

std::optional<std::array<double, 3>> parseColour(const std::string& text) {
    std::array<double, 3> rgb{};
    const char* p = text.c_str();
    for (int i = 0; i < 3; ++i) {
        char* end = nullptr;
        rgb[i] = std::strtod(p, &end);
        if (end == p || !std::isfinite(rgb[i]) || rgb[i] < 0 || rgb[i] > 1) return std::nullopt;
        p = end;
        if (i < 2) {
            if (*p != ',') return std::nullopt;
            ++p;
        }
    }
    if (*p != '\0') return std::nullopt;
    return rgb;
}

CLI::Validator colourValidator() {
    return CLI::Validator(
        [](std::string& text) {
            return parseColour(text) ? std::string() : "'" + text + "' is not a colour r,g,b with each in [0,1]";
        },
        "R,G,B");
}

std::string outputFormat(const std::string& requested, const std::string& output) {
    const std::string ext = lowerExtension(output);
    // KTX2 and DDS take the mip-mapped path the EXR takes; --format names neither, so it must be absent.
    const std::optional<Container> container = containerForPath(output);
    if (container == Container::Ktx2 || container == Container::Dds)
        return requested.empty() ? containerName(*container) : "";
    const std::string byName = ext == ".png" ? "png8" : ext == ".exr" ? "exr" : "";
    return requested.empty() || requested == byName ? byName : "";
}

std::string colourText(const std::array<double, 3>& colour) {
    char text[64];
    std::snprintf(text, sizeof text, "%.2f,%.2f,%.2f", colour[0], colour[1], colour[2]);
    return text;
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
