#include "enlargement.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "heightpack/core/parallel.hpp"

#include "range.hpp"

namespace heightpack::detail {

namespace {

constexpr int kMostEnlargeTaps = 6;  // Lanczos3's

double enlargeKernelAt(Kernel kernel, double t) {
    const double a = std::abs(t);
    switch (kernel) {
        case Kernel::Nearest: return a < 0.5 ? 1.0 : 0.0;
        case Kernel::Linear: return std::max(0.0, 1 - a);
        case Kernel::CatmullRom:
            return a < 1 ? 1.5 * a * a * a - 2.5 * a * a + 1 : a < 2 ? -0.5 * a * a * a + 2.5 * a * a - 4 * a + 2 : 0.0;
        case Kernel::BlackmanHarris: {  // OpenImageIO's, 3 texels wide: its default for enlarging
            if (a >= 1.5) return 0.0;
            const double x = 2 * std::numbers::pi * (a / 1.5 + 1) / 2;
            return 0.35875 - 0.48829 * std::cos(x) + 0.14128 * std::cos(2 * x) - 0.01168 * std::cos(3 * x);
        }
        case Kernel::Lanczos3: {
            if (a < 1e-9) return 1.0;
            if (a >= 3) return 0.0;
            const double x = std::numbers::pi * a;
            return 3 * std::sin(x) * std::sin(x / 3) / (x * x);
        }
    }
    return 0.0;
}

int kernelRadius(Kernel kernel) {
    switch (kernel) {
        case Kernel::Nearest: return 0;
        case Kernel::Linear: return 1;
        case Kernel::CatmullRom:
        case Kernel::BlackmanHarris: return 2;
        case Kernel::Lanczos3: return 3;
    }
    return 3;
}

// The taps of an enlargement by `factor`: output texel x reads source texels x / factor + first[p] + t,
// t < count, with weights weight[p][t], p = x % factor.
struct EnlargeTaps {
    int factor = 1, count = 1;
    std::vector<int> first;
    std::vector<std::array<double, kMostEnlargeTaps>> weight;
    explicit EnlargeTaps(Enlargement e) : factor(e.factor), first(size_t(e.factor)), weight(size_t(e.factor)) {
        const int radius = kernelRadius(e.kernel);
        count = e.kernel == Kernel::Nearest ? 1 : 2 * radius;
        for (int p = 0; p < factor; ++p) {
            const double s = (p + 0.5) / factor - 0.5;  // the texel's centre in source texels, from x / factor
            weight[p].fill(0.0);
            if (e.kernel == Kernel::Nearest) {
                first[p] = 0;
                weight[p][0] = 1;
                continue;
            }
            first[p] = int(std::floor(s)) - radius + 1;
            double total = 0;
            for (int t = 0; t < count; ++t) total += weight[p][t] = enlargeKernelAt(e.kernel, s - (first[p] + t));
            for (int t = 0; t < count; ++t) weight[p][t] /= total;
        }
    }
};

int clampedTap(int j, int n) { return std::clamp(j, 0, n - 1); }
int wrappedTap(int j, int n) { return ((j % n) + n) % n; }

// The least-squares source of lines of length n * factor under the taps (edges clamped): the normal
// matrix is banded (half-bandwidth count - 1), factored once by a banded Cholesky; each line is then its
// right-hand side and two substitutions.
class SourceFit {
public:
    SourceFit(const EnlargeTaps& taps, int n) : taps_(taps), n_(n), band_(taps.count - 1), l_(size_t(n) * (band_ + 1), 0.0) {
        auto at = [&](int i, int d) -> double& { return l_[size_t(i) * (band_ + 1) + d]; };
        for (int x = 0; x < n * taps.factor; ++x) {
            const int p = x % taps.factor, base = x / taps.factor + taps.first[p];
            for (int a = 0; a < taps.count; ++a)
                for (int b = 0; b < taps.count; ++b) {
                    const int ja = clampedTap(base + a, n), jb = clampedTap(base + b, n);
                    if (ja >= jb) at(ja, ja - jb) += taps.weight[p][a] * taps.weight[p][b];
                }
        }
        double largest = 0;
        for (int i = 0; i < n; ++i) largest = std::max(largest, at(i, 0));
        for (int i = 0; i < n; ++i) at(i, 0) += 1e-9 * largest;  // a source texel no output reads stays defined
        for (int i = 0; i < n; ++i)
            for (int d = std::min(band_, i); d >= 0; --d) {
                const int j = i - d;
                double sum = at(i, d);
                for (int k = std::max(0, i - band_); k < j; ++k) sum -= at(i, i - k) * at(j, j - k);
                at(i, d) = d == 0 ? std::sqrt(std::max(sum, 1e-300)) : sum / at(j, 0);
            }
    }
    // out[j * stride] for j < n from line[x * stride] for x < n * factor.
    template <class In, class Out>
    void solve(const In* line, size_t inStride, Out* out, size_t outStride, std::vector<double>& scratch) const {
        scratch.assign(size_t(n_), 0.0);
        for (int x = 0; x < n_ * taps_.factor; ++x) {
            const int p = x % taps_.factor, base = x / taps_.factor + taps_.first[p];
            const double y = double(line[size_t(x) * inStride]);
            for (int t = 0; t < taps_.count; ++t) scratch[clampedTap(base + t, n_)] += taps_.weight[p][t] * y;
        }
        auto at = [&](int i, int d) { return l_[size_t(i) * (band_ + 1) + d]; };
        for (int i = 0; i < n_; ++i) {
            double sum = scratch[i];
            for (int k = std::max(0, i - band_); k < i; ++k) sum -= at(i, i - k) * scratch[k];
            scratch[i] = sum / at(i, 0);
        }
        for (int i = n_ - 1; i >= 0; --i) {
            double sum = scratch[i];
            for (int k = i + 1; k <= std::min(n_ - 1, i + band_); ++k) sum -= at(k, k - i) * scratch[k];
            scratch[i] = sum / at(i, 0);
        }
        for (int i = 0; i < n_; ++i) out[size_t(i) * outStride] = static_cast<Out>(scratch[i]);
    }

private:
    const EnlargeTaps& taps_;
    int n_, band_;
    std::vector<double> l_;  // the Cholesky factor's band: row i, d = i - column
};

// One enlargement along a line: out[x * stride] for x < n * factor from in[j * stride] for j < n.
template <class In, class Out>
void enlargeLine(const EnlargeTaps& taps, int n, bool periodic, const In* in, size_t inStride, Out* out, size_t outStride) {
    for (int x = 0; x < n * taps.factor; ++x) {
        const int p = x % taps.factor, base = x / taps.factor + taps.first[p];
        double sum = 0;
        for (int t = 0; t < taps.count; ++t)
            sum += taps.weight[p][t] * double(in[size_t(periodic ? wrappedTap(base + t, n) : clampedTap(base + t, n)) * inStride]);
        out[size_t(x) * outStride] = static_cast<Out>(sum);
    }
}

constexpr int kEnlargeColumns = 16;  // columns handled together, so each row's read is one short run

Image windowOf(const Image& map, int x0, int y0, int w, int h) {
    Image out(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) out.at(x, y) = map.at(x0 + x, y0 + y);
    return out;
}

}  // namespace

Image fitSource(const Image& map, Enlargement e, int threads) {
    const int w = map.width, h = map.height, f = e.factor, sw = w / f, sh = h / f;
    const EnlargeTaps taps(e);
    const SourceFit alongX(taps, sw), alongY(taps, sh);
    std::vector<float> rows(size_t(h) * sw);  // each row fitted across
    parallelFor(h, threads, [&](int begin, int end) {
        std::vector<double> scratch;
        for (int y = begin; y < end; ++y) alongX.solve(&map.pixels[size_t(y) * w], 1, &rows[size_t(y) * sw], 1, scratch);
    });
    Image out(sw, sh, 1);
    parallelFor((sw + kEnlargeColumns - 1) / kEnlargeColumns, threads, [&](int begin, int end) {
        std::vector<double> scratch;
        std::vector<float> column(static_cast<size_t>(h));
        for (int b = begin; b < end; ++b)
            for (int x = b * kEnlargeColumns; x < std::min(sw, (b + 1) * kEnlargeColumns); ++x) {
                for (int y = 0; y < h; ++y) column[y] = rows[size_t(y) * sw + x];
                alongY.solve(column.data(), 1, &out.pixels[x], size_t(sw), scratch);
            }
    });
    return out;
}

Image enlarge(const Image& source, Enlargement e, bool periodic, int threads) {
    const int sw = source.width, sh = source.height, f = e.factor, w = sw * f, h = sh * f;
    const EnlargeTaps taps(e);
    std::vector<float> rows(size_t(sh) * w);  // each source row enlarged across
    parallelFor(sh, threads, [&](int begin, int end) {
        for (int y = begin; y < end; ++y) enlargeLine(taps, sw, periodic, &source.pixels[size_t(y) * sw], 1, &rows[size_t(y) * w], 1);
    });
    Image out(w, h, 1);
    parallelFor((w + kEnlargeColumns - 1) / kEnlargeColumns, threads, [&](int begin, int end) {
        for (int b = begin; b < end; ++b)
            for (int x = b * kEnlargeColumns; x < std::min(w, (b + 1) * kEnlargeColumns); ++x)
                enlargeLine(taps, sh, periodic, &rows[x], size_t(w), &out.pixels[x], size_t(w));
    });
    return out;
}

Image enlargedTile(const Image& map, const Image& source, const Image& sourceTiled, Enlargement e, int reachX, int reachY,
                   SampleRange range, int threads) {
    const int f = e.factor, w = map.width, h = map.height, sw = source.width, sh = source.height;
    Image change(sw, sh, 1);
    for (size_t i = 0; i < change.pixels.size(); ++i) change.pixels[i] = sourceTiled.pixels[i] - source.pixels[i];
    Image out = enlarge(change, e, true, threads);
    const Image sourceAsTile = enlarge(source, e, true, threads);  // with the change: sourceTiled enlarged
    parallelFor(h, threads, [&](int begin, int end) {
        for (int y = begin; y < end; ++y) {
            const int sy = y / f;
            const bool rowInBand = std::min(sy, sh - 1 - sy) < reachY + kEnlargedTileReach;
            for (int x = 0; x < w; ++x) {
                const int sx = x / f;
                const size_t i = size_t(y) * w + x;
                out.pixels[i] += rowInBand || std::min(sx, sw - 1 - sx) < reachX + kEnlargedTileReach ? sourceAsTile.pixels[i] : map.pixels[i];
            }
        }
    });
    easeIntoRange(out, range, threads);
    return out;
}

Image roundedSource(const Image& map, Enlargement e, double& quantum, SampleRange range, int threads) {
    Image source = fitSource(map, e, threads);
    // On 8-bit levels: a fit's value within a tenth of a step of one, where a value off them would be one
    // time in five. The enlargement's own rounding (16 bits) moves a fit's value by far less.
    constexpr double kEightBits = 1.0 / 255;
    if (quantum < kEightBits) {
        size_t on = 0;
        for (float v : source.pixels) on += std::abs(v / kEightBits - std::round(v / kEightBits)) < 0.1;
        if (double(on) >= 0.9 * double(source.pixels.size())) quantum = kEightBits;
    }
    putOnLevels(source, quantum, range);
    return source;
}

void putOnLevels(Image& image, double quantum, SampleRange range) {
    for (float& v : image.pixels)
        v = std::clamp(quantum > 0 ? static_cast<float>(std::round(v / quantum) * quantum) : v, range.low, range.high);
}

Enlargement findEnlargement(const Image& map, double quantum, int threads, bool isSource) {
    const int w = map.width, h = map.height;
    // Smaller maps are tiled at their own size: cheap already, and their source would leave the model
    // little to learn from (the bundled 512^2 painting is an 8x enlargement of 64^2).
    if (map.channels != 1 || (!isSource && std::min(w, h) < kLeastEnlargedSide)) return {};
    // A central window aligned to every factor's grid.
    const int cw = std::min(w, 512) / 16 * 16, ch = std::min(h, 512) / 16 * 16;
    const int x0 = (w - cw) / 2 / 16 * 16, y0 = (h - ch) / 2 / 16 * 16;
    const Image window = windowOf(map, x0, y0, cw, ch);
    // The map's finest detail: its mean square difference from its 3 x 3 mean, away from the window's edge.
    double fine = 0;
    for (int y = 1; y + 1 < ch; ++y)
        for (int x = 1; x + 1 < cw; ++x) {
            double mean = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) mean += window.at(x + dx, y + dy);
            const double d = window.at(x, y) - mean / 9;
            fine += d * d;
        }
    fine /= double(cw - 2) * (ch - 2);
    const double rounding = quantum * quantum / 12;
    for (int factor : {16, 8, 4, 2}) {
        if (w % factor != 0 || h % factor != 0 || w / factor < kLeastSourceSide || h / factor < kLeastSourceSide) continue;
        Enlargement best;
        double bestResidual = 0;
        for (Kernel kernel : {Kernel::Nearest, Kernel::Linear, Kernel::CatmullRom, Kernel::BlackmanHarris, Kernel::Lanczos3}) {
            const Enlargement e{factor, kernel};
            const int margin = factor * (kernelRadius(kernel) + 2);
            if (cw <= 4 * margin || ch <= 4 * margin) continue;
            const Image back = enlarge(fitSource(window, e, threads), e, false, threads);
            double residual = 0;
            for (int y = margin; y < ch - margin; ++y)
                for (int x = margin; x < cw - margin; ++x) {
                    const double d = double(window.at(x, y)) - back.at(x, y);
                    residual += d * d;
                }
            residual /= double(cw - 2 * margin) * (ch - 2 * margin);
            if (best.factor == 1 || residual < bestResidual) {
                best = e;
                bestResidual = residual;
            }
        }
        // Beyond the rounding's noise (of which a fit absorbs a part), what the source misses must be a small
        // part of the map's finest detail: the bands, made from the source, lack it.
        // A fit of one source value per factor^2 texels absorbs that part of the rounding's noise.
        const double unexplained = bestResidual - rounding * (1 - 1.0 / (factor * factor));
        if (best.factor > 1 && unexplained <= 0.1 * rounding + 0.02 * fine) return best;
    }
    return {};
}

}  // namespace heightpack::detail
