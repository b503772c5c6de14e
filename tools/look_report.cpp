#include "look_report.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace heightpack::cli {

namespace {

struct Statistic {
    const char* name;
    double value, threshold;
    const char* seen;  // what a person sees when it is over
};

std::vector<Statistic> statistics(const TileLook& look, const LookThresholds& t) {
    return {{"frame", look.frame, t.frame, "a band of other contrast around every tile"},
            {"blobs", look.blobs, t.blobs, "bright or dark patches along the tile edges or at its corners"},
            {"echo", look.echo, t.echo, "one feature shown twice in every tile"}};
}

// Two decimals, a rounded zero without a sign ("0.00", not "-0.00").
std::string twoDecimals(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", v);
    return text[0] == '-' && std::strtod(text, nullptr) == 0.0 ? text + 1 : text;
}

}  // namespace

nlohmann::json lookJson(const TileLook& look, const LookThresholds& t) {
    nlohmann::json doc = {{"measured", look.measured}};
    if (!look.measured) return doc;
    nlohmann::json over = nlohmann::json::array();
    for (const Statistic& s : statistics(look, t)) {
        doc[s.name] = s.value;
        if (s.value > s.threshold) over.push_back(s.name);
    }
    doc["echoBaseline"] = look.echoBaseline;
    doc["thresholds"] = {{"frame", t.frame}, {"blobs", t.blobs}, {"echo", t.echo}};
    doc["passes"] = look.passes(t);
    doc["over"] = over;
    return doc;
}

std::string lookText(const TileLook& look, const LookThresholds& t) {
    if (!look.measured) return "not measured (under 64 texels a side)";
    std::string text;
    for (const Statistic& s : statistics(look, t)) {
        char part[96];
        std::snprintf(part, sizeof part, "%s%s %s%s", text.empty() ? "" : ", ", s.name, twoDecimals(s.value).c_str(),
                      s.value > s.threshold ? " (over)" : "");
        text += part;
    }
    return text;
}

void printLook(const TileLook& look, const LookThresholds& t, bool fails) {
    std::printf("  look: %s (thresholds frame %.2f, blobs %.2f, echo %.2f)\n", lookText(look, t).c_str(), t.frame,
                t.blobs, t.echo);
    for (const Statistic& s : statistics(look, t))
        if (look.measured && s.value > s.threshold)
            std::printf("  %s: %s %s over %.2f: tiled, it shows %s\n", fails ? "LOOK FAILS" : "WARNING", s.name,
                        twoDecimals(s.value).c_str(), s.threshold, s.seen);
}

}  // namespace heightpack::cli
