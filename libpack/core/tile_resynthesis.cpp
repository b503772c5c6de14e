// Band re-synthesis by Gaussian conditional simulation: see tile_resynthesis.hpp for the steps.
#include "heightpack/core/tile_resynthesis.hpp"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "heightpack/core/parallel.hpp"
#include "heightpack/core/tileable.hpp"

#include "dft.hpp"
#include "field.hpp"
#include "gaussianise.hpp"
#include "smoothing.hpp"

namespace heightpack {

namespace {

using Complex = std::complex<double>;

using detail::Field;

enum class Axis { X, Y };

// A standard normal value for (seed, index) alone (SplitMix64, Box-Muller): the same noise on any thread.
double whiteNoise(uint64_t seed, uint64_t index) {
    auto mix = [](uint64_t z) {
        z += 0x9E3779B97F4A7C15ull;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    };
    const uint64_t a = mix(seed * 0x632BE59BD9B4E019ull + 2 * index), b = mix(seed * 0x632BE59BD9B4E019ull + 2 * index + 1);
    const double u1 = (double(a >> 11) + 0.5) / 9007199254740992.0, u2 = double(b >> 11) / 9007199254740992.0;
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * std::numbers::pi * u2);
}

// The stationary Gaussian model of a periodic field p: its circular autocovariance and one sample of the
// field with that covariance (asymptotic discrete spot noise: p's spectrum times white noise's).
struct GaussianModel {
    Field covariance, sample;
    GaussianModel(int w, int h) : covariance(w, h), sample(w, h) {}
};

// noise: the variance of the input's quantisation, in the Gaussian domain: white noise that the map holds
// as terraces and a sample would show as grain. Its level is taken off the power spectrum, so the model is
// of the field the quantised map samples, and the kriging treats it as measurement noise (a nugget).
GaussianModel modelOf(Field p, double noise, uint64_t seed, int threads) {
    const int w = p.w, h = p.h;
    const double n = double(w) * h;
    double mean = 0;
    for (double x : p.v) mean += x;
    mean /= n;
    for (double& x : p.v) x -= mean;
    GaussianModel model(w, h);
    cv::Mat spectrum = detail::forwardDft(p.mat(), threads), noiseSpectrum;
    cv::Mat power(h, w, CV_64FC2);
    const double floor = n * noise;  // the expected |A(k)|^2 of white noise of that variance
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            auto& a = spectrum.at<cv::Vec2d>(y, x);
            const double raw = a[0] * a[0] + a[1] * a[1], clean = std::max(raw - floor, 0.0);
            power.at<cv::Vec2d>(y, x) = cv::Vec2d(clean, 0.0);
            const double gain = raw > 0 ? std::sqrt(clean / raw) : 0.0;
            a = cv::Vec2d(a[0] * gain, a[1] * gain);
        }
    cv::Mat covariance = model.covariance.mat();
    detail::inverseDft(power, covariance, threads);
    model.covariance.mat() /= n;  // covariance is a view of model.covariance.v: dft wrote in place
    power.release();
    Field white(w, h);
    parallelFor(h, threads, [&](int begin, int end) {
        for (size_t i = size_t(begin) * w; i < size_t(end) * w; ++i) white.v[i] = whiteNoise(seed, i);
    });
    noiseSpectrum = detail::forwardDft(white.mat(), threads);
    cv::mulSpectrums(spectrum, noiseSpectrum, noiseSpectrum, 0);
    cv::Mat sample = model.sample.mat();
    detail::inverseDft(noiseSpectrum, sample, threads);
    model.sample.mat() /= std::sqrt(n);
    return model;
}

// Rows of a (rows x length) complex spectrum, one row per input sequence: seq(r, i) for i in [0, length).
template <class Get>
cv::Mat rowSpectra(int rows, int length, Get seq) {
    cv::Mat m(rows, length, CV_64F), out;
    for (int r = 0; r < rows; ++r)
        for (int i = 0; i < length; ++i) m.at<double>(r, i) = seq(r, i);
    cv::dft(m, out, cv::DFT_ROWS | cv::DFT_COMPLEX_OUTPUT);
    return out;
}

