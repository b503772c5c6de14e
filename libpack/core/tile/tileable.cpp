// The seam measure: whether a tile edge is unlike every other place the tile could have been cut, per
// level and direction; the verdicts, their wording, the preview. The fixes are in tile/fix.cpp.
#include "heightpack/core/tile/tileable.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numeric>

#include "heightpack/core/parallel.hpp"

namespace heightpack {

namespace {

// Levels with fewer texels than this along a direction are not judged in that direction: the spread of
// the cut statistic is estimated from the other cuts, and fewer than about two dozen of them (after
// leaving out those that share texels with the tile edge) give a spread too unstable to bound a false
// alarm. The levels above, with more texels, have been judged already.
constexpr int kMinimumTexels = 32;
// Lines across: each cut's statistic is a mean over them, and fewer than this make it heavy-tailed.
constexpr int kMinimumLines = 8;

// The three difference operators, each centred on the gap between texel c and c+1 (periodic):
//   jump1: h(c+1) - h(c)                                 a jump a shows as a; smooth slopes show too
//   jump3: h(c+2) - 3h(c+1) + 3h(c) - h(c-1)             a jump shows as 2a; blind to slopes and bends
//   kink:  h(c+2) - h(c+1) - h(c) + h(c-1)               a change of slope s shows as s; blind to jumps
// jump3 carries jumps on smooth maps, where jump1 varies with the local slope; jump1 carries them on
// rough maps, where jump3 is mostly noise.
enum Operator { kJump1, kJump3, kKink, kOperators };
// How many gaps on each side of a cut share texels with it: those neighbours see a seam at the cut too,
// so they are left out of the prediction of the cut and of the reference cuts.
constexpr int kReach[kOperators] = {0, 1, 1};
// Amplification of independent texel noise by each operator (root of the sum of squared weights).
const double kNoiseGain[kOperators] = {std::sqrt(2.0), std::sqrt(20.0), 2.0};

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    const size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + mid, v.end());
    if (v.size() % 2) return v[mid];
    const double upper = v[mid];
    return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + mid));
}

// The three operators' magnitudes at one gap, from the differences across the gap before it, the gap
// itself and the gap after it.
struct GapTerms {
    double jump1, jump3, kink;
};
inline GapTerms gapTerms(double before, double at, double after) {
    return {std::abs(at), std::abs(after - 2 * at + before), std::abs(after - before)};
}

// Sums over the lines of |operator| at every gap: sums[op][c]. lines holds m lines of n texels each.
// Lines are summed in fixed blocks and the blocks in order, so the result does not depend on threads.
std::array<std::vector<double>, kOperators> operatorSums(const float* lines, int n, int m, int threads) {
    constexpr int kBlock = 64;
    const int blocks = (m + kBlock - 1) / kBlock;
    std::vector<std::array<std::vector<double>, kOperators>> partial(blocks);
    parallelFor(blocks, threads, [&](int begin, int end) {
        // The differences padded with their wrapped neighbours (padded[c + 1] = d[c]), so the loop over
        // the gaps has no wrap to test and vectorises.
        std::vector<double> padded(size_t(n) + 2);
        for (int b = begin; b < end; ++b) {
            auto& sums = partial[b];
            for (auto& s : sums) s.assign(n, 0.0);
            double* jump1 = sums[kJump1].data();
            double* jump3 = sums[kJump3].data();
            double* kink = sums[kKink].data();
            for (int j = b * kBlock; j < std::min(m, (b + 1) * kBlock); ++j) {
                const float* h = lines + size_t(j) * n;
                double* d = padded.data() + 1;
                for (int c = 0; c + 1 < n; ++c) d[c] = double(h[c + 1]) - h[c];
                d[n - 1] = double(h[0]) - h[n - 1];
                d[-1] = d[n - 1];
                d[n] = d[0];
                for (int c = 0; c < n; ++c) {
                    const GapTerms t = gapTerms(d[c - 1], d[c], d[c + 1]);
                    jump1[c] += t.jump1;
                    jump3[c] += t.jump3;
                    kink[c] += t.kink;
                }
            }
        }
    });
    std::array<std::vector<double>, kOperators> total;
    for (auto& s : total) s.assign(n, 0.0);
    for (const auto& p : partial)
        for (int op = 0; op < kOperators; ++op)
            for (int c = 0; c < n; ++c) total[op][c] += p[op][c];
    return total;
}

