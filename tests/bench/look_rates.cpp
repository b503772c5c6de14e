// What the eye sees in tiled maps (issue 22): the frame, blob and echo statistics of tile/look.hpp on
//   - exactly periodic maps (the calibration: every one must pass; the thresholds sit above their maxima),
//   - crops of larger periodic fields made to tile by each of tile's methods (every result should pass),
//   - the same crops enlarged (issue 36: a map painted small and resized before packing), once 2x to 8x or
//     twice, by nearest, bilinear, bicubic, Lanczos3 and Blackman-Harris, to at least 1024 a side, made to
//     tile by tile's chain (re-synthesis at four seeds and bands, then the quilt, whose best match comes
//     second where the first seed breaks at the finest level; the crossfade would come after, and is
//     counted as a failure): the rate beside the crops'.
// Per family and method: maps, how many pass, and the distribution of each statistic.
//   build-test/tests/bench/heightpack_look_rates --count 200
// The maps are those of tests/support/seam_families (map i of a family is the same everywhere), rounded
// to the 8 or 16 bits of their format (float stays float; JPEG is taken as 8-bit).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/core/tile/look.hpp"
#include "heightpack/core/tile/quilt.hpp"
#include "heightpack/core/tile/resynthesis.hpp"
#include "heightpack/core/tile/tileable.hpp"

#include "tile/enlargement.hpp"
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

// Crop i enlarged to at least 1024 a side: by 2, 4 or 8 (every third map twice, by 2 or 4 each time), each
// kernel in turn, with clamped edges as resizers do; rounded to the crop's format.
Image enlargedCrop(int i, double& quantum, std::string& what) {
    const MapSpec spec = drawMap(Family::Crop, i);
    quantum = quantumOf(spec.format);
    Image map = rounded(makeMap(spec), quantum);
    const int shortSide = std::min(map.width, map.height);
    std::vector<int> factors;
    if (i % 3 == 2) factors = {2 + 2 * (i % 2), 2};
    int total = 1;
    for (int f : factors) total *= f;
    while (shortSide * total < 1024) {
        const int f = shortSide * total * 8 <= 1024 ? 8 : shortSide * total * 4 <= 1024 ? 4 : 2;
        factors.push_back(f);
        total *= f;
    }
    what = describe(spec);
    for (size_t k = 0; k < factors.size(); ++k) {
        const detail::Enlargement e{factors[k], detail::Kernel((i + int(k) * 2) % 5)};
        map = rounded(detail::enlarge(map, e, false, 1), quantum);
        what += " x" + std::to_string(factors[k]);
    }
    return map;
}

// tile's chain on one map: the re-synthesis' four attempts (the quilt's best match, at the source's size,
// before the second where the first breaks at the finest level), the quilt's other attempts, then, for an
// enlarged map, the quilt's three at the map's own size; each judged by its seams (the finest level) and its
// look; the first that passes, else the last.
TileLook tiledLook(const Image& map, double quantum, int threads) {
    TileLook look;
    bool finestBreaks = false;  // the last candidate's seams at the finest level
    auto passes = [&](const Image& candidate) {
        const Image stored = rounded(candidate, quantum);
        SeamOptions seams;
        seams.quantum = quantum;
        seams.threads = threads;
        look = measureTileLook(stored, {&map, threads, std::nullopt});
        finestBreaks = !levelTiles(measureSeams(stored, seams));
        return !finestBreaks && look.passes();
    };
    double firstBand = 0;
    auto resynthesis = [&](int from, int to) {
        Resynthesiser resynthesiser(map, quantum, threads);
        for (int attempt = from; attempt < to; ++attempt) {
            const double band = attempt < 2 ? 0.0 : std::min(0.25, firstBand * (attempt == 2 ? 1.5 : 2.0));
            const ResynthesisResult r = resynthesiser.attempt(uint64_t(1 + attempt), band);
            if (attempt == 0) firstBand = double(std::max(r.bandX, 1)) / map.width;
            if (passes(r.map)) return true;
        }
        return false;
    };
    int enlargement = 1;
    auto quilting = [&](bool atSourceSize, int from, int to) {
        for (int attempt = from; attempt < to; ++attempt) {
            QuiltOptions quilt;
            quilt.threads = threads;
            quilt.quantum = quantum;
            quilt.atSourceSize = atSourceSize;
            quilt.match = attempt == 1 ? 1 : 0;
            quilt.band = attempt == 2 ? 1.5 / 8 : 0.0;
            const QuiltResult q = quiltTile(map, quilt);
            enlargement = q.enlargement;
            if (passes(q.map)) return true;
        }
        return false;
    };
    if (resynthesis(0, 1)) return look;
    const bool quiltSooner = finestBreaks;
    if ((quiltSooner && quilting(true, 0, 1)) || resynthesis(1, 4) || quilting(true, quiltSooner ? 1 : 0, 3) ||
        (enlargement > 1 && quilting(false, 0, 3)))
        return look;
    look.frame = std::max(look.frame, LookThresholds{}.frame + 1);  // what reaches the crossfade fails here
    return look;
}

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
    {
        const int enlarged = std::max(1, count / 4);  // each costs a tile at 1024-2048 a side
        std::vector<TileLook> looks(static_cast<size_t>(enlarged));
        parallelFor(enlarged, [&](int i) {
            double q = 0;
            std::string what;
            const Image map = enlargedCrop(i, q, what);
            looks[i] = tiledLook(map, q, 1);
            if (getenv("LOOK_VERBOSE") && !looks[i].passes())
                std::printf("  enlarged fails: %s frame %.2f blobs %.2f echo %.2f\n", what.c_str(), looks[i].frame, looks[i].blobs,
                            looks[i].echo);
        });
        row("enlarged", "tile's chain", looks);
    }
    return 0;
}
