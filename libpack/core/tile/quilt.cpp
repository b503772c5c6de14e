// Quilting a strip across each wrap line: see tile/quilt.hpp for the steps.
#include "heightpack/core/tile/quilt.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <vector>

#include "heightpack/core/parallel.hpp"
#include "heightpack/core/tile/tileable.hpp"

#include "dft.hpp"
#include "enlargement.hpp"
#include "field.hpp"
#include "quilt_kernels.hpp"
#include "range.hpp"
#include "smoothing.hpp"

namespace heightpack {

namespace {

using detail::Field;

int wrapped(int i, int n) { return ((i % n) + n) % n; }

// A strip of `width` lines centred on the wrap line between the last line and the first, across a field
// whose lines run along x (acrossX: the left/right wrap line, u = x, v = y) or along y. Its outer `overlap`
// lines on each side are where the copy is cut in.
struct Strip {
    bool acrossX = true;
    int across = 0, along = 0;  // the field's size across the wrap line and along it
    int width = 0, overlap = 0;
    int first = 0;  // the strip's first line, modulo across

    Strip(bool x, int w, int h, int texels)
        : acrossX(x), across(x ? w : h), along(x ? h : w), width(texels), overlap(std::max(2, texels / 4)),
          first(wrapped(across - texels / 2, across)) {}
    int line(int u) const { return wrapped(first + u, across); }  // u may lie beyond the strip
    double& at(Field& f, int a, int l) const { return acrossX ? f.at(a, l) : f.at(l, a); }
    double at(const Field& f, int a, int l) const { return acrossX ? f.at(a, l) : f.at(l, a); }
    // Whether a copy shifted by du across takes its lines from one piece of the field, not across its wrap,
    // with a line to spare on each side: the healing uses the copy's steps to the texels beside the strip.
    bool onePiece(int du) const {
        const int start = wrapped(first + du, across);
        return start >= 1 && start + width + 1 <= across;
    }
};

// Shifts whose copies are at least half a strip apart count as different sources.
bool near(int a, int b, int n, int distance) {
    const int d = wrapped(a - b, n);
    return std::min(d, n - d) < distance;
}

// The match-th best shift (du, dv) of errors (indexed by map shift (dx, dy)) among those `allowed`, each
// next one at least half a strip from those before it; the last found when there are fewer.
std::pair<int, int> chooseShift(const Field& errors, const Strip& s, bool anyAlong, int match) {
    std::vector<std::pair<int, int>> chosen;
    for (int round = 0; round <= match; ++round) {
        double best = std::numeric_limits<double>::infinity();
        std::pair<int, int> shift{-1, -1};
        for (int dv = 0; dv < (anyAlong ? s.along : 1); ++dv)
            for (int du = 0; du < s.across; ++du) {
                if (!s.onePiece(du)) continue;
                const bool taken = std::any_of(chosen.begin(), chosen.end(), [&](const std::pair<int, int>& c) {
                    return near(du, c.first, s.across, s.width / 2) && near(dv, c.second, s.along, s.width / 2);
                });
                const double e = s.at(errors, du, dv);
                if (!taken && e < best) best = e, shift = {du, dv};
            }
        if (shift.first < 0) break;
        chosen.push_back(shift);
    }
    return chosen.back();
}

// Adds to f the zero-mean periodic field whose five-point Laplacian is rhs, given on the strip's lines and
// one line beside each (as quiltStrip makes it) and 0 elsewhere: its spectrum divided by the Laplacian's
// symbol, in half spectra of floats (a quarter of the memory of a complex one in doubles; the correction
// is a small smooth field, which floats hold to far below a 16-bit step), each row added as it comes.
void addPoissonSolution(Field& f, const Strip& s, const std::vector<double>& rhs, int threads) {
    const int w = f.w, h = f.h, columns = w / 2 + 1;
    std::vector<int> stripLine(size_t(s.across), -2);  // the strip's u of each line across, -2 for none
    for (int u = -1; u <= s.width; ++u) stripLine[size_t(s.line(u))] = u;
    std::vector<std::complex<float>> half = detail::forwardRealDftToHalf(w, h, threads, [&](int y, float* row) {
        std::fill(row, row + w, 0.0f);
        if (s.acrossX) {
            for (int u = -1; u <= s.width; ++u) row[s.line(u)] = float(rhs[size_t(u + 1) * s.along + y]);
        } else if (const int u = stripLine[size_t(y)]; u >= -1) {
            for (int x = 0; x < w; ++x) row[x] = float(rhs[size_t(u + 1) * s.along + x]);
        }
    });
    const double scale = 1.0 / (double(w) * h);  // the inverse is unscaled
    // The symbol's two terms, once per column and per row (the same values as computed in place).
    std::vector<double> cosX(static_cast<size_t>(columns)), cosY(static_cast<size_t>(h));
    for (int q = 0; q < columns; ++q) cosX[size_t(q)] = 2 * std::cos(2 * std::numbers::pi * q / w);
    for (int r = 0; r < h; ++r) cosY[size_t(r)] = 2 * std::cos(2 * std::numbers::pi * r / h);
    parallelFor(h, threads, [&](int begin, int end) {
        for (int r = begin; r < end; ++r)
            for (int q = 0; q < columns; ++q) {
                const double symbol = cosX[size_t(q)] + cosY[size_t(r)] - 4;
                std::complex<float>& z = half[size_t(r) * columns + q];
                z = (q == 0 && r == 0) ? 0.0f : z * float(scale / symbol);
            }
    });
    detail::inverseRealDftOfHalf(half.data(), w, h, threads, [&](int y, const float* row) {
        for (int x = 0; x < w; ++x) f.at(x, y) += row[x];
    });
}

// Replaces the strip of f with the copy shifted by (du, dv), cut in along the least visible paths of the
// overlaps and healed (see tile/quilt.hpp, steps 3 and 4).
void quiltStrip(Field& f, const Strip& s, int du, int dv, int threads) {
    const int width = s.width, along = s.along, overlap = s.overlap;
    auto mapValue = [&](int u, int v) { return s.at(f, s.line(u), wrapped(v, along)); };
    auto copyValue = [&](int u, int v) { return s.at(f, wrapped(s.line(u) + du, s.across), wrapped(v + dv, along)); };
    // 3. The cuts: the first copied place on the left overlap, the last on the right (counted from the
    //    edge). The healing takes out an offset between map and copy, so what shows is where their
    //    difference changes: its squared gradient, plus its square over the overlap's width squared (an
    //    offset the healing must spread counts like a slope across the overlap).
    auto difference = [&](int u, int v) { return mapValue(u, v) - copyValue(u, v); };
    auto cost = [&](int u, int v) {
        const double d = difference(u, v), du2 = 0.5 * (difference(u + 1, v) - difference(u - 1, v)),
                     dv2 = 0.5 * (difference(u, v + 1) - difference(u, v - 1));
        return du2 * du2 + dv2 * dv2 + d * d / (double(overlap) * overlap);
    };
    std::vector<double> leftCost(size_t(overlap) * along), rightCost(leftCost.size());
    parallelFor(along, threads, [&](int begin, int end) {
        for (int v = begin; v < end; ++v)
            for (int k = 0; k < overlap; ++k) {
                leftCost[size_t(v) * overlap + k] = cost(k, v);
                rightCost[size_t(v) * overlap + k] = cost(width - 1 - k, v);
            }
    });
    const std::vector<int> left = detail::minimalCut(leftCost, overlap, along);
    const std::vector<int> right = detail::minimalCut(rightCost, overlap, along);
    // The copy's share of the guidance: 0 beyond the cut paths, 1 between them, ramping over half an
    //    overlap centred on each path (gradients blended there, so no crease runs along a path), 0 beyond
    //    the strip.
    const double ramp = std::max(1, overlap / 2);
    auto share = [&](int u, int v) {
        if (u < 0 || u >= width) return 0.0;
        const int line = wrapped(v, along);
        const double fromLeft = u - left[line] + 0.5, fromRight = width - 1 - right[line] - u + 0.5;
        return std::clamp(0.5 + std::min(fromLeft, fromRight) / ramp, 0.0, 1.0);
    };
    // 4. The healing: the result f + c whose steps are closest (least squares, over the whole torus) to
    //    the guidance: the map's steps blended with the copy's by their share (the mean share of an edge's
    //    two texels). For each texel p, the sum over its neighbours q of c(p) - c(q) is the sum of
    //    (guidance - f's step), nonzero only on the strip and beside it: a periodic Poisson equation, whose
    //    solution beyond the strip is harmonic (no line where the strip ends).
    // The map and the copy on the strip's lines and the one beside each (u = -1 .. width) and one more
    // along each end (v = -1 .. along), as [u + 1][v + 1], gathered once: the sums below read each value
    // up to eight times, and through the field's wrap and orientation each read cost a division and, for
    // the left/right strip, a cache miss.
    const size_t stride = size_t(along) + 2;
    std::vector<double> mapLines(size_t(width + 2) * stride), copyLines(mapLines.size());
    auto gather = [&](int v) {
        for (int u = -1; u <= width; ++u) {
            const size_t i = size_t(u + 1) * stride + size_t(v + 1);
            mapLines[i] = mapValue(u, v);
            copyLines[i] = copyValue(u, v);
        }
    };
    parallelFor(along, threads, [&](int begin, int end) {
        for (int v = begin; v < end; ++v) gather(v);
    });
    gather(-1);
    gather(along);
    // The shares of the lines u = -1 .. width along one line v (0 beyond the strip).
    auto sharesOf = [&](int v, double* out) {
        for (int u = -1; u <= width; ++u) out[u + 1] = share(u, v);
    };
    // The right-hand side on the strip's lines and the one beside each (u = -1 .. width), as [u + 1][v]:
    // nothing elsewhere, so no whole field of it is kept. Each texel's excess over its four neighbours, in
    // the order (u - 1, v), (u + 1, v), (u, v - 1), (u, v + 1); per line v, so any split gives the same.
    std::vector<double> rhs(size_t(width + 2) * along, 0.0);
    auto rhsAt = [&](int u, int v) -> double& { return rhs[size_t(u + 1) * along + v]; };
    parallelFor(along, threads, [&](int begin, int end) {
        std::vector<double> before(size_t(width) + 2), here(before.size()), after(before.size());
        for (int v = begin; v < end; ++v) {
            sharesOf(v - 1, before.data());
            sharesOf(v, here.data());
            sharesOf(v + 1, after.data());
            auto excess = [&](int u, double shareQ, int qu, int qv) {
                const double a = 0.5 * (here[size_t(u + 1)] + shareQ);
                if (a == 0) return 0.0;
                const size_t p = size_t(u + 1) * stride + size_t(v + 1), q = size_t(qu + 1) * stride + size_t(qv + 1);
                return a * (copyLines[p] - copyLines[q] - (mapLines[p] - mapLines[q]));
            };
            for (int u = 0; u < width; ++u) {
                double sum = 0;
                sum += excess(u, here[size_t(u)], u - 1, v);
                sum += excess(u, here[size_t(u + 2)], u + 1, v);
                sum += excess(u, before[size_t(u + 1)], u, v - 1);
                sum += excess(u, after[size_t(u + 1)], u, v + 1);
                rhsAt(u, v) = -sum;  // the Laplacian of c is minus that sum
            }
        }
    });
    auto excess = [&](int u, int v, int qu, int qv) {
        const double a = 0.5 * (share(u, v) + share(qu, qv));
        if (a == 0) return 0.0;
        return a * (copyValue(u, v) - copyValue(qu, qv) - (mapValue(u, v) - mapValue(qu, qv)));
    };
    for (int v = 0; v < along; ++v) {  // the texels beside the strip take the other end of its edges
        rhsAt(-1, v) += excess(0, v, -1, v);
        rhsAt(width, v) += excess(width - 1, v, width, v);
    }
    addPoissonSolution(f, s, rhs, threads);
}

// The map's texels on the strip's overlaps (the rest 0), and the mask of them.
std::pair<Field, Field> overlapsOf(const Field& f, const Strip& s) {
    Field target(f.w, f.h), mask(f.w, f.h);
    for (int u = 0; u < s.width; ++u) {
        if (u >= s.overlap && u < s.width - s.overlap) continue;
        for (int v = 0; v < s.along; ++v) {
            s.at(target, s.line(u), v) = s.at(f, s.line(u), v);
            s.at(mask, s.line(u), v) = 1.0;
        }
    }
    return {std::move(target), std::move(mask)};
}

// Maps from this many texels a side are searched coarse to fine: the errors of every shift at a quarter of
// the size (a sixteenth of the transforms' time and memory), then every shift within a coarse texel of the
// one chosen there at full size. Below, the full-size search is cheap already.
constexpr int kCoarseSearchSide = 1024;
constexpr int kCoarseStep = 4;

// f averaged over step x step blocks (sides that step divides).
Field coarseOf(const Field& f, int step, int threads) {
    Field out(f.w / step, f.h / step);
    parallelFor(out.h, threads, [&](int begin, int end) {
        for (int y = begin; y < end; ++y)
            for (int x = 0; x < out.w; ++x) {
                double sum = 0;
                for (int j = 0; j < step; ++j)
                    for (int i = 0; i < step; ++i) sum += f.at(x * step + i, y * step + j);
                out.at(x, y) = sum / (step * step);
            }
    });
    return out;
}

// The sum of squared differences between the strip's overlaps and the copy shifted by (du, dv), directly:
// over the overlaps' lines, each line's texels in order (a row of f where the strip is across y).
double overlapError(const Field& f, const Strip& s, int du, int dv, int threads) {
    std::vector<int> lines;  // the overlaps' lines
    for (int u = 0; u < s.width; ++u)
        if (u < s.overlap || u >= s.width - s.overlap) lines.push_back(u);
    std::vector<double> perLine(lines.size(), 0.0);  // summed in order after: the same on any thread count
    if (s.acrossX) {
        // The lines are columns: each thread takes a run of them and walks down the rows, so each row's
        // texels of its lines are read together (a column at a time was a cache miss a texel). Each line's
        // sum still adds its texels in order of v.
        parallelFor(int(lines.size()), threads, [&](int begin, int end) {
            for (int v = 0; v < s.along; ++v) {
                const double* row = &f.v[size_t(v) * f.w];
                const double* copyRow = &f.v[size_t(wrapped(v + dv, s.along)) * f.w];
                for (int k = begin; k < end; ++k) {
                    const int line = s.line(lines[size_t(k)]);
                    const double d = row[line] - copyRow[wrapped(line + du, s.across)];
                    perLine[size_t(k)] += d * d;
                }
            }
        });
        double total = 0;
        for (double e : perLine) total += e;
        return total;
    }
    parallelFor(int(lines.size()), threads, [&](int begin, int end) {
        std::vector<double> copy(size_t(s.along));
        for (int k = begin; k < end; ++k) {
            const int line = s.line(lines[size_t(k)]), from = wrapped(line + du, s.across);
            for (int v = 0; v < s.along; ++v) copy[size_t(v)] = s.at(f, from, wrapped(v + dv, s.along));
            double sum = 0;
            for (int v = 0; v < s.along; ++v) {
                const double d = s.at(f, line, v) - copy[size_t(v)];
                sum += d * d;
            }
            perLine[size_t(k)] = sum;
        }
    });
    double total = 0;
    for (double e : perLine) total += e;
    return total;
}

// The shift (du, dv) of the strip's copy: the match-th best by the errors of every shift, on a large map
// found on its coarse version and refined at full size: across within a coarse texel of it, then along.
std::pair<int, int> findShift(const Field& f, const Strip& s, bool anyAlong, int match, int threads) {
    if (std::min(f.w, f.h) < kCoarseSearchSide || f.w % kCoarseStep != 0 || f.h % kCoarseStep != 0) {
        auto [target, mask] = overlapsOf(f, s);
        return chooseShift(detail::maskedSquaredErrors(std::move(target), std::move(mask), f, threads), s, anyAlong, match);
    }
    std::pair<int, int> coarse;
    {
        const Field small = coarseOf(f, kCoarseStep, threads);
        const Strip c(s.acrossX, small.w, small.h, std::max(8, s.width / kCoarseStep));
        auto [target, mask] = overlapsOf(small, c);
        coarse = chooseShift(detail::maskedSquaredErrors(std::move(target), std::move(mask), small, threads), c, anyAlong, match);
    }
    std::pair<int, int> best{wrapped(coarse.first * kCoarseStep, s.across), wrapped(coarse.second * kCoarseStep, s.along)};
    double bestError = s.onePiece(best.first) ? overlapError(f, s, best.first, best.second, threads)
                                              : std::numeric_limits<double>::infinity();
    auto tryShift = [&](int du, int dv) {
        if (!s.onePiece(du) || (du == best.first && dv == best.second)) return;
        const double e = overlapError(f, s, du, dv, threads);
        if (e < bestError) bestError = e, best = {du, dv};
    };
    const int u0 = coarse.first * kCoarseStep, v0 = best.second;
    for (int du = u0 - kCoarseStep; du <= u0 + kCoarseStep; ++du) tryShift(wrapped(du, s.across), v0);
    if (anyAlong) {
        const int u1 = best.first;
        for (int dv = v0 - kCoarseStep; dv <= v0 + kCoarseStep; ++dv) tryShift(u1, wrapped(dv, s.along));
    }
    return best;
}

// Finds the source of the strip and quilts it in; returns the shift as (dx, dy). anyAlong: the field wraps
// along the strip, so a copy may come from any place along it.
std::pair<int, int> quiltWrapLine(Field& f, const Strip& s, bool anyAlong, int match, int threads) {
    const auto [du, dv] = findShift(f, s, anyAlong, match, threads);
    quiltStrip(f, s, du, dv, threads);
    return s.acrossX ? std::pair{du, dv} : std::pair{dv, du};
}

int stripTexels(double fraction, int size) {
    const long texels = fraction > 0 ? std::lround(fraction * size) : std::lround(size / 8.0);
    return std::clamp(int(texels), 8, size / 2);
}

}  // namespace

namespace {

QuiltResult quiltAtOwnSize(const Image& map, const QuiltOptions& options) {
    const int w = map.width, h = map.height;
    if (std::min(w, h) < 16) return {periodicComponent(map, PeriodicContinuity::Heights)};  // no room for two overlaps
    QuiltResult result;
    Field f(w, h);
    f.v.assign(map.pixels.begin(), map.pixels.end());
    // The large scales that do not wrap (harmonic inside the tile), as the re-synthesis takes them off.
    const std::vector<float> mismatch = detail::largeScaleField(map.pixels, w, h, std::min(w, h) / 16.0, options.threads);
    for (size_t i = 0; i < f.v.size(); ++i) f.v[i] -= mismatch[i];
    result.bandX = stripTexels(options.band, w);
    result.bandY = stripTexels(options.band, h);
    // The left/right strip's copy comes from the same rows (the map does not wrap top to bottom yet, and
    // a copy from other rows would carry the map's top/bottom seam to a row the second strip leaves).
    const auto [xdx, xdy] = quiltWrapLine(f, Strip(true, w, h, result.bandX), false, options.match, options.threads);
    const auto [ydx, ydy] = quiltWrapLine(f, Strip(false, w, h, result.bandY), true, options.match, options.threads);
    result.sourceX[0] = xdx;
    result.sourceX[1] = xdy;
    result.sourceY[0] = ydx;
    result.sourceY[1] = ydy;
    result.map = Image(w, h, 1);
    std::transform(f.v.begin(), f.v.end(), result.map.pixels.begin(), [](double x) { return static_cast<float>(x); });
    detail::easeIntoRange(result.map, sampleRange(map, options.threads), options.threads);
    return result;
}

}  // namespace

namespace {

// isSource: map is an enlarged map's source, taken for an enlargement in turn by a source's rules, so a
// composed enlargement (8x, then 4x) is quilted at its first source's size.
QuiltResult quiltAtSourceSize(const Image& map, const QuiltOptions& options, bool isSource) {
    const detail::Enlargement e = detail::findEnlargement(map, options.quantum, options.threads, isSource);
    if (e.factor == 1) return quiltAtOwnSize(map, options);
    const SampleRange range = sampleRange(map, options.threads);
    QuiltOptions atSource = options;
    const Image source = detail::roundedSource(map, e, atSource.quantum, range, options.threads);
    QuiltResult result = quiltAtSourceSize(source, atSource, true);
    detail::putOnLevels(result.map, atSource.quantum, range);
    result.map = detail::enlargedTile(map, source, result.map, e, (result.bandX + 1) / 2 + 1, (result.bandY + 1) / 2 + 1, range,
                                      options.threads);
    // The texels changed: those enlargedTile takes from the source's tile.
    result.enlargement *= e.factor;
    result.bandX = std::min(map.width, 2 * ((result.bandX + 1) / 2 + 1 + detail::kEnlargedTileReach) * e.factor);
    result.bandY = std::min(map.height, 2 * ((result.bandY + 1) / 2 + 1 + detail::kEnlargedTileReach) * e.factor);
    for (int* offset : {&result.sourceX[0], &result.sourceX[1], &result.sourceY[0], &result.sourceY[1]}) *offset *= e.factor;
    return result;
}

}  // namespace

QuiltResult quiltTile(const Image& map, const QuiltOptions& options) {
    return options.atSourceSize ? quiltAtSourceSize(map, options, false) : quiltAtOwnSize(map, options);
}

}  // namespace heightpack