// operatorSums of the columns of a w x h image (rows as stored) without transposing it: gap r lies between
// rows r and r+1, and each gap's sums run along its rows, x in order, in four partial sums (x modulo 4)
// added at the end (one running sum would wait on each add's latency). Gaps are independent: the result
// does not depend on threads.
std::array<std::vector<double>, kOperators> operatorSumsAcrossRows(const float* rows, int w, int h, int threads) {
    std::array<std::vector<double>, kOperators> sums;
    for (auto& v : sums) v.assign(h, 0.0);
    parallelFor(h, threads, [&](int begin, int end) {
        for (int r = begin; r < end; ++r) {
            auto row = [&](int k) { return rows + size_t((r + k + h) % h) * w; };
            const float *before = row(-1), *at = row(0), *next = row(1), *after = row(2);
            double jump1[4] = {}, jump3[4] = {}, kink[4] = {};
            auto add = [&](int x, int part) {
                const GapTerms t = gapTerms(double(at[x]) - before[x], double(next[x]) - at[x], double(after[x]) - next[x]);
                jump1[part] += t.jump1;
                jump3[part] += t.jump3;
                kink[part] += t.kink;
            };
            int x = 0;
            for (; x + 4 <= w; x += 4)
                for (int part = 0; part < 4; ++part) add(x + part, part);
            for (; x < w; ++x) add(x, 0);
            sums[kJump1][r] = (jump1[0] + jump1[1]) + (jump1[2] + jump1[3]);
            sums[kJump3][r] = (jump3[0] + jump3[1]) + (jump3[2] + jump3[3]);
            sums[kKink][r] = (kink[0] + kink[1]) + (kink[2] + kink[3]);
        }
    });
    return sums;
}

// The period of an 8x8 block grid (JPEG) as it appears at this level, when the gaps on the grid's lines
// stand out from the others; 1 when there is none. The tile edge is a grid line itself (the grid starts
// at texel 0), so it is then compared with the cuts of its own phase.
int blockPeriod(const std::vector<double>& jump3, int level) {
    const int n = static_cast<int>(jump3.size());
    const int period = level < 3 ? 8 >> level : 1;
    if (period < 2 || n % period != 0 || n < 4 * period) return 1;
    std::vector<double> onGrid, offGrid;
    for (int c = 0; c < n; ++c) (c % period == period - 1 ? onGrid : offGrid).push_back(jump3[c]);
    return median(onGrid) > 1.15 * median(offGrid) ? period : 1;
}

// How far the tile edge's statistic stands above what the cuts beside it predict, in robust standard
// deviations of the same contrast over every other cut. s holds one operator's mean |value| per gap;
// the tile edge is gap n-1.
// floor: the least spread, in the statistic's units.
double edgeContrast(std::vector<double> s, int reach, int period, double floor) {
    const int n = static_cast<int>(s.size());
    if (period > 1) {
        const double typical = median(s);
        if (typical > 0) floor /= typical;
        // Each phase of the block grid by its own typical level, so grid lines and the others compare.
        for (int p = 0; p < period; ++p) {
            std::vector<double> phase;
            for (int c = p; c < n; c += period) phase.push_back(s[c]);
            const double typical = median(phase);
            if (typical > 0)
                for (int c = p; c < n; c += period) s[c] /= typical;
        }
    }
    // Predict each cut from its neighbours just outside its reach; what it has beyond that is its contrast.
    const int window = std::clamp((n - 2 * reach - 4) / 6, 1, 4);
    std::vector<double> contrast(n);
    for (int c = 0; c < n; ++c) {
        double predicted = 0;
        for (int k = reach + 1; k <= reach + window; ++k) predicted += s[(c + k) % n] + s[(c - k + n) % n];
        contrast[c] = s[c] - predicted / (2 * window);
    }
    // Reference cuts: those whose contrast does not involve the tile edge's own gaps.
    const int exclude = 2 * reach + window;
    std::vector<double> reference;
    for (int c = exclude; c < n - 1 - exclude; ++c) reference.push_back(contrast[c]);
    const double centre = median(reference);
    std::vector<double> deviation;
    for (double r : reference) deviation.push_back(std::abs(r - centre));
    const double spread = std::max(1.4826 * median(deviation), floor);
    const double excess = contrast[n - 1] - centre;
    // A spread estimated from few cuts is itself uncertain, and the ratio's tail grows heavier as they get
    // fewer (as Student's t against the normal): shrink the score by about the ratio of their critical
    // values, so that one threshold holds at 32 texels as at 4096.
    const double fewCuts = 1.0 + 8.0 / static_cast<double>(reference.size());
    if (spread > 0) return excess / spread / fewCuts;
    return excess > 0 ? std::numeric_limits<double>::infinity() : 0.0;
}


