// Acceptance tests of issue 11: can `check`'s verdict and `tile`'s fix be trusted? Judged from the outside,
// through checkFile and tileFile only, on maps whose verdict is known by construction (seam_families) and
// on real maps from games (tests/corpus). Scores are read through worstSeam() alone.
//
// Maps are spread over the cores; results are kept by map index, so what is printed does not depend on
// the scheduling. HEIGHTPACK_SEAM_SCALE=4 runs four times as many generated maps (never fewer than the
// issue's minimum: 500 periodic, 100 of each seamed family).
#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "heightpack/bake/check_job.hpp"
#include "heightpack/bake/tile_job.hpp"
#include "heightpack/io/read.hpp"

#include "support/seam_families.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

const std::string kCorpus = std::string(HEIGHTPACK_SOURCE_DIR) + "/tests/corpus";

// Pass/fail counts and worst scores of a set of verdicts, per format, printed as a table.
void printRates(const char* title, const std::vector<MapVerdict>& verdicts) {
    std::printf("%s\n", title);
    for (MapFormat format : kAllFormats) {
        std::vector<double> scores;
        int failures = 0;
        for (const MapVerdict& v : verdicts) {
            if (v.spec.format != format) continue;
            scores.push_back(v.worst.score);
            failures += !v.tiles;
        }
        if (scores.empty()) continue;
        std::printf("  %-7s %4zu maps  %4d fail (%5.1f%%)  worst score: %s\n", formatName(format), scores.size(),
                    failures, 100.0 * failures / double(scores.size()), distributionText(scores).c_str());
    }
    std::vector<double> all;
    int failures = 0;
    for (const MapVerdict& v : verdicts) {
        all.push_back(v.worst.score);
        failures += !v.tiles;
    }
    std::printf("  %-7s %4zu maps  %4d fail (%5.1f%%)  worst score: %s\n", "all", all.size(), failures,
                100.0 * failures / double(all.size()), distributionText(all).c_str());
    std::fflush(stdout);
}

std::vector<MapVerdict> checkFamily(const std::vector<MapSpec>& specs) {
    ScratchDir dir;
    std::vector<MapVerdict> verdicts(specs.size());
    parallelFor(static_cast<int>(specs.size()),
                [&](int i) { verdicts[i] = checkGeneratedMap(specs[i], dir.path().string()); });
    return verdicts;
}

// ---- The real corpus: ORIGIN.md's table is the expected verdict ----

struct CorpusEntry {
    std::string file;
    bool tiles = false;
    std::string reason;  // the 'tiles' cell
};

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

std::vector<CorpusEntry> readCorpusTable() {
    std::ifstream in(kCorpus + "/ORIGIN.md");
    std::vector<CorpusEntry> entries;
    std::vector<std::string> header;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("| ", 0) != 0) continue;
        std::vector<std::string> cells;
        std::stringstream row(line.substr(1));
        for (std::string cell; std::getline(row, cell, '|');) cells.push_back(trim(cell));
        if (!cells.empty() && cells[0] == "file") {
            header = cells;
            continue;
        }
        const auto tilesColumn = std::find(header.begin(), header.end(), "tiles");
        if (tilesColumn == header.end() || cells.size() < header.size()) continue;
        const std::string verdict = cells[size_t(tilesColumn - header.begin())];
        if (verdict.rfind("yes", 0) != 0 && verdict.rfind("no", 0) != 0) continue;
        entries.push_back({cells[0], verdict.rfind("yes", 0) == 0, verdict});
    }
    return entries;
}

LoadOptions corpusLoad() {
    LoadOptions load;
    load.channel = ChannelSelect::Luma;  // colour files as their luma; a grey file is its own
    return load;
}

// ---- Independent measures of damage ----

double span(const Image& m) {
    const auto [lo, hi] = std::minmax_element(m.pixels.begin(), m.pixels.end());
    return double(*hi) - *lo;
}

