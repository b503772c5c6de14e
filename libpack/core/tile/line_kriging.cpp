#include "line_kriging.hpp"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "heightpack/core/parallel.hpp"

namespace heightpack::detail {

namespace {

using Complex = std::complex<double>;

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
// The inner products are written out in real arithmetic: std::complex's product checks for infinities
// and NaNs on every call, which keeps the loops from vectorising (twice the time of the whole solve).
// With AVX where the processor has it (chosen at load time; 0.1 s less CPU in a 4096^2 tile): the same
// arithmetic in the same order, four partial sums to a register instead of two, and no FMA, so the same
// bits as the SSE2 build.
__attribute__((target_clones("avx", "default"))) void choleskySolve(std::vector<Complex>& a, std::vector<Complex>& b, int n) {
    // a[i n + k] times the conjugate of a[j n + k], summed over k < count.
    // Four partial sums (k modulo 4), added in a fixed order at the end: one running sum waits on each
    // add's latency, which was most of the solve's time.
    auto rowProduct = [&](int i, int j, int count) {
        const double* p = reinterpret_cast<const double*>(&a[size_t(i) * n]);
        const double* q = reinterpret_cast<const double*>(&a[size_t(j) * n]);
        double re[4] = {0, 0, 0, 0}, im[4] = {0, 0, 0, 0};
        int k = 0;
        for (; k + 4 <= count; k += 4)
            for (int l = 0; l < 4; ++l) {
                re[l] += p[2 * (k + l)] * q[2 * (k + l)] + p[2 * (k + l) + 1] * q[2 * (k + l) + 1];
                im[l] += p[2 * (k + l) + 1] * q[2 * (k + l)] - p[2 * (k + l)] * q[2 * (k + l) + 1];
            }
        for (; k < count; ++k) {
            re[0] += p[2 * k] * q[2 * k] + p[2 * k + 1] * q[2 * k + 1];
            im[0] += p[2 * k + 1] * q[2 * k] - p[2 * k] * q[2 * k + 1];
        }
        return Complex((re[0] + re[1]) + (re[2] + re[3]), (im[0] + im[1]) + (im[2] + im[3]));
    };
    for (int j = 0; j < n; ++j) {
        const double d = std::sqrt(std::max(a[size_t(j) * n + j].real() - rowProduct(j, j, j).real(), 1e-300));
        a[size_t(j) * n + j] = d;
        for (int i = j + 1; i < n; ++i) a[size_t(i) * n + j] = (a[size_t(i) * n + j] - rowProduct(i, j, j)) / d;
    }
    for (int i = 0; i < n; ++i) {  // L y = b
        Complex s = b[i];
        for (int k = 0; k < i; ++k) s -= a[size_t(i) * n + k] * b[k];
        b[i] = s / a[size_t(i) * n + i].real();
    }
    for (int i = n - 1; i >= 0; --i) {  // L^H x = y
        Complex s = b[i];
        for (int k = i + 1; k < n; ++k) s -= std::conj(a[size_t(k) * n + i]) * b[k];
        b[i] = s / a[size_t(i) * n + i].real();
    }
}


// The kriged values of the band's lines m < band at one frequency: the sum over the 2 c conditioning
// lines j of cov(c + m - local(j)) weights[j], local(j) = j for the context before the band and band + j
// after it; covRow holds (re, im) of the covariance per offset 0 .. strip - 1. In real arithmetic, as in
// choleskySolve, for every m at once: each m's terms add in the order of j, and the lines m are the inner
// loop, which reads the covariances in a run (forwards for the context before the band, whose offsets are
// positive; backwards, conjugated, for the one after it) and vectorises; with AVX as choleskySolve.
__attribute__((target_clones("avx", "default"))) void krigedSums(const double* covRow, const Complex* weights, int c, int band,
                                                                 double* re, double* im) {
    std::fill(re, re + band, 0.0);
    std::fill(im, im + band, 0.0);
    for (int j = 0; j < 2 * c; ++j) {
        const double wr = weights[j].real(), wi = weights[j].imag();
        if (j < c) {
            const int base = c - j;  // the offset for m = 0
            for (int m = 0; m < band; ++m) {
                const double zr = covRow[2 * (base + m)], zi = covRow[2 * (base + m) + 1];
                re[m] += zr * wr - zi * wi;
                im[m] += zr * wi + zi * wr;
            }
        } else {
            const int base = band + j - c;  // minus the offset for m = 0
            for (int m = 0; m < band; ++m) {
                const double zr = covRow[2 * (base - m)], zi = -covRow[2 * (base - m) + 1];
                re[m] += zr * wr - zi * wi;
                im[m] += zr * wi + zi * wr;
            }
        }
    }
}

}  // namespace

// In the loops below, u runs across the lines and v along them.
double resynthesiseLines(StripField& field, const GaussianModel& model, const StripField& sample, Axis axis, int band, int context,
                         double noise, double mean, int threads) {
    const bool across = axis == Axis::X;
    const int w = across ? field.w : field.h, h = across ? field.h : field.w, c = context, strip = band + 2 * context;
    auto at = [&](const StripField& f, int u, int v) { return across ? f.at(u, v) : f.at(v, u); };
    auto set = [&](int u, int v) -> double& { return across ? field.at(u, v) : field.at(v, u); };
    const int first = w - band / 2 - context;  // the strip's first line, modulo w
    auto column = [&](int local) { return ((first + local) % w + w) % w; };
    const cv::Mat covHat = lineCovarianceSpectra(model, axis, strip, threads);
    auto cov = [&](int dx, int ky) {
        const cv::Vec2d z = covHat.at<cv::Vec2d>(ky, std::abs(dx));
        return dx >= 0 ? Complex(z[0], z[1]) : Complex(z[0], -z[1]);  // C(-dx, dy) = C(dx, -dy)
    };
    const int conditioning = 2 * c;
    auto local = [&](int k) { return k < c ? k : band + k; };  // context line k's place in the strip
    const cv::Mat residual = rowSpectra(conditioning, h, [&](int k, int y) {
        const int x = column(local(k));
        return at(field, x, y) - mean - at(sample, x, y);
    });
    const double nugget = noise + 1e-7 * std::max(model.variance(), 1e-12);
    const int half = h / 2;
    cv::Mat kriged(band, h, CV_64FC2, cv::Scalar(0, 0));
    // The frequencies in blocks of kBlock, each block's kriged values kept here and then stored a row
    // segment at a time: stored one frequency at a time, each value went to another row of kriged (a
    // cache and TLB miss per value, a seventh of the kriging's time).
    constexpr int kBlock = 8;
    parallelFor((half + kBlock) / kBlock, threads, [&](int beginBlock, int endBlock) {
        std::vector<Complex> a(size_t(conditioning) * conditioning), weights(conditioning), block(size_t(band) * kBlock);
        std::vector<double> re(band), im(band);
        for (int ky0 = beginBlock * kBlock; ky0 < std::min(half + 1, endBlock * kBlock); ky0 += kBlock) {
        const int kyEnd = std::min(half + 1, ky0 + kBlock);
        for (int ky = ky0; ky < kyEnd; ++ky) {
            for (int i = 0; i < conditioning; ++i) {
                for (int j = 0; j <= i; ++j) a[size_t(i) * conditioning + j] = cov(local(i) - local(j), ky);
                a[size_t(i) * conditioning + i] += nugget;
                const cv::Vec2d r = residual.at<cv::Vec2d>(i, ky);
                weights[i] = Complex(r[0], r[1]);
            }
            choleskySolve(a, weights, conditioning);
            krigedSums(covHat.ptr<double>(ky), weights.data(), c, band, re.data(), im.data());
            for (int m = 0; m < band; ++m) block[size_t(m) * kBlock + (ky - ky0)] = Complex(re[m], im[m]);
        }
        for (int m = 0; m < band; ++m)
            for (int ky = ky0; ky < kyEnd; ++ky) {
                const Complex sum = block[size_t(m) * kBlock + (ky - ky0)];
                kriged.at<cv::Vec2d>(m, ky) = cv::Vec2d(sum.real(), sum.imag());
                if (ky > 0 && ky < h - ky) kriged.at<cv::Vec2d>(m, h - ky) = cv::Vec2d(sum.real(), -sum.imag());
            }
        }
    });
    cv::Mat values(band, h, CV_64F);
    parallelFor(band, threads, [&](int begin, int end) {  // each row alone: any split gives the same rows
        cv::Mat rows = values.rowRange(begin, end);
        cv::dft(kriged.rowRange(begin, end), rows, cv::DFT_ROWS | cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
    });
    double change = 0;
    for (int m = 0; m < band; ++m) {
        const int x = column(c + m);
        for (int y = 0; y < h; ++y) {
            double& value = set(x, y);
            const double next = mean + at(sample, x, y) + values.at<double>(m, y);
            change += next - value;
            value = next;
        }
    }
    return change;
}


}  // namespace heightpack::detail