// The score of one direction from its operator sums over m lines at each of n gaps (the tile edge the
// last), largest the largest |height|.
SeamScore scoreOfSums(std::array<std::vector<double>, kOperators> sums, int m, double largest, const SeamOptions& options) {
    SeamScore score;
    const int n = static_cast<int>(sums[kJump1].size());
    score.measured = true;
    for (auto& s : sums)
        for (double& v : s) v /= m;
    const int period = blockPeriod(sums[kJump3], options.level);
    // Below the source's steps, or float rounding at the heights' magnitude, a difference is no evidence:
    // on an exactly periodic, noiseless field every cut differs from the others by rounding alone.
    const double quantum = std::max(options.quantum, largest * 4 * std::numeric_limits<float>::epsilon());
    // Nor is a contrast under a hundredth of the map's typical height step: no one sees a jump that small
    // (jump3 shows a jump twice over), and a noiseless analytic field, whose third differences are next to
    // nothing, would otherwise call a jump of curvature a seam.
    double typicalStep = 0;
    for (double v : sums[kJump1]) typicalStep += v / n;
    const double kVisible[kOperators] = {0.01, 0.02, 0.01};
    double z[kOperators];
    for (int op = 0; op < kOperators; ++op) {
        // Rounding to those steps alone moves a mean over m lines by about this much.
        const double floor = std::max(kNoiseGain[op] * quantum / std::sqrt(12.0 * m), kVisible[op] * typicalStep);
        z[op] = edgeContrast(sums[op], kReach[op], period, floor);
    }
    score.value = std::max(z[kJump1], z[kJump3]);
    score.slope = z[kKink];
    return score;
}

}  // namespace

// The largest of 8, 4 and 2 that the map repeats every texel of along x (or y) exactly that many times,
// leaving at least `least` texels: a map enlarged by nearest neighbour; 1 when there is none.
int repetition(const Image& map, bool alongX, int least) {
    const int n = alongX ? map.width : map.height, m = alongX ? map.height : map.width;
    auto at = [&](int along, int across) { return alongX ? map.at(along, across) : map.at(across, along); };
    for (int times : {8, 4, 2}) {
        if (n % times != 0 || n / times < least) continue;
        bool repeats = true;
        for (int j = 0; j < m && repeats; ++j)
            for (int i = 0; i < n && repeats; ++i)
                repeats = i % times == 0 || at(i, j) == at(i - 1, j);
        if (repeats) return times;
    }
    return 1;
}