// A separable Gaussian blur of sigma texels (kernel to 3 sigma, normalised), mirrored at the edges
// (half-texel symmetric: texel -1 is texel 0).
Image gaussianBlur(const Image& m, double sigma) {
    const int r = std::max(1, static_cast<int>(std::ceil(3 * sigma)));
    std::vector<double> k(2 * r + 1);
    double sum = 0;
    for (int i = -r; i <= r; ++i) sum += k[i + r] = std::exp(-0.5 * i * i / (sigma * sigma));
    for (double& v : k) v /= sum;
    auto reflect = [](int i, int n) {
        while (i < 0 || i >= n) i = i < 0 ? -i - 1 : 2 * n - i - 1;
        return i;
    };
    Image across(m.width, m.height, 1), out(m.width, m.height, 1);
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            double v = 0;
            for (int i = -r; i <= r; ++i) v += k[i + r] * m.at(reflect(x + i, m.width), y);
            across.at(x, y) = static_cast<float>(v);
        }
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            double v = 0;
            for (int i = -r; i <= r; ++i) v += k[i + r] * across.at(x, reflect(y + i, m.height));
            out.at(x, y) = static_cast<float>(v);
        }
    return out;
}

// Pearson correlation of the fine detail (map minus its blur at sigma = width / 64) of a and b over the
// middle half, x in [W/4, 3W/4), y in [H/4, 3H/4).
double fineDetailCorrelation(const Image& a, const Image& b) {
    const double sigma = a.width / 64.0;
    const Image ba = gaussianBlur(a, sigma), bb = gaussianBlur(b, sigma);
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    long long n = 0;
    for (int y = a.height / 4; y < 3 * a.height / 4; ++y)
        for (int x = a.width / 4; x < 3 * a.width / 4; ++x, ++n) {
            const double da = double(a.at(x, y)) - ba.at(x, y), db = double(b.at(x, y)) - bb.at(x, y);
            sa += da;
            sb += db;
            saa += da * da;
            sbb += db * db;
            sab += da * db;
        }
    const double cov = sab - sa * sb / n, va = saa - sa * sa / n, vb = sbb - sb * sb / n;
    return va > 0 && vb > 0 ? cov / std::sqrt(va * vb) : (va == vb ? 1.0 : 0.0);
}

// One map through tile: what was measured, for printing and judging.
struct TileOutcome {
    std::string name;
    std::string skipped;   // why the map was not tiled (check passes it)
    std::string refused;   // tile wrote nothing: the failure of its best candidate
    std::string error;     // tile or a check failed to run
    WorstSeam before, after;
    bool afterTiles = false;
    double spanRatio = 0, detail = 0;
    std::string method;    // what tile reported doing
};

TileOutcome tileAndJudge(const std::string& name, const std::string& input, const std::string& output,
                         const LoadOptions& load) {
    TileOutcome o;
    o.name = name;
    CheckOptions check;
    check.load = load;
    auto before = checkFile(input, check);
    if (!before) {
        o.error = "check of the input: " + before.error().what;
        return o;
    }
    o.before = worstSeam(*before);
    if (before->tiles) {
        o.skipped = "check passes the input";
        return o;
    }
    TileOptions options;
    options.load = load;
    options.bits = 32;
    auto tiled = tileFile(input, output, options);
    if (!tiled) {
        o.error = "tile: " + tiled.error().what;
        return o;
    }
    o.method = tiled->alreadyTiled ? "copied as already tiling" : tiled->methodUsed;
    if (!tiled->written) {
        o.refused = describeSeamFailure(*tiled->after.failure, tiled->after.threshold);
        return o;
    }
    auto after = checkFile(output, CheckOptions{});
    auto in = loadHeightMap(input, load), out = loadHeightMap(output);
    if (!after || !in || !out) {
        o.error = "cannot check or reload the output, or reload the input";
        return o;
    }
    o.after = worstSeam(*after);
    o.afterTiles = after->tiles;
    o.spanRatio = span(out->heights) / std::max(1e-12, span(in->heights));
    if (out->heights.width != in->heights.width || out->heights.height != in->heights.height) {
        o.error = "the output's size differs from the input's";
        return o;
    }
    o.detail = fineDetailCorrelation(in->heights, out->heights);
    return o;
}

}  // namespace

