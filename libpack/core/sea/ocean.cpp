// The Ocean class of spectrum.hpp: random amplitudes over half the DFT grid (the other half follows by
// Hermitian symmetry, the sea being real), evolved in time and turned into heights, shift (horizontal displacement) and its
// Jacobian by real inverse DFTs in float (dft.hpp), one column pass at a time through the heights' storage.
#include <cassert>
#include <cmath>
#include <numbers>
#include <type_traits>

#include "counter_normals.hpp"
#include "dft.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/parallel.hpp"
#include "heightpack/core/sea/spectrum.hpp"

namespace heightpack {

namespace {

// The signed index of DFT bin q of n: 0, 1, ..., n/2 - 1, -n/2, ..., -1.
int signedBin(int q, int n) { return q < n / 2 ? q : q - n; }

// What one wave vector of the full grid holds: its amplitude h0(k), its modulus, and the spectrum's
// variance there.
struct Mode {
    std::complex<double> amplitude;
    double modulus = 0.0;
    double variance = 0.0;
};

}  // namespace

Ocean::Ocean(const SpectrumOptions& options, const OceanOptions& how) : options_(options) {
    assert(isPowerOfTwo(options.size) && options.tileSize > 0);
    const int n = options.size, columns = n / 2 + 1;
    const double dk = 2 * std::numbers::pi / options.tileSize;
    const SeaSpectrum spectrum(options);
    const uint64_t key = detail::normalStreamKey(options.seed);
    // Cell (r, q) of the full grid. The Nyquist row and column have no partner -k on the grid: left empty so
    // the field is real. Where the spectrum is zero (against the wind, outside the band) no draw is made:
    // each cell's draw is its own (counter-based), so skipping one changes no other.
    auto mode = [&](int r, int q) -> Mode {
        const int m = signedBin(q, n), p = signedBin(r, n);
        if (m == -n / 2 || p == -n / 2) return {};
        const double kx = m * dk, ky = p * dk, k = std::sqrt(kx * kx + ky * ky);
        if (k < options.bandLow || (options.bandHigh > 0.0 && k >= options.bandHigh)) return {};
        const double s = spectrum.directional(kx, ky, k) * dk * dk;
        if (!(s > 0.0)) return {};
        // Half the variance here, half through the conjugate partner's term: sqrt(s / 2) / sqrt(2) a part.
        const double a = 0.5 * std::sqrt(s);
        const detail::NormalPair g = detail::normalPair(key, uint64_t(r) * n + q);
        return {{a * g.first, a * g.second}, a * g.radius, s};
    };
    initial_.assign(size_t(n) * columns, {});
    if (how.evolves) partner_.assign(size_t(n) * columns, {});
    // Sums per row, added in row order afterwards: the same total whatever the thread count.
    std::vector<double> rowVariance(n, 0.0), rowBound(n, 0.0);
    parallelFor(n, how.threads, [&](int begin, int end) {
        for (int r = begin; r < end; ++r) {
            for (int q = 0; q < columns; ++q) {
                const Mode here = mode(r, q), there = mode((n - r) % n, (n - q) % n);  // k and -k
                const size_t i = size_t(r) * columns + q;
                initial_[i] = std::complex<float>(here.amplitude + std::conj(there.amplitude));
                if (how.evolves) partner_[i] = std::complex<float>(here.amplitude - std::conj(there.amplitude));
                // Every cell of the full grid once: -k is in this half only in column 0 (and the Nyquist
                // column, empty), where it is counted as its own k.
                rowVariance[r] += here.variance + (q > 0 ? there.variance : 0.0);
                rowBound[r] += here.modulus + (q > 0 ? there.modulus : 0.0);
            }
        }
    });
    for (int r = 0; r < n; ++r) {
        resolvedVariance_ += rowVariance[r];
        shiftBound_ += 2.0 * rowBound[r];  // |h0(k)| and, through its partner, |h0(-k)|
    }
}

void Ocean::fieldsInto(double t, const SeaFieldTargets& to, double choppiness, int threads) const {
    const int n = options_.size, columns = n / 2 + 1;
    const size_t cells = size_t(n) * columns;
    const double dk = 2 * std::numbers::pi / options_.tileSize;
    // h(k, t) = h0(k) e^{-i w t} + conj(h0(-k)) e^{i w t} = cos(w t) h(k, 0) - i sin(w t) partner(k):
    // Hermitian in k, so the sea is real, and the energy that the spectrum puts at k (along the wind) runs
    // toward +k, with the wind. At t = 0 (a single frame, a loop's first) it is h(k, 0) as it is.
    std::vector<std::complex<float>> evolved;
    const std::complex<float>* spectrum = initial_.data();
    if (t != 0.0) {
        assert(!partner_.empty() && "an ocean made with evolves = false holds t = 0 only");
        evolved.resize(cells);
        parallelFor(n, threads, [&](int begin, int end) {
            for (int r = begin; r < end; ++r) {
                const double ky = signedBin(r, n) * dk;
                for (int q = 0; q < columns; ++q) {
                    const size_t i = size_t(r) * columns + q;
                    const std::complex<double> a(initial_[i]), b(partner_[i]);
                    if (a == 0.0 && b == 0.0) continue;  // no wave here: no sine or cosine to take
                    const double kx = q * dk, w = angularFrequency(options_, std::sqrt(kx * kx + ky * ky));
                    const double c = std::cos(w * t), s = std::sin(w * t);
                    evolved[i] = std::complex<float>(c * a - std::complex<double>(0.0, s) * b);
                }
            }
        });
        spectrum = evolved.data();
    }

    // The fields' multipliers of h(k, t), as a column pass's (of kx and ky) times a row pass's (of kx alone),
    // so that fields sharing the first share one column pass (dft.hpp): D(k) = i k/|k| h(k) (a crest pulls
    // its neighbours in: x + D compresses it, as a Gerstner wave does) and its derivatives, i kx or i ky
    // once more. Four column passes for six fields:
    //   h / k       then  i kx: Dx,  -kx^2: Dxx
    //   -ky^2 h / k            Dyy
    //   ky h / k    then  i: Dy,     -kx: Dxy
    //   h                      heights
    // The Jacobian (1 + c Dxx)(1 + c Dyy) - c^2 Dxy^2 is built up in its target in that order. k = 0
    // carries nothing. Each column pass reads h(k, t) times its multiplier as it goes (the loop compiled
    // for each pass alone) and keeps its result in the heights' storage, which the heights, last, write
    // over: no spectrum-sized scratch (4 bytes a texel) beside the image. Without heights, a plane of its own.
    enum ColumnPass { Plain, OverK, MinusKy2OverK, KyOverK };
    std::vector<float> ownScratch;
    std::vector<std::complex<float>> lastColumn(n);
    detail::HalfSpectrumScratch scratch{to.heights.first, to.heights.stride, lastColumn.data()};
    if (!scratch.first) {
        ownScratch.resize(size_t(n) * n);
        scratch = {ownScratch.data(), 1, lastColumn.data()};
    }
    auto source = [&](auto passConstant) -> detail::HalfSpectrumSource {
        return [&](int q0, int count, std::complex<float>* lines, size_t lineStride) {
            constexpr ColumnPass pass = decltype(passConstant)::value;
            for (int r = 0; r < n; ++r) {
                const std::complex<float>* from = spectrum + size_t(r) * columns;
                std::complex<float>* rowOfLines = lines + r;  // row r of line i at rowOfLines[i * lineStride]
                if constexpr (pass == Plain) {
                    for (int q = q0; q < q0 + count; ++q) rowOfLines[(q - q0) * lineStride] = from[q];
                } else {
                    const float ky = float(signedBin(r, n) * dk);
                    for (int q = q0; q < q0 + count; ++q) {
                        const float kx = float(q * dk), k2 = kx * kx + ky * ky;
                        const float inverse = k2 > 0.0f ? 1.0f / std::sqrt(k2) : 0.0f;
                        std::complex<float>& z = rowOfLines[(q - q0) * lineStride];
                        if constexpr (pass == OverK) z = from[q] * inverse;
                        if constexpr (pass == MinusKy2OverK) z = from[q] * (-ky * ky * inverse);
                        if constexpr (pass == KyOverK) z = from[q] * (ky * inverse);
                    }
                }
            }
        };
    };
    // Row-pass factors (of kx = q dk) and where each field's rows go.
    std::vector<std::complex<float>> ikx(columns), minusKx2(columns), minusKx(columns), i(columns, {0.0f, 1.0f});
    for (int q = 0; q < columns; ++q) {
        const float kx = float(q * dk);
        ikx[q] = {0.0f, kx}, minusKx2[q] = -kx * kx, minusKx[q] = -kx;
    }
    const double c = choppiness;
    auto into = [](const SeaFieldTarget& target, int width, auto combine) {
        return [&target, width, combine](int y, const float* values) {
            float* out = target.first + size_t(y) * width * target.stride;
            const size_t step = size_t(target.stride);
            for (int x = 0; x < width; ++x) combine(out[x * step], double(values[x]));
        };
    };
    auto store = [](float& texel, double v) { texel = float(v); };
    auto transform = [&](auto passConstant, const std::vector<detail::HalfSpectrumRows>& rows) {
        detail::inverseRealDftOfHalf(n, n, threads, source(passConstant), scratch, rows);
    };
    using std::integral_constant;
    using Rows = std::vector<detail::HalfSpectrumRows>;
    if (to.shiftX.first || to.jacobian.first) {
        Rows rows;
        if (to.shiftX.first) rows.push_back({ikx, into(to.shiftX, n, store)});
        if (to.jacobian.first) rows.push_back({minusKx2, into(to.jacobian, n, [c](float& j, double xx) { j = float(1 + c * xx); })});
        transform(integral_constant<ColumnPass, OverK>{}, rows);
    }
    if (to.jacobian.first)
        transform(integral_constant<ColumnPass, MinusKy2OverK>{},
                  Rows{{{}, into(to.jacobian, n, [c](float& j, double yy) { j = float(double(j) * (1 + c * yy)); })}});
    if (to.shiftY.first || to.jacobian.first) {
        Rows rows;
        if (to.shiftY.first) rows.push_back({i, into(to.shiftY, n, store)});
        if (to.jacobian.first)
            rows.push_back({minusKx, into(to.jacobian, n, [c](float& j, double xy) { j = float(double(j) - c * c * xy * xy); })});
        transform(integral_constant<ColumnPass, KyOverK>{}, rows);
    }
    if (to.heights.first) transform(integral_constant<ColumnPass, Plain>{}, Rows{{{}, into(to.heights, n, store)}});
}

SeaFields Ocean::fields(double t, const SeaFieldSet& which, double choppiness, int threads) const {
    const int n = options_.size;
    SeaFields result;
    SeaFieldTargets to;
    if (which.heights) {
        result.heights = Image(n, n, 1);
        to.heights = {result.heights.pixels.data(), 1};
    }
    if (which.shift) {
        result.shift = Image(n, n, 2);
        to.shiftX = {result.shift.pixels.data(), 2};
        to.shiftY = {result.shift.pixels.data() + 1, 2};
    }
    if (which.jacobian) {
        result.jacobian = Image(n, n, 1);
        to.jacobian = {result.jacobian.pixels.data(), 1};
    }
    fieldsInto(t, to, choppiness, threads);
    return result;
}

Image Ocean::heights(double t) const { return fields(t, {}).heights; }

Image Ocean::shift(double t) const { return fields(t, {false, true, false}).shift; }

}  // namespace heightpack
