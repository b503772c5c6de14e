// How often `check` is right on maps whose verdict is known by construction (issue 11): per family and
// format, the number of maps, how many check fails, the rate, and the distribution of worst scores.
// Periodic maps should all pass (failures are false alarms); crops, ramps and parabolas should all fail.
//   build/tests/bench/heightpack_seam_rates --count 500
// The maps are those of tests/seam_test.cpp (map i of a family is the same there and here).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "support/seam_families.hpp"
#include "support/test_support.hpp"

using namespace heightpack::test;

int main(int argc, char** argv) {
    int count = 100;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--count") == 0 && i + 1 < argc) {
            count = std::atoi(argv[++i]);
        } else {
            std::fprintf(stderr, "usage: %s [--count N]   (N maps per family, default 100)\n", argv[0]);
            return 2;
        }
    }
    if (count <= 0) {
        std::fprintf(stderr, "--count needs a positive number\n");
        return 2;
    }
    ScratchDir dir;
    std::printf("%d maps per family, formats cycling; a periodic map should pass, every other should fail\n", count);
    std::printf("%-9s %-7s %6s %6s %8s   worst score\n", "family", "format", "maps", "fail", "right");
    for (Family family : {Family::Periodic, Family::Crop, Family::Ramp, Family::Parabola}) {
        std::vector<MapVerdict> verdicts(static_cast<size_t>(count));
        parallelFor(count, [&](int i) { verdicts[i] = checkGeneratedMap(drawMap(family, i), dir.path().string()); });
        const bool shouldPass = family == Family::Periodic;
        auto row = [&](const char* format, const std::vector<const MapVerdict*>& of) {
            std::vector<double> scores;
            int failures = 0, errors = 0;
            for (const MapVerdict* v : of) {
                if (!v->error.empty()) {
                    ++errors;
                    continue;
                }
                scores.push_back(v->worst.score);
                failures += !v->tiles;
            }
            const int right = shouldPass ? int(scores.size()) - failures : failures;
            std::printf("%-9s %-7s %6zu %6d %7.1f%%   %s%s\n", familyName(family), format, scores.size(), failures,
                        scores.empty() ? 0.0 : 100.0 * right / double(scores.size()), distributionText(scores).c_str(),
                        errors ? (" (" + std::to_string(errors) + " could not be written or read)").c_str() : "");
        };
        std::vector<const MapVerdict*> all;
        for (const MapVerdict& v : verdicts) all.push_back(&v);
        for (MapFormat format : kAllFormats) {
            std::vector<const MapVerdict*> of;
            for (const MapVerdict& v : verdicts)
                if (v.spec.format == format) of.push_back(&v);
            row(formatName(format), of);
        }
        row("all", all);
        std::fflush(stdout);
    }
    return 0;
}