// In-place Cholesky of a Hermitian positive definite n x n matrix (lower triangle), then solves A x = b.
void choleskySolve(std::vector<Complex>& a, std::vector<Complex>& b, int n) {
    for (int j = 0; j < n; ++j) {
        double d = a[j * n + j].real();
        for (int k = 0; k < j; ++k) d -= std::norm(a[j * n + k]);
        d = std::sqrt(std::max(d, 1e-300));
        a[j * n + j] = d;
        for (int i = j + 1; i < n; ++i) {
            Complex s = a[i * n + j];
            for (int k = 0; k < j; ++k) s -= a[i * n + k] * std::conj(a[j * n + k]);
            a[i * n + j] = s / d;
        }
    }
    for (int i = 0; i < n; ++i) {  // L y = b
        Complex s = b[i];
        for (int k = 0; k < i; ++k) s -= a[i * n + k] * b[k];
        b[i] = s / a[i * n + i].real();
    }
    for (int i = n - 1; i >= 0; --i) {  // L^H x = y
        Complex s = b[i];
        for (int k = i + 1; k < n; ++k) s -= std::conj(a[k * n + i]) * b[k];
        b[i] = s / a[i * n + i].real();
    }
}

// The variance, in the Gaussian domain, of rounding the map to its levels: each run of equal values spans
// an interval of Gaussians, over which a value is spread as if uniformly. 0 for a float map.
double quantisationNoise(const std::vector<float>& sorted) {
    const double n = double(sorted.size());
    auto quantile = [&](double rank) { return detail::inverseNormalCdf(std::clamp(rank / n, 0.5 / n, 1 - 0.5 / n)); };
    double variance = 0;
    for (size_t start = 0; start < sorted.size();) {
        size_t end = start + 1;
        while (end < sorted.size() && sorted[end] == sorted[start]) ++end;
        if (end - start > 1) {
            const double span = quantile(double(end)) - quantile(double(start));
            variance += double(end - start) / n * span * span / 12;
        }
        start = end;
    }
    return variance;
}