LevelSeams measureSeams(const Image& level, const SeamOptions& options) {
    assert(level.channels == 1);
    // A map whose texels come in repeated blocks (enlarged by nearest neighbour) is judged as the map it
    // repeats: within the blocks every cut is a non-step, and the block edges' steps would be measured
    // against them.
    const int timesX = repetition(level, true, kMinimumTexels), timesY = repetition(level, false, kMinimumTexels);
    if (timesX > 1 || timesY > 1) {
        Image repeated(level.width / timesX, level.height / timesY, 1);
        for (int y = 0; y < repeated.height; ++y)
            for (int x = 0; x < repeated.width; ++x) repeated.at(x, y) = level.at(x * timesX, y * timesY);
        LevelSeams seams = measureSeams(repeated, options);
        seams.width = level.width;
        seams.height = level.height;
        return seams;
    }
    LevelSeams seams;
    seams.width = level.width;
    seams.height = level.height;
    const int w = level.width, h = level.height;
    const float* heights = level.pixels.data();
    const SampleRange range = sampleRange(level, options.threads);
    const double largest = std::max(std::abs(double(range.low)), std::abs(double(range.high)));
    // Each direction is judged where it has the texels and lines to be (kMinimumTexels, kMinimumLines).
    if (w >= kMinimumTexels && h >= kMinimumLines)
        seams.leftRight = scoreOfSums(operatorSums(heights, w, h, options.threads), h, largest, options);
    if (h >= kMinimumTexels && w >= kMinimumLines)
        seams.topBottom = scoreOfSums(operatorSumsAcrossRows(heights, w, h, options.threads), w, largest, options);
    return seams;
}

bool seamPasses(const SeamScore& score, double threshold) {
    return !score.measured || (score.value <= threshold && score.slope <= threshold);
}

bool levelTiles(const LevelSeams& seams, double threshold) {
    return seamPasses(seams.leftRight, threshold) && seamPasses(seams.topBottom, threshold);
}

std::optional<SeamFailure> firstSeamFailure(const std::vector<LevelSeams>& levels, double threshold,
                                            std::optional<SeamEdge> edge) {
    for (size_t level = 0; level < levels.size(); ++level) {
        const LevelSeams& l = levels[level];
        for (SeamEdge e : {SeamEdge::LeftRight, SeamEdge::TopBottom}) {
            const SeamScore& s = e == SeamEdge::LeftRight ? l.leftRight : l.topBottom;
            if ((edge && *edge != e) || seamPasses(s, threshold)) continue;
            const bool jump = s.value > threshold;
            return SeamFailure{static_cast<int>(level), l.width, l.height, e, jump ? SeamKind::Jump : SeamKind::Kink,
                               jump ? s.value : s.slope};
        }
    }
    return std::nullopt;
}

namespace {

ChainSeams measureLevels(const std::vector<const Image*>& chain, double threshold, SeamOptions options) {
    ChainSeams result;
    result.threshold = threshold;
    for (size_t level = 0; level < chain.size(); ++level) {
        options.level = static_cast<int>(level);
        result.levels.push_back(measureSeams(*chain[level], options));
    }
    result.failure = firstSeamFailure(result.levels, threshold);
    return result;
}

}  // namespace

ChainSeams measureChainSeams(const std::vector<Image>& chain, double threshold, SeamOptions options) {
    std::vector<const Image*> levels;
    for (const Image& level : chain) levels.push_back(&level);
    return measureLevels(levels, threshold, options);
}

ChainSeams measureChainSeams(const Image& level0, const std::vector<Image>& below, double threshold, SeamOptions options) {
    std::vector<const Image*> levels{&level0};
    for (const Image& level : below) levels.push_back(&level);
    return measureLevels(levels, threshold, options);
}

const char* seamEdgeName(SeamEdge edge) { return edge == SeamEdge::LeftRight ? "left/right" : "top/bottom"; }

std::string describeSeamFailure(const SeamFailure& f, double threshold) {
    char text[200];
    std::snprintf(text, sizeof text, "%s edges at level %d (%dx%d): %s, score %s (threshold %s)", seamEdgeName(f.edge),
                  f.level, f.width, f.height, f.kind == SeamKind::Jump ? "heights jump" : "slopes break",
                  seamScoreText(f.score, threshold).c_str(), seamScoreText(threshold, threshold).c_str());
    return text;
}

