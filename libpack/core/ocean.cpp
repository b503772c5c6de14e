// The Ocean class of spectrum.hpp: random amplitudes over the DFT grid, evolved in time and turned into
// heights, displacement and its Jacobian by inverse DFTs (OpenCV).
#include <opencv2/core.hpp>

#include <cassert>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "heightpack/core/mip.hpp"
#include "heightpack/core/parallel.hpp"
#include "heightpack/core/spectrum.hpp"

namespace heightpack {

namespace {

// Standard normal deviates from a generator the C++ standard pins down bit for bit (mt19937_64), by
// Box-Muller, so a seed gives the same map with any standard library: deviate 2i is r cos(2 pi u2) and
// 2i + 1 is r sin(2 pi u2), r = sqrt(-2 ln u1), for the i-th pair of uniforms (u1 > 0: a zero is drawn
// again). The uniforms are drawn in order on one thread (cheap), the transcendental part is shared
// among threads: each pair's deviates depend on that pair alone, so any thread count gives the same.
std::vector<double> gaussianDeviates(uint64_t seed, size_t count, int threads) {
    std::mt19937_64 engine(seed);
    auto uniform = [&] { return double(engine() >> 11) * (1.0 / 9007199254740992.0); };
    std::vector<double> out(count + count % 2);
    for (size_t i = 0; i < out.size(); i += 2) {
        double u1 = 0.0;
        while (u1 <= 0.0) u1 = uniform();
        out[i] = u1;
        out[i + 1] = uniform();
    }
    const int pairs = static_cast<int>(out.size() / 2);
    parallelFor(pairs, threads, [&](int begin, int end) {
        for (size_t i = size_t(begin) * 2; i < size_t(end) * 2; i += 2) {
            const double r = std::sqrt(-2.0 * std::log(out[i])), a = 2 * std::numbers::pi * out[i + 1];
            out[i] = r * std::cos(a);
            out[i + 1] = r * std::sin(a);
        }
    });
    out.resize(count);
    return out;
}

// The real fields a frame can need, each the evolved spectrum times a multiplier that keeps it Hermitian.
enum OceanField { Height, DispX, DispY, DispXX, DispYY, DispXY, FieldCount };

// The signed index of DFT bin q of n: 0, 1, ..., n/2 - 1, -n/2, ..., -1.
int signedBin(int q, int n) { return q < n / 2 ? q : q - n; }

}  // namespace

Ocean::Ocean(const SpectrumOptions& options, int threads) : options_(options) {
    assert(isPowerOfTwo(options.size) && options.tileSize > 0);
    const int n = options.size;
    const size_t cells = size_t(n) * n;
    const double dk = 2 * std::numbers::pi / options.tileSize;
    // Drawn for every cell in the same order, used or not, so a seed means the same sea at any setting
    // (and whatever the band a cascade keeps).
    const std::vector<double> draws = gaussianDeviates(options.seed, 2 * cells, threads);
    amplitudeRe_.assign(cells, 0.0);
    amplitudeIm_.assign(cells, 0.0);
    omega_.assign(cells, 0.0);
    const SeaSpectrum spectrum(options);
    // Sums per row, added in row order afterwards: the same total whatever the thread count.
    std::vector<double> rowVariance(n, 0.0), rowBound(n, 0.0);
    parallelFor(n, threads, [&](int begin, int end) {
        for (int r = begin; r < end; ++r) {
            for (int q = 0; q < n; ++q) {
                const int m = signedBin(q, n), p = signedBin(r, n);
                // The Nyquist row and column have no partner -k on the grid: left empty so the field is real.
                if (m == -n / 2 || p == -n / 2) continue;
                const double kx = m * dk, ky = p * dk, k = std::hypot(kx, ky);
                if (k < options.bandLow || (options.bandHigh > 0.0 && k >= options.bandHigh)) continue;
                const double s = spectrum.directional(kx, ky) * dk * dk;
                // Half the variance here, half through the conjugate partner's term in fields().
                const double a = std::sqrt(s / 2.0) / std::sqrt(2.0);
                const size_t i = size_t(r) * n + q;
                amplitudeRe_[i] = a * draws[2 * i];
                amplitudeIm_[i] = a * draws[2 * i + 1];
                omega_[i] = angularFrequency(options, k);
                rowVariance[r] += s;
                // sqrt, not hypot (a tenth of the constructor): amplitudes this small cannot overflow.
                rowBound[r] += std::sqrt(amplitudeRe_[i] * amplitudeRe_[i] + amplitudeIm_[i] * amplitudeIm_[i]);
            }
        }
    });
    for (int r = 0; r < n; ++r) {
        resolvedVariance_ += rowVariance[r];
        displacementBound_ += 2.0 * rowBound[r];  // |h0(k)| and, through its partner, |h0(-k)|
    }
}

SeaFields Ocean::fields(double t, const SeaFieldSet& which, double choppiness, int threads) const {
    const int n = options_.size;
    const size_t cells = size_t(n) * n;
    const double dk = 2 * std::numbers::pi / options_.tileSize;
    // h(k, t) = h0(k) e^{-i w t} + conj(h0(-k)) e^{i w t}: Hermitian in k, so the sea is real, and the
    // energy that the spectrum puts at k (along the wind) runs toward +k, with the wind.
    std::vector<double> evolvedRe(cells), evolvedIm(cells);
    parallelFor(n, threads, [&](int begin, int end) {
        for (int r = begin; r < end; ++r) {
            for (int q = 0; q < n; ++q) {
                const size_t i = size_t(r) * n + q;
                const size_t j = size_t((n - r) % n) * n + (n - q) % n;  // -k
                // At t = 0 (a single frame, a loop's first) the phase is exactly 1: no sine or cosine to take.
                const double c = t == 0.0 ? 1.0 : std::cos(omega_[i] * t), s = t == 0.0 ? 0.0 : std::sin(omega_[i] * t);
                const double a = amplitudeRe_[i], b = amplitudeIm_[i], a2 = amplitudeRe_[j], b2 = amplitudeIm_[j];
                evolvedRe[i] = a * c + b * s + a2 * c + b2 * s;
                evolvedIm[i] = b * c - a * s + a2 * s - b2 * c;
            }
        }
    });

    std::vector<OceanField> wanted;
    if (which.heights) wanted.push_back(Height);
    if (which.displacement) wanted.insert(wanted.end(), {DispX, DispY});
    if (which.jacobian) wanted.insert(wanted.end(), {DispXX, DispYY, DispXY});
    // One inverse DFT per field, the fields shared among the threads; each field is the same
    // arithmetic in the same order whichever thread does it.
    std::vector<cv::Mat> out(FieldCount);
    parallelFor(int(wanted.size()), threads, [&](int begin, int end) {
        cv::Mat spectrum(n, n, CV_64FC2);  // one a thread, refilled for each field: 256 MB fewer to fault in at 4096^2
        for (int w = begin; w < end; ++w) {
            const OceanField field = wanted[w];
            for (int r = 0; r < n; ++r) {
                cv::Vec2d* row = spectrum.ptr<cv::Vec2d>(r);
                const double ky = signedBin(r, n) * dk;
                for (int q = 0; q < n; ++q) {
                    const size_t i = size_t(r) * n + q;
                    const double re = evolvedRe[i], im = evolvedIm[i];
                    if (field == Height) {
                        row[q] = cv::Vec2d(re, im);
                        continue;
                    }
                    // sqrt, not hypot: no overflow is possible here, and this runs 16 million times a field.
                    const double kx = signedBin(q, n) * dk, k = std::sqrt(kx * kx + ky * ky);
                    if (k <= 0.0) {
                        row[q] = cv::Vec2d(0, 0);
                        continue;
                    }
                    // D(k) = i k/|k| h(k) (a crest pulls its neighbours in: x + D compresses it, as a
                    // Gerstner wave does); its derivatives multiply by i kx or i ky once more.
                    switch (field) {
                        case DispX: row[q] = cv::Vec2d(-im * kx / k, re * kx / k); break;
                        case DispY: row[q] = cv::Vec2d(-im * ky / k, re * ky / k); break;
                        case DispXX: row[q] = cv::Vec2d(re, im) * (-kx * kx / k); break;
                        case DispYY: row[q] = cv::Vec2d(re, im) * (-ky * ky / k); break;
                        default: row[q] = cv::Vec2d(re, im) * (-kx * ky / k); break;
                    }
                }
            }
            cv::dft(spectrum, out[field], cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT);  // no 1/N: a sum over k
        }
    });

    // The conversions to float, rows shared among the threads (each texel on its own: any count gives the same).
    auto rows = [&](const std::function<void(int y)>& convert) {
        parallelFor(n, threads, [&](int begin, int end) {
            for (int y = begin; y < end; ++y) convert(y);
        });
    };
    SeaFields result;
    if (which.heights) {
        result.heights = Image(n, n, 1);
        rows([&](int y) {
            const double* src = out[Height].ptr<double>(y);
            float* dst = result.heights.row(y);
            for (int x = 0; x < n; ++x) dst[x] = static_cast<float>(src[x]);
        });
    }
    if (which.displacement) {
        result.displacement = Image(n, n, 2);
        rows([&](int y) {
            const double *dx = out[DispX].ptr<double>(y), *dy = out[DispY].ptr<double>(y);
            float* dst = result.displacement.row(y);
            for (int x = 0; x < n; ++x) dst[2 * x] = float(dx[x]), dst[2 * x + 1] = float(dy[x]);
        });
    }
    if (which.jacobian) {
        result.jacobian = Image(n, n, 1);
        const double c = choppiness;
        rows([&](int y) {
            const double *xx = out[DispXX].ptr<double>(y), *yy = out[DispYY].ptr<double>(y), *xy = out[DispXY].ptr<double>(y);
            float* dst = result.jacobian.row(y);
            for (int x = 0; x < n; ++x) dst[x] = float((1 + c * xx[x]) * (1 + c * yy[x]) - c * c * xy[x] * xy[x]);
        });
    }
    return result;
}

Image Ocean::heights(double t) const { return fields(t, {}).heights; }

Image Ocean::displacement(double t) const { return fields(t, {false, true, false}).displacement; }

}  // namespace heightpack