// Replaces the `band` columns (Axis::X; rows for Axis::Y) around the wrap line between the last and the
// first with the model's sample conditioned on `context` lines on each side. The field must wrap along
// the lines. In the loops below, u runs across the lines and v along them.
void resynthesiseLines(Field& field, const GaussianModel& model, Axis axis, int band, int context, double noise, int threads) {
    const bool across = axis == Axis::X;
    const int w = across ? field.w : field.h, h = across ? field.h : field.w, c = context, strip = band + 2 * context;
    auto at = [&](const Field& f, int u, int v) { return across ? f.at(u, v) : f.at(v, u); };
    auto set = [&](int u, int v) -> double& { return across ? field.at(u, v) : field.at(v, u); };
    const int first = w - band / 2 - context;  // the strip's first line, modulo w
    auto column = [&](int local) { return ((first + local) % w + w) % w; };
    double mean = 0;
    for (int v = 0; v < h; ++v)
        for (int u = 0; u < w; ++u) mean += at(field, u, v);
    mean /= double(field.v.size());
    // The covariance between lines du apart, per frequency along them: dft of C's line du.
    const cv::Mat covHat = rowSpectra(strip, h, [&](int du, int dv) { return at(model.covariance, du % w, dv); });
    auto cov = [&](int dx, int ky) {
        const cv::Vec2d z = covHat.at<cv::Vec2d>(std::abs(dx), ky);
        return dx >= 0 ? Complex(z[0], z[1]) : Complex(z[0], -z[1]);  // C(-dx, dy) = C(dx, -dy)
    };
    const int conditioning = 2 * c;
    auto local = [&](int k) { return k < c ? k : band + k; };  // context line k's place in the strip
    const cv::Mat residual = rowSpectra(conditioning, h, [&](int k, int y) {
        const int x = column(local(k));
        return at(field, x, y) - mean - at(model.sample, x, y);
    });
    const double nugget = noise + 1e-7 * std::max(model.covariance.at(0, 0), 1e-12);
    const int half = h / 2;
    cv::Mat kriged(band, h, CV_64FC2, cv::Scalar(0, 0));
    parallelFor(half + 1, threads, [&](int begin, int end) {
        std::vector<Complex> a(size_t(conditioning) * conditioning), weights(conditioning);
        for (int ky = begin; ky < end; ++ky) {
            for (int i = 0; i < conditioning; ++i) {
                for (int j = 0; j <= i; ++j) a[size_t(i) * conditioning + j] = cov(local(i) - local(j), ky);
                a[size_t(i) * conditioning + i] += nugget;
                const cv::Vec2d r = residual.at<cv::Vec2d>(i, ky);
                weights[i] = Complex(r[0], r[1]);
            }
            choleskySolve(a, weights, conditioning);
            for (int m = 0; m < band; ++m) {
                Complex sum = 0;
                for (int j = 0; j < conditioning; ++j) sum += cov(c + m - local(j), ky) * weights[j];
                kriged.at<cv::Vec2d>(m, ky) = cv::Vec2d(sum.real(), sum.imag());
                if (ky > 0 && ky < h - ky) kriged.at<cv::Vec2d>(m, h - ky) = cv::Vec2d(sum.real(), -sum.imag());
            }
        }
    });
    cv::Mat values;
    cv::dft(kriged, values, cv::DFT_ROWS | cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
    for (int m = 0; m < band; ++m) {
        const int x = column(c + m);
        for (int y = 0; y < h; ++y) set(x, y) = mean + at(model.sample, x, y) + values.at<double>(m, y);
    }
}

// Moisan's smooth field of the jumps across the top/bottom wrap line alone: periodic in both directions,
// harmonic but at that line, where it carries the jump. Taking it off makes field wrap top to bottom
// without touching the left/right wrap line, as the left/right band's Fourier treatment along y needs.
Field topBottomSmoothField(const Field& f, int threads) {
    const int w = f.w, h = f.h;
    Field v(w, h);
    for (int x = 0; x < w; ++x) {
        const double jump = f.at(x, h - 1) - f.at(x, 0);
        v.at(x, 0) += jump;
        v.at(x, h - 1) -= jump;
    }
    Field s(w, h);
    cv::Mat out = s.mat();
    detail::solvePeriodicPoisson(v.mat(), out, threads);
    return s;
}

// Where the slopes along x (or y) stop resembling themselves: the lag at which the autocorrelation of the
// difference field falls below 1/e, from the covariance C of the heights.
double slopeCorrelationLength(const Field& covariance, Axis axis) {
    const int w = axis == Axis::X ? covariance.w : covariance.h;
    auto c = [&](int d) {
        const int lag = ((d % w) + w) % w;
        return axis == Axis::X ? covariance.at(lag, 0) : covariance.at(0, lag);
    };
    auto d = [&](int dx) { return 2 * c(dx) - c(dx + 1) - c(dx - 1); };
    const double d0 = d(0);
    if (!(d0 > 0)) return 1.0;
    double previous = 1.0;
    for (int dx = 1; dx < w / 2; ++dx) {
        const double r = d(dx) / d0;
        if (r < std::exp(-1.0)) return dx - 1 + (previous - std::exp(-1.0)) / std::max(previous - r, 1e-12);
        previous = r;
    }
    return w / 2.0;
}

// Beyond the bands the map less a smooth field can pass the map's own extremes (a crop that spans [0,1]
// then no longer fits an integer file). Where it does, the values within 2% of the range of an extreme
// and beyond are eased into that 2% (tanh, monotone, continuous): the rest, the whole middle of the range,
// is untouched.
void keepWithinRange(Image& out, const Image& map) {
    const auto [lo, hi] = std::minmax_element(map.pixels.begin(), map.pixels.end());
    const auto [olo, ohi] = std::minmax_element(out.pixels.begin(), out.pixels.end());
    const double low = *lo, high = *hi, margin = 0.02 * (high - low);
    if (!(margin > 0)) return;
    const bool over = *ohi > high, under = *olo < low;
    for (float& v : out.pixels) {
        if (over && v > high - margin) v = static_cast<float>(high - margin + margin * std::tanh((v - (high - margin)) / margin));
        if (under && v < low + margin) v = static_cast<float>(low + margin - margin * std::tanh((low + margin - v) / margin));
    }
}

int chooseBand(double fraction, double correlation, int size) {
    const int texels = fraction > 0 ? static_cast<int>(std::lround(fraction * size))
                                    : static_cast<int>(std::lround(std::clamp(4 * correlation, size / 16.0, size / 4.0)));
    return std::clamp(texels, std::min(4, size / 4), size / 2);
}

}  // namespace

