#include "heightpack/core/tileable.hpp"

#include <opencv2/core.hpp>

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

constexpr double kPi = 3.14159265358979323846;

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

// Sums over the lines of |operator| at every gap: sums[op][c]. lines holds m lines of n texels each.
// Lines are summed in fixed blocks and the blocks in order, so the result does not depend on threads.
std::array<std::vector<double>, kOperators> operatorSums(const float* lines, int n, int m, int threads) {
    constexpr int kBlock = 64;
    const int blocks = (m + kBlock - 1) / kBlock;
    std::vector<std::array<std::vector<double>, kOperators>> partial(blocks);
    parallelFor(blocks, threads, [&](int begin, int end) {
        std::vector<double> d(n);
        for (int b = begin; b < end; ++b) {
            auto& sums = partial[b];
            for (auto& s : sums) s.assign(n, 0.0);
            for (int j = b * kBlock; j < std::min(m, (b + 1) * kBlock); ++j) {
                const float* h = lines + size_t(j) * n;
                for (int c = 0; c < n; ++c) d[c] = double(h[c + 1 == n ? 0 : c + 1]) - h[c];
                for (int c = 0; c < n; ++c) {
                    const double before = d[c == 0 ? n - 1 : c - 1], after = d[c + 1 == n ? 0 : c + 1];
                    sums[kJump1][c] += std::abs(d[c]);
                    sums[kJump3][c] += std::abs(after - 2 * d[c] + before);
                    sums[kKink][c] += std::abs(after - before);
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

// The map with rows and columns swapped: its columns become lines that read contiguously.
Image transposed(const Image& map) {
    Image out(map.height, map.width, 1);
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) out.at(y, x) = map.at(x, y);
    return out;
}

// Scores along one direction: lines holds m lines of n texels, the tile edge between texel n-1 and 0.
SeamScore scoreAlong(const float* lines, int n, int m, const SeamOptions& options) {
    SeamScore score;
    if (n < kMinimumTexels || m < kMinimumLines) return score;
    score.measured = true;
    std::array<std::vector<double>, kOperators> sums = operatorSums(lines, n, m, options.threads);
    for (auto& s : sums)
        for (double& v : s) v /= m;
    const int period = blockPeriod(sums[kJump3], options.level);
    // Below the source's steps, or float rounding at the heights' magnitude, a difference is no evidence:
    // on an exactly periodic, noiseless field every cut differs from the others by rounding alone.
    double largest = 0;
    for (size_t i = 0; i < size_t(n) * m; ++i) largest = std::max(largest, double(std::abs(lines[i])));
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

double smoothstep(double edge, double x) {
    const double t = std::clamp(x / edge, 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

// The standard normal CDF and its inverse (Acklam's rational approximation refined by one Halley step,
// accurate to about 1e-15).
double normalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

double inverseNormalCdf(double p) {
    static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                               1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00};
    static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                               6.680131188771972e+01, -1.328068155288572e+01};
    static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                               -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00};
    static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                               3.754408661907416e+00};
    const double low = 0.02425;
    double x;
    if (p < low) {
        const double q = std::sqrt(-2 * std::log(p));
        x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
            ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
    } else if (p > 1 - low) {
        const double q = std::sqrt(-2 * std::log(1 - p));
        x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
            ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
    } else {
        const double q = p - 0.5, r = q * q;
        x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
            (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
    }
    const double e = normalCdf(x) - p;
    const double u = e * std::sqrt(2 * kPi) * std::exp(x * x / 2);
    return x - u / (1 + x * u / 2);
}

// The Gaussianising transform of Heitz & Neyret: each value to the standard normal quantile of its
// (mid-)rank, so equal values map to equal Gaussians; and back through the sorted values.
struct Gaussianiser {
    std::vector<float> sorted;
    std::vector<double> gaussian;  // per texel of the map it was built from

    explicit Gaussianiser(const std::vector<float>& values) : sorted(values), gaussian(values.size()) {
        const size_t n = values.size();
        std::vector<size_t> order(n);
        std::iota(order.begin(), order.end(), size_t(0));
        std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return values[a] < values[b]; });
        std::sort(sorted.begin(), sorted.end());
        for (size_t start = 0; start < n;) {
            size_t end = start + 1;
            while (end < n && values[order[end]] == values[order[start]]) ++end;
            const double midRank = 0.5 * (start + end - 1);
            const double g = inverseNormalCdf((midRank + 0.5) / n);
            for (size_t k = start; k < end; ++k) gaussian[order[k]] = g;
            start = end;
        }
    }

    float back(double g) const {
        const double pos = std::clamp(normalCdf(g) * sorted.size() - 0.5, 0.0, double(sorted.size() - 1));
        const size_t i = static_cast<size_t>(pos);
        const size_t j = std::min(i + 1, sorted.size() - 1);
        return static_cast<float>(sorted[i] + (double(sorted[j]) - sorted[i]) * (pos - i));
    }
};

}  // namespace

LevelSeams measureSeams(const Image& level, const SeamOptions& options) {
    assert(level.channels == 1);
    LevelSeams seams;
    seams.width = level.width;
    seams.height = level.height;
    seams.leftRight = scoreAlong(level.pixels.data(), level.width, level.height, options);
    // Columns as lines: the same code then reads every line contiguously.
    const Image columns = transposed(level);
    seams.topBottom = scoreAlong(columns.pixels.data(), level.height, level.width, options);
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

ChainSeams measureChainSeams(const std::vector<Image>& chain, double threshold, SeamOptions options) {
    ChainSeams result;
    result.threshold = threshold;
    for (size_t level = 0; level < chain.size(); ++level) {
        options.level = static_cast<int>(level);
        result.levels.push_back(measureSeams(chain[level], options));
    }
    result.failure = firstSeamFailure(result.levels, threshold);
    return result;
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
    return text;
}

namespace {

// relativeToSlope: the jump across an edge is measured from the line through the slopes beside it
// (the step minus their mean), so a smooth slope running through the edge is kept rather than flattened
// into one level step; Moisan's original measures it from the edge texel repeated.
Image moisanPeriodic(const Image& map, bool relativeToSlope) {
    assert(map.channels == 1);
    const int w = map.width, h = map.height;
    // The boundary image v: what the periodic Laplacian of the map has at the texels beside a tile edge
    // that the map's own interior does not: the jump across the edge. Its sum over each line is zero, so
    // the smooth field has no net curvature to spread over the tile (no dome).
    cv::Mat v(h, w, CV_64F, cv::Scalar(0.0));
    auto add = [&](int x, int y, double value) { v.at<double>(y, x) += value; };
    for (int y = 0; y < h; ++y) {
        const double first = map.at(0, y), last = map.at(w - 1, y);
        const double slope = relativeToSlope && w >= 3
                                 ? 0.5 * (double(map.at(1, y)) - first + last - map.at(w - 2, y)) : 0.0;
        add(0, y, last - first + slope);
        add(w - 1, y, first - last - slope);
    }
    for (int x = 0; x < w; ++x) {
        const double first = map.at(x, 0), last = map.at(x, h - 1);
        const double slope = relativeToSlope && h >= 3
                                 ? 0.5 * (double(map.at(x, 1)) - first + last - map.at(x, h - 2)) : 0.0;
        add(x, 0, last - first + slope);
        add(x, h - 1, first - last - slope);
    }
    // The smooth field s solves the periodic Poisson equation laplacian(s) = v with zero mean; the map
    // minus s has, everywhere, the Laplacian of the map's interior: no seam, and its mean kept.
    cv::Mat spectrum;
    cv::dft(v, spectrum, cv::DFT_COMPLEX_OUTPUT);
    for (int r = 0; r < h; ++r) {
        for (int q = 0; q < w; ++q) {
            auto& z = spectrum.at<cv::Vec2d>(r, q);
            const double denominator = 2 * std::cos(2 * kPi * q / w) + 2 * std::cos(2 * kPi * r / h) - 4;
            if (q == 0 && r == 0) {
                z = cv::Vec2d(0, 0);
            } else {
                z[0] /= denominator;
                z[1] /= denominator;
            }
        }
    }
    cv::Mat smooth;
    cv::dft(spectrum, smooth, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
    Image out(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) out.at(x, y) = static_cast<float>(map.at(x, y) - smooth.at<double>(y, x));
    return out;
}

// The bend's height at distance u (in bands) from the edge: G(u) = integral from u to 1 of w, where the
// slope profile w is 1 up to half the band and eases to 0 by its end with a smoothstep. So the bend's slope
// is constant over the half band next to the edge (the change of slope is cancelled at every scale up
// to half a band, as the coarse mip levels see it too) and its curvature stays spread over the outer half.
double bendProfile(double u) {
    if (u >= 1) return 0.0;
    if (u <= 0.5) return 0.75 - u;
    const double x = 2 * (u - 0.5);
    return 0.5 * (0.5 - x + x * x * x - 0.5 * x * x * x * x);
}

// Removes the change of slope that the periodic component leaves at the left/right tile edge (call it on
// a transposed map for top/bottom). The change is measured per line from the mean slopes over a few
// texels on each side and smoothed along the edge (the part that varies from line to line is like the
// interior's own bends), then bent away within `band` texels on each side: heights stay continuous and
// nothing beyond the band changes. Unlike a global smooth field that matches slopes, which must bend the
// whole tile into a dome when the slopes differ on average, the change is local: at most 3/8 of the
// slope difference times the band.
void bendAwayEdgeKinks(Image& map, int band) {
    const int w = map.width, h = map.height;
    const int span = std::max(1, std::min(4, band / 4));
    std::vector<double> kink(h);
    for (int y = 0; y < h; ++y) {
        const double after = (double(map.at(span, y)) - map.at(0, y)) / span;
        const double before = (double(map.at(w - 1, y)) - map.at(w - 1 - span, y)) / span;
        kink[y] = after - before;
    }
    // Smooth along the edge (itself periodic) with a Gaussian of a sixteenth of its length.
    const double sigma = std::max(1.0, h / 16.0);
    const int reach = static_cast<int>(std::ceil(3 * sigma));
    std::vector<double> weights(2 * reach + 1);
    double total = 0;
    for (int k = -reach; k <= reach; ++k) total += weights[k + reach] = std::exp(-0.5 * k * k / (sigma * sigma));
    std::vector<double> smooth(h, 0.0);
    for (int y = 0; y < h; ++y)
        for (int k = -reach; k <= reach; ++k) smooth[y] += weights[k + reach] / total * kink[wrapIndex(y + k, h, Wrap::Periodic)];
    for (int y = 0; y < h; ++y) {
        // Slope -kink/2 after the edge and +kink/2 before it: the bend's own change of slope is -kink.
        const double amplitude = 0.5 * smooth[y] * band;
        for (int i = 0; i < band && i < w / 2; ++i) {
            const double g = amplitude * bendProfile((i + 0.5) / band);
            map.at(i, y) += static_cast<float>(g);
            map.at(w - 1 - i, y) += static_cast<float>(g);
        }
    }
}

}  // namespace

Image periodicComponent(const Image& map, PeriodicContinuity continuity) {
    const bool slopes = continuity == PeriodicContinuity::HeightsAndSlopes;
    Image out = moisanPeriodic(map, slopes);
    if (!slopes || map.width < 8 || map.height < 8) return out;
    bendAwayEdgeKinks(out, std::max(4, map.width / 8));
    out = transposed(out);
    bendAwayEdgeKinks(out, std::max(4, map.height / 8));
    return transposed(out);
}

double crossfadeWeight(int x, int y, int width, int height, double band) {
    // Distance to the nearest tile edge as a fraction of the tile, zero on the edge texels themselves so the
    // shifted copy (continuous across the edge) is used alone there.
    const double dx = double(std::min(x, width - 1 - x)) / width;
    const double dy = double(std::min(y, height - 1 - y)) / height;
    return smoothstep(band, dx) * smoothstep(band, dy);
}

Image crossfadeTile(const Image& map, double width, CrossfadeBlend blend) {
    assert(map.channels == 1 && width > 0 && width <= 0.5);
    const int w = map.width, h = map.height;
    auto shifted = [&](int x, int y) { return map.at((x + w / 2) % w, (y + h / 2) % h); };
    Image out(w, h, 1);
    if (blend == CrossfadeBlend::Linear) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double a = crossfadeWeight(x, y, w, h, width);
                out.at(x, y) = static_cast<float>(a * map.at(x, y) + (1 - a) * shifted(x, y));
            }
        return out;
    }
    // The shifted copy has the same histogram, so one transform serves both.
    const Gaussianiser g(map.pixels);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double a = crossfadeWeight(x, y, w, h, width);
            const double original = g.gaussian[size_t(y) * w + x];
            const double other = g.gaussian[size_t((y + h / 2) % h) * w + (x + w / 2) % w];
            // Weights whose squares sum to one keep the variance of the Gaussian blend at one.
            const double blended = (a * original + (1 - a) * other) / std::sqrt(a * a + (1 - a) * (1 - a));
            out.at(x, y) = g.back(blended);
        }
    }
    return out;
}

Image mirrorTile(const Image& map) {
    const int w = map.width, h = map.height;
    Image out(2 * w, 2 * h, map.channels);
    for (int y = 0; y < 2 * h; ++y)
        for (int x = 0; x < 2 * w; ++x)
            for (int c = 0; c < map.channels; ++c)
                out.at(x, y, c) = map.at(x < w ? x : 2 * w - 1 - x, y < h ? y : 2 * h - 1 - y, c);
    return out;
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
