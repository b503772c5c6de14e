// What the eye sees in tiled maps (issue 22): the frame, blob and echo statistics of tile_look.hpp on
//   - exactly periodic maps (the calibration: every one must pass; the thresholds sit above their maxima),
//   - crops of larger periodic fields made to tile by each of tile's methods (every result should pass).
// Per family and method: maps, how many pass, and the distribution of each statistic.
//   build-test/tests/bench/heightpack_look_rates --count 200
// The maps are those of tests/support/seam_families (map i of a family is the same everywhere), rounded
// to the 8 or 16 bits of their format (float stays float; JPEG is taken as 8-bit).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "heightpack/core/tile_look.hpp"
#include "heightpack/core/tile_resynthesis.hpp"
#include "heightpack/core/tileable.hpp"

#include "support/seam_families.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

double quantumOf(MapFormat format) {
    return format == MapFormat::ExrFloat ? 0.0 : format == MapFormat::Png16 ? 1.0 / 65535 : 1.0 / 255;
}

Image rounded(Image map, double quantum) {
    if (quantum > 0)
        for (float& v : map.pixels) v = static_cast<float>(std::round(v / quantum) * quantum);
    return map;
}

struct Method {
    const char* name;
    Image (*apply)(const Image& map, double quantum);
};

const Method kMethods[] = {
    {"resynthesis", [](const Image& m, double q) {
         ResynthesisOptions o;
         o.quantum = q;
         return resynthesiseTile(m, o).map;
     }},
    {"moisan+bend", [](const Image& m, double) { return periodicComponent(m, PeriodicContinuity::HeightsAndSlopes); }},
    {"moisan", [](const Image& m, double) { return periodicComponent(m, PeriodicContinuity::Heights); }},
    {"crossfade", [](const Image& m, double) { return crossfadeTile(m, 0.1); }},
};

}  // namespace

int main(int argc, char** argv) {
    int count = 100;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--count") == 0 && i + 1 < argc) {
            count = std::atoi(argv[++i]);
        } else {
            std::fprintf(stderr, "usage: %s [--count N]   (N maps per row, default 100)\n", argv[0]);
            return 2;
        }
    }
    if (count <= 0) return 2;
    const LookThresholds t;
    std::printf("thresholds: frame %.2f, blobs %.2f, echo %.2f; %d maps a row\n", t.frame, t.blobs, t.echo, count);
    std::printf("%-12s %-12s %5s %6s   %-44s %-44s %s\n", "maps", "method", "maps", "pass", "frame", "blobs", "echo");
    auto row = [&](const char* maps, const char* method, const std::vector<TileLook>& looks) {
        std::vector<double> frame, blobs, echo;
        int pass = 0;
        for (const TileLook& l : looks) {
            if (!l.measured) continue;
            frame.push_back(l.frame);
            blobs.push_back(l.blobs);
            echo.push_back(l.echo);
            pass += l.passes(t);
        }
        auto brief = [](const std::vector<double>& v) {
            char text[64];
            std::snprintf(text, sizeof text, "med %.2f p99 %.2f max %.2f", quantile(v, 0.5), quantile(v, 0.99), quantile(v, 1.0));
            return std::string(text);
        };
        std::printf("%-12s %-12s %5zu %5.1f%%   %-44s %-44s %s\n", maps, method, frame.size(),
                    frame.empty() ? 0.0 : 100.0 * pass / double(frame.size()), brief(frame).c_str(), brief(blobs).c_str(),
                    brief(echo).c_str());
        std::fflush(stdout);
    };
    {
        std::vector<TileLook> looks(static_cast<size_t>(count));
        parallelFor(count, [&](int i) {
            const MapSpec spec = drawMap(Family::Periodic, i);
            looks[i] = measureTileLook(rounded(makeMap(spec), quantumOf(spec.format)), {nullptr, 1, std::nullopt});
            if (getenv("LOOK_VERBOSE") && (looks[i].frame > 5 || looks[i].blobs > 5))
                std::printf("  periodic fails: %s frame %.2f blobs %.2f echo %.2f\n", describe(spec).c_str(), looks[i].frame,
                            looks[i].blobs, looks[i].echo);
        });
        row("periodic", "(none)", looks);
    }
    for (const Method& method : kMethods) {
        std::vector<TileLook> looks(static_cast<size_t>(count));
        parallelFor(count, [&](int i) {
            const MapSpec spec = drawMap(Family::Crop, i);
            const double q = quantumOf(spec.format);
            const Image crop = rounded(makeMap(spec), q);
            const Image tiled = method.apply(crop, q);
            looks[i] = measureTileLook(rounded(tiled, q), {&crop, 1, std::nullopt});
        });
        row("crop", method.name, looks);
    }
    return 0;
}
