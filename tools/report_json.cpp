#include "report_json.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>

namespace heightpack::cli {

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

}  // namespace heightpack::cli
