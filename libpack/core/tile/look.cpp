// The frame, blob and echo statistics of tile/look.hpp.
#include "heightpack/core/tile/look.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "heightpack/core/parallel.hpp"
#include "heightpack/core/tile/tileable.hpp"

#include "field.hpp"
#include "gaussian_model.hpp"
#include "look_spectrum.hpp"

namespace heightpack {

namespace {

using Grid = detail::Field;
using detail::HalfSpectrum;
using detail::Profiles;
using detail::bandPassed;
using detail::energyProfiles;
using detail::fieldOf;
using detail::spectrumOf;

// Torus distance between offsets a and b on a circle of n.
int circularDistance(int a, int n) {
    a = ((a % n) + n) % n;
    return std::min(a, n - a);
}

// z = (value - mean) / std of the null values, taken as Student's t with `independent` - 1 degrees of
// freedom (neighbouring placements overlap: only about `independent` of them say something new) and
// brought to the normal scale (Wallace's approximation), so a wide ring on a small map, judged against a
// handful of independent placements, does not score like a narrow one judged against hundreds.
double zScore(double value, const std::vector<double>& null, double independent) {
    if (null.size() < 2) return 0.0;
    double mean = 0, var = 0;
    for (double x : null) mean += x;
    mean /= double(null.size());
    for (double x : null) var += (x - mean) * (x - mean);
    const double sd = std::sqrt(var / double(null.size() - 1));
    if (!(sd > 1e-12)) return 0.0;
    const double t = (value - mean) / sd, nu = std::max(1.0, independent - 1);
    const double z = (1 - 1 / (8 * nu)) * std::sqrt(nu * std::log1p(t * t / nu));
    return t < 0 ? -z : z;
}

// The largest |z| over rings at distances [0,1), [1,2), [2,4), ... up to reach from a grid line placed at
// offset 0 of a circular profile, against the same rings around every offset at least 2 * reach away
// (whose rings cannot reach into a band the tile edge spoiled).
// Ring means are compared as log ratios to the profile's mean, plus floor (energies and squared values
// are skewed: their logs are closer to normal, so a z-score means the same on smooth and rough maps).
double ringScore(const std::vector<double>& profile, int reach, double floor) {
    const int n = static_cast<int>(profile.size());
    std::vector<double> prefix(2 * n + 1, 0.0);  // over the profile repeated twice
    for (int i = 0; i < 2 * n; ++i) prefix[i + 1] = prefix[i] + profile[i % n];
    const double mean = prefix[n] / n;
    auto range = [&](int from, int count) {  // sum of count values starting at from (circular)
        const int start = ((from % n) + n) % n;
        return prefix[start + count] - prefix[start];
    };
    double worst = 0;
    for (int lo = 0, hi = 1; lo < reach; lo = hi, hi *= 2) {
        const int top = std::min(hi, reach), count = top - lo;
        auto ring = [&](int o) {  // columns o + lo .. o + top - 1 and o - top .. o - lo - 1
            const double r = (range(o + lo, count) + range(o - top, count)) / (2.0 * count);
            return std::log((r + floor * mean + 1e-30) / (mean + floor * mean + 1e-30));
        };
        std::vector<double> null;
        for (int o = 0; o < n; ++o)
            if (circularDistance(o, n) >= 2 * reach) null.push_back(ring(o));
        worst = std::max(worst, std::abs(zScore(ring(0), null, double(null.size()) / count)));
    }
    return worst;
}

// The means of g's columns and of its rows, on all threads: each mean sums in one fixed order, so the
// thread count cannot change it.
Profiles profilesOf(const Grid& g, int threads) {
    Profiles p{std::vector<double>(g.w, 0.0), std::vector<double>(g.h, 0.0)};
    parallelFor(g.h, threads, [&](int begin, int end) {
        for (int y = begin; y < end; ++y) {
            double sum = 0;
            for (int x = 0; x < g.w; ++x) sum += g.at(x, y);
            p.rows[y] = sum / g.w;
        }
    });
    constexpr int kColumns = 64;  // a block of columns per task, read a row segment at a time
    parallelFor((g.w + kColumns - 1) / kColumns, threads, [&](int begin, int end) {
        for (int x0 = begin * kColumns; x0 < std::min(g.w, end * kColumns); x0 += kColumns) {
            const int x1 = std::min(g.w, x0 + kColumns);
            for (int y = 0; y < g.h; ++y)
                for (int x = x0; x < x1; ++x) p.columns[x] += g.at(x, y);
            for (int x = x0; x < x1; ++x) p.columns[x] /= g.h;
        }
    });
    return p;
}

// A summed-area table of q, so that the sum over any circular square is at most four rectangles of four
// lookups each. Made on all threads: the rows' running sums, then the columns' (each sum in one order).
struct TiledSums {
    int w, h;
    std::vector<double> sat;  // (w + 1) x (h + 1): sat(x, y) is the sum over [0, x) x [0, y)
    TiledSums(const Grid& q, int threads) : w(q.w), h(q.h), sat(size_t(q.w + 1) * (q.h + 1), 0.0) {
        parallelFor(h, threads, [&](int begin, int end) {
            for (int y = begin; y < end; ++y) {
                double* row = &sat[size_t(y + 1) * (w + 1)];
                for (int x = 0; x < w; ++x) row[x + 1] = row[x] + q.at(x, y);
            }
        });
        constexpr int kColumns = 64;
        parallelFor((w + kColumns) / kColumns, threads, [&](int begin, int end) {
            for (int y = 1; y <= h; ++y)
                for (int x = begin * kColumns; x < std::min(w + 1, end * kColumns); ++x) at(x, y) += at(x, y - 1);
        });
    }
    double& at(int x, int y) { return sat[size_t(y) * (w + 1) + x]; }
    double at(int x, int y) const { return sat[size_t(y) * (w + 1) + x]; }
    double rectangle(int x0, int y0, int x1, int y1) const { return at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0); }
    // The sum over the side x side square (side at most the tile's) whose corner is (x0, y0), both taken
    // modulo the tile: the parts before and after each wrap line.
    double square(int x0, int y0, int side) const {
        x0 = (x0 % w + w) % w;
        y0 = (y0 % h + h) % h;
        const int xEnd = std::min(w, x0 + side), xWrap = x0 + side - xEnd, yEnd = std::min(h, y0 + side), yWrap = y0 + side - yEnd;
        return rectangle(x0, y0, xEnd, yEnd) + rectangle(0, y0, xWrap, yEnd) + rectangle(x0, 0, xEnd, yWrap) + rectangle(0, 0, xWrap, yWrap);
    }
};

// The largest |z| of the mean of q over squares of half-side s centred on the tile corner (0, 0), against
// squares centred on every point at least an eighth of the tile from both grid lines.
double cornerScore(const TiledSums& sums, int half) {
    const int w = sums.w, h = sums.h, side = 2 * half;
    auto square = [&](int cx, int cy) {
        return std::sqrt(std::max(0.0, sums.square(cx - half, cy - half, side) / (double(side) * side)));
    };
    std::vector<double> null;
    const int step = std::max(1, half / 4);
    for (int cy = 0; cy < h; cy += step)
        for (int cx = 0; cx < w; cx += step)
            if (circularDistance(cx, w) >= w / 8 && circularDistance(cy, h) >= h / 8) null.push_back(square(cx, cy));
    return std::abs(zScore(square(0, 0), null, double(null.size()) * step * step / (4.0 * half * half)));
}

Image halved(const Image& map, int threads) {
    Image out(map.width / 2, map.height / 2, 1);
    parallelFor(out.height, threads, [&](int begin, int end) {
        for (int y = begin; y < end; ++y)
            for (int x = 0; x < out.width; ++x)
                out.at(x, y) = 0.25f * (map.at(2 * x, 2 * y) + map.at(2 * x + 1, 2 * y) + map.at(2 * x, 2 * y + 1) +
                                        map.at(2 * x + 1, 2 * y + 1));
    });
    return out;
}

// The map's first channel, halved until no side is over 2048 (the scale the statistics are taken at); a
// one-channel map larger than that is halved from itself, not copied first.
Image atLookScale(const Image& input, int threads) {
    auto tooLarge = [](const Image& m) { return m.width > 2048 || m.height > 2048; };
    Image map = input.channels != 1 ? selectChannels(input, {0}) : tooLarge(input) ? halved(input, threads) : input;
    while (tooLarge(map)) map = halved(map, threads);
    return map;
}

// The map's power spectrum and the same smoothed over 5x5 frequency bins (a box, three times each way,
// circular): the smooth part is the field's statistics, what stays in the ratio is fine structure. Both
// for the half kx <= w/2 only (w / 2 + 1 columns): the power is even, P(x, y) = P(w - x, -y), and the
// symmetric smoothing keeps it so, so the other half is the mirror and need not be made.
struct Spectra {
    Grid power, smooth;
    Spectra(int columns, int h) : power(columns, h, Grid::unset), smooth(columns, h, Grid::unset) {}  // both written in full
};

Spectra spectraOf(const HalfSpectrum& spectrum, int threads) {
    const int h = spectrum.h, w = spectrum.w, columns = spectrum.columns;
    Spectra out(columns, h);
    Grid& power = out.power;
    Grid& smooth = out.smooth;
    parallelFor(h, threads, [&](int begin, int end) {
        for (int y = begin; y < end; ++y)
            for (int x = 0; x < columns; ++x)
                power.at(x, y) = (x == 0 && y == 0) ? 0.0 : std::norm(std::complex<double>(spectrum.at(x, y)));
    });
    // Smoothed over 5x5 frequency bins (a box, three times each way, circular), the first pass from the
    // power itself. A row's neighbours beyond the half (x < 0 or x >= columns, modulo w) are the mirror
    // row's (-y) at w - x; the rows' indices are wrapped once per line, not per texel.
    Grid next(columns, h, Grid::unset);
    std::vector<int> wrapY(size_t(h) + 4);
    for (int i = -2; i < h + 2; ++i) wrapY[i + 2] = (i + h) % h;
    for (int pass = 0; pass < 3; ++pass) {
        const Grid& from = pass == 0 ? power : smooth;
        parallelFor(h, threads, [&](int begin, int end) {
            std::vector<double> padded(size_t(columns) + 4);  // the row with its wrapped neighbours: no gather
            for (int y = begin; y < end; ++y) {
                const double* row = &from.v[size_t(y) * columns];
                const double* mirror = &from.v[size_t((h - y) % h) * columns];
                for (int i = 0; i < columns + 4; ++i) {
                    const int x = ((i - 2) % w + w) % w;  // the full spectrum's column
                    padded[i] = x < columns ? row[x] : mirror[w - x];
                }
                for (int x = 0; x < columns; ++x) {
                    double sum = 0;
                    for (int d = 0; d < 5; ++d) sum += padded[x + d];
                    next.at(x, y) = sum / 5;
                }
            }
        });
        parallelFor(h, threads, [&](int begin, int end) {
            for (int y = begin; y < end; ++y) {
                const double* rows[5];
                for (int d = 0; d < 5; ++d) rows[d] = &next.v[size_t(wrapY[y + d]) * columns];
                for (int x = 0; x < columns; ++x) {
                    double sum = 0;
                    for (int d = 0; d < 5; ++d) sum += rows[d][x];
                    smooth.at(x, y) = sum / 5;
                }
            }
        });
    }
    return out;
}

// echoOf for the map whose spectrum (spectrumOf) is given: measureTileLook has it already.
double echoOfSpectrum(const HalfSpectrum& spectrum, int threads) {
    const int w = spectrum.w, h = spectrum.h;
    // The autocorrelation of the map whitened by its own smoothed spectrum: a stationary field's structure
    // (smooth, directional, large or small scaled) divides out, leaving a spike at lag 0 and noise of about
    // 1/sqrt(texels); a feature repeated at lag L multiplies the spectrum by 1 + cos(k.L), an oscillation
    // finer than the smoothing, which stays and becomes a peak at L.
    const Spectra s = spectraOf(spectrum, threads);
    HalfSpectrum whitened{w, h, spectrum.columns, std::vector<std::complex<float>>(spectrum.values.size())};
    parallelFor(h, threads, [&](int begin, int end) {
        for (int y = begin; y < end; ++y)
            for (int x = 0; x < whitened.columns; ++x)
                whitened.values[size_t(y) * whitened.columns + x] =
                    float(s.smooth.at(x, y) > 0 ? s.power.at(x, y) / s.smooth.at(x, y) : 0.0);
    });
    const Grid correlation = fieldOf(whitened, threads);
    const double zero = correlation.at(0, 0);
    if (!(zero > 0)) return 0.0;
    std::vector<double> worstOfRow(h, -1.0);  // a maximum is the same in any order
    parallelFor(h, threads, [&](int begin, int end) {
        for (int y = begin; y < end; ++y)
            for (int x = 0; x < w; ++x)
                if (circularDistance(x, w) > w / 16 || circularDistance(y, h) > h / 16)
                    worstOfRow[y] = std::max(worstOfRow[y], correlation.at(x, y) / zero);
    });
    return *std::max_element(worstOfRow.begin(), worstOfRow.end());
}

}  // namespace