// The generator itself, before anything is judged with it: the ranges the issue names are all drawn, the
// spectrum has the slope asked for, and JPEG quality reaches the file.
TEST(SeamFamilies, DrawTheRangesTheIssueNames) {
    std::map<std::string, int> seen;
    double betaLo = 9, betaHi = 0, anisoHi = 0;
    for (int i = 0; i < 500; ++i) {
        const MapSpec s = drawMap(Family::Periodic, i);
        seen[formatName(s.format)]++;
        seen[std::to_string(std::max(s.width, s.height))]++;
        seen[s.width == s.height ? "square" : s.width > s.height ? "wide" : "tall"]++;
        seen[s.aniso == 1.0 ? "isotropic" : "anisotropic"]++;
        betaLo = std::min(betaLo, s.beta);
        betaHi = std::max(betaHi, s.beta);
        anisoHi = std::max(anisoHi, s.aniso);
        EXPECT_GE(std::min(s.width, s.height), 16);
        EXPECT_EQ(drawMap(Family::Periodic, i).seed, s.seed);  // deterministic
    }
    for (const char* key : {"png8", "png16", "exr", "jpeg75", "jpeg90"}) EXPECT_EQ(seen[key], 100) << key;
    for (const char* key : {"64", "128", "256", "512", "1024", "square", "wide", "tall", "isotropic", "anisotropic"})
        EXPECT_GT(seen[key], 5) << key;
    EXPECT_LT(betaLo, 1.6);
    EXPECT_GT(betaHi, 3.9);
    EXPECT_GT(anisoHi, 2.8);
}

TEST(SeamFamilies, PeriodicFieldsHaveThePowerSpectrumAskedFor) {
    for (double beta : {1.5, 2.5, 4.0}) {
        const int n = 256;
        const Image m = periodicField(n, n, 7, beta, 1.0, 0.0);
        cv::Mat f(n, n, CV_64F), F;
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) f.at<double>(y, x) = m.at(x, y);
        cv::dft(f, F, cv::DFT_COMPLEX_OUTPUT);
        // Least-squares slope of log power against log k over octave rings from k = 4 to 64 cycles.
        std::vector<double> lk, lp;
        for (int k0 = 4; k0 < 64; k0 *= 2) {
            double power = 0, ks = 0;
            int count = 0;
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const double k = std::hypot(x <= n / 2 ? x : x - n, y <= n / 2 ? y : y - n);
                    if (k < k0 || k >= 2 * k0) continue;
                    power += std::norm(std::complex<double>(F.at<cv::Vec2d>(y, x)[0], F.at<cv::Vec2d>(y, x)[1]));
                    ks += std::log(k);
                    ++count;
                }
            lk.push_back(ks / count);
            lp.push_back(std::log(power / count));
        }
        double mk = 0, mp = 0, sxy = 0, sxx = 0;
        for (size_t i = 0; i < lk.size(); ++i) mk += lk[i] / lk.size(), mp += lp[i] / lp.size();
        for (size_t i = 0; i < lk.size(); ++i) sxy += (lk[i] - mk) * (lp[i] - mp), sxx += (lk[i] - mk) * (lk[i] - mk);
        EXPECT_NEAR(sxy / sxx, -beta, 0.25) << "beta " << beta;
        // Exactly periodic: the seam is just another pair of neighbours (no leakage of a step).
        EXPECT_LT(std::abs(m.at(0, 5) - m.at(n - 1, 5)), 20 * meanFirstDifference(m, true));
    }
}

TEST(SeamFamilies, JpegQualityReachesTheFile) {
    ScratchDir dir;
    const Image m = periodicField(256, 256, 3, 1.5, 1.0, 0.0);  // rough: quality shows in the size
    ASSERT_EQ(writeMap(dir.file("q75.jpg"), m, MapFormat::Jpeg75), "");
    ASSERT_EQ(writeMap(dir.file("q90.jpg"), m, MapFormat::Jpeg90), "");
    const size_t q75 = readBytes(dir.file("q75.jpg")).size(), q90 = readBytes(dir.file("q90.jpg")).size();
    std::printf("jpeg of a 256x256 k^-1.5 field: quality 75 %zu bytes, quality 90 %zu bytes\n", q75, q90);
    EXPECT_LT(double(q75), 0.8 * double(q90));
    auto loaded = loadHeightMap(dir.file("q75.jpg"));
    ASSERT_TRUE(loaded.ok()) << loaded.error().what;
    EXPECT_EQ(loaded->source.channels, 1);
}

