#include "heightpack/tileable.hpp"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace heightpack {

namespace {

constexpr double kPi = 3.14159265358979323846;

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    const size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + mid, v.end());
    if (v.size() % 2) return v[mid];
    const double upper = v[mid];
    return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + mid));
}

// boundary / interior, with flat maps handled: no interior variation and none at the boundary is fine.
double ratio(double boundary, double interior) {
    constexpr double kTiny = 1e-12;
    if (interior > kTiny) return boundary / interior;
    return boundary > kTiny ? std::numeric_limits<double>::infinity() : 1.0;
}

// Levels with fewer texels than this along a direction are not judged in that direction: a handful of
// columns says nothing reliable about a seam, and the levels above have already been checked.
constexpr int kMinimumTexels = 16;

// How many interior columns next to each side of the boundary the boundary is compared with: a seam is
// local, and a map's character can change across it (a painting is busier in one place than another).
constexpr int kNeighbourColumns = 8;

// Scores along one direction of a level of n texels along it and m across. h(i, j) reads texel i along
// the direction in line j.
template <class Read>
SeamScore scoreAlong(int n, int m, Read h) {
    SeamScore score;
    if (n < kMinimumTexels || m < 4) return score;
    score.measured = true;
    const int k = std::min(kNeighbourColumns, (n - 2) / 2);
    // First differences across the boundary gap n-1|0 and across the interior gaps i|i+1 nearest it.
    double boundary = 0.0, boundaryBend = 0.0;
    std::vector<int> gapColumns, bendColumns;
    for (int i = 0; i < k; ++i) {
        gapColumns.push_back(i);              // gaps 0|1 .. k-1|k
        gapColumns.push_back(n - 2 - i);      // gaps n-2|n-1 ..
        bendColumns.push_back(1 + i);         // second differences centred on 1 .. k
        bendColumns.push_back(n - 2 - i);     // and on n-2 ..
    }
    std::vector<double> gaps(gapColumns.size(), 0.0), bends(bendColumns.size(), 0.0);
    for (int j = 0; j < m; ++j) {
        for (size_t c = 0; c < gapColumns.size(); ++c) {
            const int i = gapColumns[c];
            gaps[c] += std::abs(double(h(i + 1, j)) - h(i, j));
        }
        for (size_t c = 0; c < bendColumns.size(); ++c) {
            const int i = bendColumns[c];
            bends[c] += std::abs(double(h(i + 1, j)) - 2.0 * h(i, j) + h(i - 1, j));
        }
        boundary += std::abs(double(h(0, j)) - h(n - 1, j));
        // The two second differences that straddle the boundary, centred on texel 0 and on texel n-1.
        boundaryBend += 0.5 * (std::abs(double(h(1, j)) - 2.0 * h(0, j) + h(n - 1, j)) +
                               std::abs(double(h(0, j)) - 2.0 * h(n - 1, j) + h(n - 2, j)));
    }
    score.value = ratio(boundary / m, median(gaps) / m);
    score.slope = ratio(boundaryBend / m, median(bends) / m);
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

LevelSeams measureSeams(const Image& level) {
    LevelSeams seams;
    seams.width = level.width;
    seams.height = level.height;
    seams.leftRight = scoreAlong(level.width, level.height, [&](int i, int j) { return level.at(i, j); });
    seams.topBottom = scoreAlong(level.height, level.width, [&](int i, int j) { return level.at(j, i); });
    return seams;
}

bool seamPasses(const SeamScore& score, double threshold) {
    return !score.measured || (score.value <= threshold && score.slope <= threshold);
}

bool levelTiles(const LevelSeams& seams, double threshold) {
    return seamPasses(seams.leftRight, threshold) && seamPasses(seams.topBottom, threshold);
}

Image periodicComponent(const Image& map, PeriodicContinuity continuity) {
    assert(map.channels == 1);
    const int w = map.width, h = map.height;
    // The boundary image v: what the periodic Laplacian of the map has at the texels beside a tile edge
    // that the map's own interior does not. Heights (Moisan): the jump across the edge, as if the missing
    // neighbour repeated the edge texel. Heights and slopes: the whole second difference across the edge,
    // as if the missing neighbour continued the map linearly.
    cv::Mat v(h, w, CV_64F, cv::Scalar(0.0));
    const bool slopes = continuity == PeriodicContinuity::HeightsAndSlopes && w >= 3 && h >= 3;
    auto add = [&](int x, int y, double value) { v.at<double>(y, x) += value; };
    for (int y = 0; y < h; ++y) {
        const double first = map.at(0, y), second = map.at(std::min(1, w - 1), y);
        const double last = map.at(w - 1, y), beforeLast = map.at(std::max(0, w - 2), y);
        add(0, y, slopes ? last - 2 * first + second : last - first);
        add(w - 1, y, slopes ? first - 2 * last + beforeLast : first - last);
    }
    for (int x = 0; x < w; ++x) {
        const double first = map.at(x, 0), second = map.at(x, std::min(1, h - 1));
        const double last = map.at(x, h - 1), beforeLast = map.at(x, std::max(0, h - 2));
        add(x, 0, slopes ? last - 2 * first + second : last - first);
        add(x, h - 1, slopes ? first - 2 * last + beforeLast : first - last);
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