double echoOf(const Image& map, int threads) {
    if (map.width < 64 || map.height < 64) return 0.0;
    return echoOfSpectrum(spectrumOf(map, threads), threads);
}

double sourceEchoOf(const Image& input, int threads) {
    if (input.width < 64 || input.height < 64) return 0.0;
    const Image source = atLookScale(input, threads);
    const HalfSpectrum periodic{source.width, source.height, source.width / 2 + 1, detail::periodicHalfSpectrum(source, threads)};
    return std::max(0.0, echoOfSpectrum(periodic, threads));
}

TileLook measureTileLook(const Image& input, const LookOptions& options) {
    TileLook look;
    const Image map = atLookScale(input, options.threads);
    const int w = map.width, h = map.height;
    if (w < 64 || h < 64) return look;
    look.measured = true;
    const HalfSpectrum spectrum = spectrumOf(map, options.threads);
    const int reachX = std::max(4, w / 8), reachY = std::max(4, h / 8);

    // Frame: band-pass energy in octaves, from 1-2 texels up to 1/64-1/32 of the tile (a smooth painting's
    //        detail is far coarser than a texel, and a frame is a loss or excess of its contrast).
    for (double fine = 1.0; fine == 1.0 || 2 * fine <= std::max(w, h) / 32.0; fine *= 2) {
        const double coarse = 2 * fine;
        const Profiles energy = energyProfiles(spectrum, fine, coarse, options.threads);
        look.frame = std::max({look.frame, ringScore(energy.columns, reachX, 0.0), ringScore(energy.rows, reachY, 0.0)});
    }
    // Blobs: the squared standardised band-pass at the scale of a blob, 1/128 to 1/32 of the tile (the
    //        low-pass of the detail: a red-noise map's swell, far larger, would make every place unlike
    //        every other).
    const double large = std::max(w, h) / 32.0, small = std::max(1.0, std::max(w, h) / 128.0);
    Grid q = bandPassed(spectrum, small, large, options.threads);
    // Per row on all threads, the rows then summed in order: the same on any thread count.
    auto sumOverRows = [&](auto term) {
        std::vector<double> rows(q.h, 0.0);
        parallelFor(q.h, options.threads, [&](int begin, int end) {
            for (int y = begin; y < end; ++y)
                for (int x = 0; x < q.w; ++x) rows[y] += term(q.at(x, y));
        });
        double total = 0;
        for (double r : rows) total += r;
        return total;
    };
    const double mean = sumOverRows([](double v) { return v; }) / double(q.v.size());
    const double sd = std::sqrt(sumOverRows([&](double v) { return (v - mean) * (v - mean); }) / double(q.v.size()));
    parallelFor(q.h, options.threads, [&](int begin, int end) {
        for (size_t i = size_t(begin) * q.w; i < size_t(end) * q.w; ++i)
            q.v[i] = sd > 1e-12 ? ((q.v[i] - mean) / sd) * ((q.v[i] - mean) / sd) : 0.0;
    });
    const TiledSums sums(q, options.threads);
    const Profiles profiles = profilesOf(q, options.threads);
    look.blobs = std::max({ringScore(profiles.columns, reachX, 0.05), ringScore(profiles.rows, reachY, 0.05),
                           cornerScore(sums, std::max(2, std::min(w, h) / 32)), cornerScore(sums, std::max(2, std::min(w, h) / 16))});
    // Echo, less the source's own (of its periodic component: its seams would echo along their lines).
    look.echo = echoOfSpectrum(spectrum, options.threads);  // the map's spectrum, transformed once
    look.echoBaseline = options.sourceEcho ? *options.sourceEcho : options.source ? sourceEchoOf(*options.source, options.threads) : 0.0;
    // An echo the tile adds: never below 0 (a tile that echoes less than its source adds none).
    look.echo = std::max(0.0, look.echo - look.echoBaseline);
    return look;
}

}  // namespace heightpack