TEST(SeamFamilies, SeamsHaveTheStrengthTheyAreMadeWith) {
    // Float maps, so the mean differences the seams are made from are the ones measured here.
    for (int i = 2; i < 60; i += 5) {
        const MapSpec periodic = drawMap(Family::Periodic, i), crop = drawMap(Family::Crop, i),
                      ramp = drawMap(Family::Ramp, i), parabola = drawMap(Family::Parabola, i);
        ASSERT_EQ(ramp.format, MapFormat::ExrFloat);
        if (std::max({crop.width, crop.height, ramp.width, ramp.height, parabola.width, parabola.height}) > 512)
            continue;  // the large ones only make this slower
        const WrapRatios p = wrapRatios(makeMap(periodic)), c = wrapRatios(makeMap(crop)),
                         r = wrapRatios(makeMap(ramp)), q = wrapRatios(makeMap(parabola));
        // Periodic: the wrap is one more pair of neighbours (a few texels' ratios, so loose bounds).
        EXPECT_LT(std::max(p.firstX, p.firstY), 2.0) << describe(periodic) << ": " << p.text();
        // A crop's opposite edges are unrelated places of the field: further apart than neighbours.
        EXPECT_GT(std::max(c.firstX, c.firstY), 1.2) << describe(crop) << ": " << c.text();
        // The ramp falls 3 mu1 at the wrap, on top of the periodic map's own step there (mean mu1).
        EXPECT_GT(ramp.alongX ? r.firstX : r.firstY, 2.0) << describe(ramp) << ": " << r.text();
        EXPECT_LT(ramp.alongX ? r.firstX : r.firstY, 4.5) << describe(ramp) << ": " << r.text();
        // The parabola's heights meet; its slope flips by 2 b n = 6 mu2, shared by the two second
        // differences that straddle the wrap: about 3 mu2 each.
        EXPECT_GT(parabola.alongX ? q.secondX : q.secondY, 2.0) << describe(parabola) << ": " << q.text();
        EXPECT_LT(parabola.alongX ? q.secondX : q.secondY, 4.5) << describe(parabola) << ": " << q.text();
        EXPECT_LT(parabola.alongX ? q.firstX : q.firstY, 2.0) << describe(parabola) << ": " << q.text();
    }
}

TEST(SeamMeasure, PeriodicMapsTile) {
    const int count = scaledCount(500, 500);
    std::vector<MapSpec> specs;
    for (int i = 0; i < count; ++i) specs.push_back(drawMap(Family::Periodic, i));
    const std::vector<MapVerdict> verdicts = checkFamily(specs);
    int failures = 0;
    std::vector<double> scores;
    for (const MapVerdict& v : verdicts) {
        ASSERT_EQ(v.error, "") << describe(v.spec);
        scores.push_back(v.worst.score);
        if (!v.tiles) {
            ++failures;
            std::printf("false alarm: %s: %s (map's own %s)\n", describe(v.spec).c_str(), v.worst.text().c_str(),
                        v.ratios.text().c_str());
        }
    }
    printRates("exactly periodic maps (every one should pass):", verdicts);
    RecordProperty("maps", count);
    RecordProperty("false_alarms", failures);
    RecordProperty("worst_score_median", std::to_string(quantile(scores, 0.5)));
    RecordProperty("worst_score_p99", std::to_string(quantile(scores, 0.99)));
    RecordProperty("worst_score_max", std::to_string(quantile(scores, 1.0)));
    EXPECT_EQ(failures, 0) << "of " << count << " exactly periodic maps; each is listed above";
}

TEST(SeamMeasure, SeamedMapsFail) {
    const int count = scaledCount(100, 100);
    std::vector<MapSpec> specs;
    for (Family family : kSeamedFamilies)
        for (int i = 0; i < count; ++i) specs.push_back(drawMap(family, i));
    const std::vector<MapVerdict> verdicts = checkFamily(specs);
    int missed = 0;
    for (Family family : kSeamedFamilies) {
        std::vector<MapVerdict> of;
        for (const MapVerdict& v : verdicts) {
            if (v.spec.family != family) continue;
            ASSERT_EQ(v.error, "") << describe(v.spec);
            of.push_back(v);
            if (v.tiles) {
                ++missed;
                std::printf("missed seam: %s: %s (map's own %s)\n", describe(v.spec).c_str(), v.worst.text().c_str(),
                            v.ratios.text().c_str());
            }
        }
        printRates((std::string(familyName(family)) + " maps (every one should fail):").c_str(), of);
        RecordProperty(std::string(familyName(family)) + "_missed",
                       static_cast<int>(std::count_if(of.begin(), of.end(),
                                                      [](const MapVerdict& v) { return v.tiles; })));
    }
    EXPECT_EQ(missed, 0) << "of " << verdicts.size() << " maps with a seam; each is listed above";
}