std::string seamScoreText(double score, double threshold) {
    if (std::isinf(score)) return score > 0 ? "inf" : "-inf";
    char text[32];
    for (int decimals = 1; decimals < 6; ++decimals) {
        std::snprintf(text, sizeof text, "%.*f", decimals, score);
        if ((std::strtod(text, nullptr) > threshold) == (score > threshold)) break;
    }
    // -0.04 shown as 0.0, not -0.0: a rounded zero has no sign.
    return text[0] == '-' && std::strtod(text, nullptr) == 0.0 ? text + 1 : text;
}

PackingCheck checkPacking(const std::vector<Image>& packedLevels, Wrap wrap) {
    PackingCheck check;
    for (size_t level = 0; level < packedLevels.size(); ++level) {
        const Image& p = packedLevels[level];
        assert(p.channels == 4);
        double worst = 0.0;
        for (int y = 0; y < p.height; ++y) {
            const int y1 = wrapIndex(y + 1, p.height, wrap);
            for (int x = 0; x < p.width; ++x) {
                const int x1 = wrapIndex(x + 1, p.width, wrap);
                worst = std::max({worst, std::abs(double(p.at(x, y, 1)) - p.at(x1, y, 0)),
                                  std::abs(double(p.at(x, y, 2)) - p.at(x, y1, 0)),
                                  std::abs(double(p.at(x, y, 3)) - p.at(x1, y1, 0))});
            }
        }
        check.maxError = std::max(check.maxError, worst);
        if (worst > 0.0 && check.firstBadLevel < 0) check.firstBadLevel = static_cast<int>(level);
    }
    check.consistent = check.firstBadLevel < 0;
    return check;
}

Image seamPreview(const Image& level0, const LevelSeams& seams, double threshold) {
    const int w = level0.width, h = level0.height;
    // Power-of-two scale putting the 2x2 tiling's longer side in [512, 1024].
    double scale = 1.0;
    const int longer = 2 * std::max(w, h);
    while (longer * scale > 1024) scale /= 2;
    while (longer * scale < 512) scale *= 2;
    const int outW = std::max(1, static_cast<int>(2 * w * scale)), outH = std::max(1, static_cast<int>(2 * h * scale));
    const auto [lo, hi] = std::minmax_element(level0.pixels.begin(), level0.pixels.end());
    const double range = *hi - *lo > 0 ? *hi - *lo : 1.0;
    const int step = scale < 1 ? static_cast<int>(1 / scale) : 1;  // texels averaged per output pixel
    Image out(outW, outH, 3);
    for (int y = 0; y < outH; ++y) {
        for (int x = 0; x < outW; ++x) {
            double sum = 0;
            const int sx = scale < 1 ? x * step : static_cast<int>(x / scale);
            const int sy = scale < 1 ? y * step : static_cast<int>(y / scale);
            for (int j = 0; j < step; ++j)
                for (int i = 0; i < step; ++i) sum += level0.at((sx + i) % w, (sy + j) % h);
            const float grey = static_cast<float>((sum / (step * step) - *lo) / range);
            for (int c = 0; c < 3; ++c) out.at(x, y, c) = grey;
        }
    }
    auto mark = [&](const SeamScore& s, bool vertical) {
        if (seamPasses(s, threshold)) return;
        const bool jump = s.value > threshold;
        const float colour[3] = {1.0f, jump ? 0.0f : 0.55f, 0.0f};  // red: heights jump; orange: slopes break
        const int thickness = std::max(2, std::max(outW, outH) / 256);
        const int mid = vertical ? outW / 2 : outH / 2;
        for (int t = -thickness / 2; t < thickness - thickness / 2; ++t) {
            for (int k = 0; k < (vertical ? outH : outW); ++k) {
                const int x = vertical ? mid + t : k, y = vertical ? k : mid + t;
                // Half-transparent, so the seam under the mark stays visible.
                for (int c = 0; c < 3; ++c) out.at(x, y, c) = 0.5f * out.at(x, y, c) + 0.5f * colour[c];
            }
        }
    };
    mark(seams.leftRight, true);
    mark(seams.topBottom, false);
    return out;
}

}  // namespace heightpack