ResynthesisResult resynthesiseTile(const Image& map, const ResynthesisOptions& options) {
    ResynthesisResult result;
    const int w = map.width, h = map.height;
    if (w < 16 || h < 16) {
        result.map = periodicComponent(map, PeriodicContinuity::Heights);
        return result;
    }
    // 1. Ranks to Gaussians, of the map with its quantisation undone: otherwise a smooth 8-bit painting is a
    //    staircase whose steps the model takes for fine detail, and a sample shows them as grain.
    const std::vector<float> values = options.quantum > 0 ? detail::dequantised(map, options.quantum, options.threads) : map.pixels;
    GaussianModel model(w, h);
    double noise = 0;
    {
        const detail::Gaussianiser ranks(values, options.threads);
        // The model: the covariance and a sample of the Gaussianised map's periodic component (which has
        // no cross of edge jumps in its spectrum).
        Image gImage(w, h, 1);
        for (size_t i = 0; i < gImage.pixels.size(); ++i) gImage.pixels[i] = static_cast<float>(ranks.gaussian[i]);
        Field p(w, h);
        const Image periodic = periodicComponent(gImage, PeriodicContinuity::Heights);
        for (size_t i = 0; i < p.v.size(); ++i) p.v[i] = periodic.pixels[i];
        noise = quantisationNoise(ranks.sorted);
        model = modelOf(std::move(p), noise, options.seed, options.threads);
    }
    result.bandX = chooseBand(options.band, slopeCorrelationLength(model.covariance, Axis::X), w);
    result.bandY = chooseBand(options.band, slopeCorrelationLength(model.covariance, Axis::Y), h);
    // 2. Large scales, in heights: Moisan's smooth field of a low-pass of the map at the band's scale (at
    //    least 1/16 of the tile: only scales the eye reads as the map's swell; each side of a wrap line
    //    blurred apart, mirrored). Beyond the bands this is the whole change.
    std::vector<float> smooth(values.size(), 0.0f), corrected(values.size());
    {
        Field heights(w, h);
        heights.v.assign(values.begin(), values.end());
        const double sigma = std::max(0.5 * std::max(result.bandX, result.bandY), std::min(w, h) / 16.0);
        {
            Field scratch(w, h);
            detail::blur(heights, scratch, sigma, options.threads);
        }
        Image lowImage(w, h, 1);
        for (size_t i = 0; i < heights.v.size(); ++i) lowImage.pixels[i] = static_cast<float>(heights.v[i]);
        const Image lowPeriodic = periodicComponent(lowImage, PeriodicContinuity::Heights);
        for (size_t i = 0; i < values.size(); ++i) {
            smooth[i] = lowImage.pixels[i] - lowPeriodic.pixels[i];
            corrected[i] = values[i] - smooth[i];
        }
    }
    const detail::Gaussianiser ranks(corrected, options.threads);
    Field g(w, h);
    g.v = ranks.gaussian;
    // 3. and 4. The bands, left/right first, then top/bottom.
    const int contextX = std::clamp(result.bandX / 2, 4, 32), contextY = std::clamp(result.bandY / 2, 4, 32);
    if (result.bandX + 2 * contextX <= w) {
        // The left/right band is solved per frequency along y, so its field must wrap top to bottom: the
        // top/bottom jump is set aside meanwhile (the top/bottom band replaces what it touches later).
        const Field aside = topBottomSmoothField(g, options.threads);
        for (size_t i = 0; i < g.v.size(); ++i) g.v[i] -= aside.v[i];
        resynthesiseLines(g, model, Axis::X, result.bandX, contextX, noise, options.threads);
        for (size_t i = 0; i < g.v.size(); ++i) g.v[i] += aside.v[i];
    }
    if (result.bandY + 2 * contextY <= h) resynthesiseLines(g, model, Axis::Y, result.bandY, contextY, noise, options.threads);
    // 5. Back to heights through the sorted values. Beyond the bands, the map itself plus the large-scale
    //    change there (so its own fine detail, terraces and all, stays exactly); in the bands, the new
    //    content, which a quantised output rounds to its levels.
    auto inBand = [&](int x, int y) {
        const int dx = std::min(x, w - 1 - x), dy = std::min(y, h - 1 - y);
        return dx < (result.bandX + 1) / 2 + 1 || dy < (result.bandY + 1) / 2 + 1;
    };
    result.map = Image(w, h, 1);
    parallelFor(h, options.threads, [&](int begin, int end) {
        for (int y = begin; y < end; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t i = size_t(y) * w + x;
                result.map.pixels[i] = inBand(x, y) ? ranks.back(g.v[i]) : map.pixels[i] - smooth[i];
            }
    });
    keepWithinRange(result.map, map);
    return result;
}

}  // namespace heightpack