TEST(SeamMeasure, RealCorpus) {
    const std::vector<CorpusEntry> entries = readCorpusTable();
    // Every image in the folder has its row, and every row its file.
    int images = 0;
    for (const auto& f : std::filesystem::directory_iterator(kCorpus)) {
        const std::string ext = f.path().extension().string();
        if (ext == ".md" || ext == ".py") continue;
        ++images;
        EXPECT_TRUE(std::any_of(entries.begin(), entries.end(),
                                [&](const CorpusEntry& e) { return e.file == f.path().filename().string(); }))
            << f.path() << " has no row in ORIGIN.md";
    }
    ASSERT_EQ(size_t(images), entries.size());
    ASSERT_GE(entries.size(), 20u);

    std::vector<Result<CheckReport>> reports(entries.size(), Result<CheckReport>(Error{}));
    parallelFor(static_cast<int>(entries.size()), [&](int i) {
        CheckOptions options;
        options.load = corpusLoad();
        reports[i] = checkFile(kCorpus + "/" + entries[i].file, options);
    });
    int wrong = 0, yes = 0, no = 0, falseAlarms = 0, missed = 0;
    for (size_t i = 0; i < entries.size(); ++i) {
        const CorpusEntry& e = entries[i];
        ASSERT_TRUE(reports[i].ok()) << e.file << ": " << reports[i].error().what;
        const bool tiles = reports[i]->tiles;
        (e.tiles ? yes : no)++;
        if (tiles != e.tiles) {
            ++wrong;
            (e.tiles ? falseAlarms : missed)++;
        }
        std::printf("%-34s expected %-4s check %-5s %s  %s%s\n", e.file.c_str(), e.tiles ? "yes" : "no",
                    tiles ? "tiles" : "fails", worstSeam(*reports[i]).text().c_str(), tiles == e.tiles ? "" : "WRONG ",
                    reports[i]->note.empty() ? "" : ("(" + reports[i]->note + ")").c_str());
        EXPECT_EQ(tiles, e.tiles) << e.file << ": " << e.reason;
    }
    std::printf("real corpus: %zu maps (%d tile, %d do not): %d false alarms, %d missed seams\n", entries.size(), yes,
                no, falseAlarms, missed);
    RecordProperty("corpus_wrong", wrong);
}

TEST(SeamFix, TileFixesWithoutDamage) {
    ScratchDir dir;
    struct Case {
        std::string name, input;
        LoadOptions load;
        MapSpec spec;
        bool generated = false;
    };
    std::vector<Case> cases;
    // About 40 seamed maps of the families (the same draws SeamedMapsFail checks), sides up to 512.
    for (Family family : kSeamedFamilies) {
        int taken = 0;
        for (int i = 0; taken < 14 && i < 1000; ++i) {
            const MapSpec s = drawMap(family, i);
            if (std::max(s.width, s.height) > 512) continue;
            ++taken;
            cases.push_back({describe(s), dir.file("in" + std::to_string(cases.size()) + formatExtension(s.format)), {},
                             s, true});
        }
    }
    // Every real map that does not tile (tile takes any size; check scores level 0 only where the sides
    // are not powers of two).
    for (const CorpusEntry& e : readCorpusTable())
        if (!e.tiles) cases.push_back({e.file, kCorpus + "/" + e.file, corpusLoad(), {}, false});

    std::vector<TileOutcome> outcomes(cases.size());
    parallelFor(static_cast<int>(cases.size()), [&](int i) {
        const Case& c = cases[i];
        if (c.generated) {
            if (std::string err = writeMap(c.input, makeMap(c.spec), c.spec.format); !err.empty()) {
                outcomes[i].error = err;
                return;
            }
        }
        outcomes[i] = tileAndJudge(c.name, c.input, dir.file("out" + std::to_string(i) + ".exr"), c.load);
    });

    int judged = 0, stillSeamed = 0, spread = 0, damaged = 0;
    for (const TileOutcome& o : outcomes) {
        EXPECT_EQ(o.error, "") << o.name;
        if (!o.error.empty()) continue;
        if (!o.skipped.empty()) {
            std::printf("not tiled (%s): %s\n", o.skipped.c_str(), o.name.c_str());
            continue;
        }
        // A sheet of 64 unrelated pictures is not a height map; no blend of it tiled (the old default
        // refused it). The re-synthesis replaces the bands at its wrap lines with new content and keeps
        // the pictures beyond them: that tiles, and is judged below like every other map.
        EXPECT_EQ(o.refused, "") << o.name << ": tile wrote nothing";
        if (!o.refused.empty()) continue;
        ++judged;
        std::printf("%s\n  before %s | tile: %s | after %s %s | span x%.2f | fine detail r = %.3f\n", o.name.c_str(),
                    o.before.text().c_str(), o.method.c_str(), o.afterTiles ? "tiles" : "FAILS", o.after.text().c_str(),
                    o.spanRatio, o.detail);
        EXPECT_TRUE(o.afterTiles) << o.name << ": the output still fails check: " << o.after.text();
        EXPECT_LE(o.spanRatio, 1.5) << o.name << ": the height span grew";
        EXPECT_GE(o.detail, 0.95) << o.name << ": the fine detail in the middle half changed";
        stillSeamed += !o.afterTiles;
        spread += o.spanRatio > 1.5;
        damaged += o.detail < 0.95;
    }
    std::printf("tile on %d maps check fails: %d still fail check, %d spans grew past 1.5x, %d lost fine detail "
                "(r < 0.95)\n", judged, stillSeamed, spread, damaged);
    RecordProperty("tiled", judged);
    RecordProperty("still_fail", stillSeamed);
    RecordProperty("span_over_1_5", spread);
    RecordProperty("detail_under_0_95", damaged);
    EXPECT_GE(judged, 30);
}

TEST(SeamFix, TileLeavesATilingMapUnchanged) {
    ScratchDir dir;
    std::vector<MapSpec> specs;
    for (int i = 0; specs.size() < 30 && i < 1000; ++i) {
        const MapSpec s = drawMap(Family::Periodic, i);
        if (std::max(s.width, s.height) <= 512 &&
            (s.format == MapFormat::Png8 || s.format == MapFormat::Png16 || s.format == MapFormat::ExrFloat))
            specs.push_back(s);
    }
    struct Outcome {
        std::string skipped, error;
        bool sameBytes = false, sameValues = false, exrSameValues = false;
    };
    std::vector<Outcome> outcomes(specs.size());
    parallelFor(static_cast<int>(specs.size()), [&](int i) {
        const MapSpec& s = specs[i];
        Outcome& o = outcomes[i];
        const std::string ext = formatExtension(s.format), in = dir.file("in" + std::to_string(i) + ext),
                          same = dir.file("same" + std::to_string(i) + ext),
                          exr = dir.file("float" + std::to_string(i) + "-out.exr");
        if (o.error = writeMap(in, makeMap(s), s.format); !o.error.empty()) return;
        auto check = checkFile(in, CheckOptions{});
        if (!check) return void(o.error = check.error().what);
        if (!check->tiles) return void(o.skipped = "check fails it: " + worstSeam(*check).text());
        auto t1 = tileFile(in, same, TileOptions{});
        TileOptions asFloat;
        asFloat.bits = 32;
        auto t2 = tileFile(in, exr, asFloat);
        if (!t1 || !t2) return void(o.error = "tile: " + (t1 ? t2.error().what : t1.error().what));
        auto a = loadHeightMap(in), b = loadHeightMap(same), c = loadHeightMap(exr);
        if (!a || !b || !c) return void(o.error = "cannot reload");
        o.sameBytes = readBytes(in) == readBytes(same) &&
                      (s.format != MapFormat::ExrFloat || readBytes(in) == readBytes(exr));
        o.sameValues = a->heights.pixels == b->heights.pixels;
        o.exrSameValues = a->heights.pixels == c->heights.pixels;
    });
    int judged = 0, changed = 0;
    for (size_t i = 0; i < specs.size(); ++i) {
        const Outcome& o = outcomes[i];
        const std::string name = describe(specs[i]);
        EXPECT_EQ(o.error, "") << name;
        if (!o.skipped.empty()) {
            std::printf("not judged (%s): %s\n", o.skipped.c_str(), name.c_str());
            continue;
        }
        if (!o.error.empty()) continue;
        ++judged;
        const bool ok = o.sameBytes && o.sameValues && o.exrSameValues;
        changed += !ok;
        if (!ok)
            std::printf("changed: %s: same-format bytes %s, values %s, float EXR values %s\n", name.c_str(),
                        o.sameBytes ? "equal" : "DIFFER", o.sameValues ? "equal" : "DIFFER",
                        o.exrSameValues ? "equal" : "DIFFER");
        EXPECT_TRUE(o.sameBytes) << name << ": a same-format output is not the input's bytes";
        EXPECT_TRUE(o.sameValues) << name;
        EXPECT_TRUE(o.exrSameValues) << name << ": the float EXR output's values differ from the input's";
    }
    std::printf("tile on %d periodic maps check passes: %d changed; %zu not judged (check failed them)\n", judged,
                changed, specs.size() - judged);
    EXPECT_GE(judged, 1) << "check passed none of the periodic maps, so nothing could be judged";
}
