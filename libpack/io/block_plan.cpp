// Planning a block-compressed chain: the blocks are encoded once, when the plan is made, so the error
// they decode with is known before anything is written and the writer stores exactly what was measured.
#include <algorithm>
#include <cstdint>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/core/normal_angle.hpp"
#include "heightpack/core/parallel.hpp"
#include "texel_encode.hpp"

// Vectors of four doubles pass between NormalRow's inlined functions only (see there).
#pragma GCC diagnostic ignored "-Wpsabi"

namespace heightpack::detail {

namespace {

// Two or four texels at a time (GCC's vector extension: SSE2, or AVX2 where the processor has it, plain
// code elsewhere): each lane takes the same operations in the same order as one texel would (square roots
// are exact, and no multiply-add is fused), so the figures are those of texel-by-texel code on any of them.
using Pair = double __attribute__((vector_size(16)));
using Quad = double __attribute__((vector_size(32)));

struct LevelError {
    double worst = 0.0, squares = 0.0, count = 0.0;
    double worstDegrees = 0.0, squareDegrees = 0.0;
};

// The measure of one row of normals, W texels (D's lanes) at a time. Everything is inlined into the two
// entry points below, so no vector crosses a call.
template <class D>
struct NormalRow {
    static constexpr int W = int(sizeof(D) / sizeof(double));

    [[gnu::always_inline]] static D sqrtOf(const D& a) {
        D r;
        for (int i = 0; i < W; ++i) r[i] = std::sqrt(a[i]);
        return r;
    }

    // The unit normals whose x and y are given, z rebuilt as the shader does (x, y past the unit circle: on it).
    [[gnu::always_inline]] static void normalsOf(const D& x, const D& y, D n[3]) {
        const D rr = x * x + y * y, zero{};
        const auto inside = rr <= 1.0;
        n[0] = x, n[1] = y, n[2] = sqrtOf(inside ? 1.0 - rr : zero);
        bool all = true;
        for (int i = 0; i < W; ++i) all = all && inside[i];
        if (all) return;  // nearly always: no square root and division more
        const D r = sqrtOf(rr);
        n[0] = inside ? x : x / r, n[1] = inside ? y : y / r;
    }

    // The angles between the normals of (ax, ay) and of (bx, by), 2 asin(|a - b| / 2): from the chord, which
    // (unlike the dot product's acos) keeps its precision at small angles; the series for those is what
    // makes a level's measurement cheap next to its encoding (|a - b| / 2 under 0.1: the next term is below
    // 1e-11 radians).
    [[gnu::always_inline]] static D anglesBetween(const D& ax, const D& ay, const D& bx, const D& by) {
        D a[3], b[3];
        normalsOf(ax, ay, a);
        normalsOf(bx, by, b);
        const D dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
        const D h = 0.5 * sqrtOf(dx * dx + dy * dy + dz * dz), h2 = h * h;
        D angle = 2.0 * h * (1.0 + h2 * (1.0 / 6.0 + h2 * (3.0 / 40.0 + h2 * (15.0 / 336.0 + h2 * (105.0 / 3456.0)))));
        for (int i = 0; i < W; ++i)
            if (h[i] >= 0.1) angle[i] = 2.0 * std::asin(std::min(h[i], 1.0));
        return angle;
    }

    // The error of `decoded` (offset + scale * unorm) against `given`, one row of `width` xy normals, added
    // to e texel by texel: each component's error, then the normal's angle.
    [[gnu::always_inline]] static void measure(const float* given, const float* decoded, int width, const Normalisation& n, LevelError& e) {
        const double offset = n.offset, scale = n.scale;
        double worst = e.worst, squares = e.squares, worstDegrees = e.worstDegrees, squareDegrees = e.squareDegrees;
        for (int x = 0; x < width; x += W) {
            D gx, gy, bx, by;
            for (int i = 0; i < W; ++i) {
                const int at = std::min(x + i, width - 1);  // a row's last texels in the spare lanes, counted once
                gx[i] = given[2 * at], gy[i] = given[2 * at + 1];
                bx[i] = offset + scale * double(decoded[2 * at]), by[i] = offset + scale * double(decoded[2 * at + 1]);
            }
            const D degrees = anglesBetween(gx, gy, bx, by) * kDegreesPerRadian;
            for (int i = 0; i < std::min(W, width - x); ++i) {
                for (const double d : {std::fabs(bx[i] - gx[i]), std::fabs(by[i] - gy[i])}) {
                    worst = std::max(worst, d);
                    squares += d * d;
                }
                worstDegrees = std::max(worstDegrees, degrees[i]);
                squareDegrees += degrees[i] * degrees[i];
            }
        }
        e.worst = worst, e.squares = squares, e.worstDegrees = worstDegrees, e.squareDegrees = squareDegrees;
        e.count += 2.0 * width;  // a whole number: the same as adding 1 a component
    }
};

[[gnu::flatten]] void measureNormalRowPortable(const float* given, const float* decoded, int width, const Normalisation& n, LevelError& e) {
    NormalRow<Pair>::measure(given, decoded, width, n, e);
}

#if defined(__x86_64__)
[[gnu::flatten, gnu::target("avx2")]] void measureNormalRowAvx2(const float* given, const float* decoded, int width, const Normalisation& n,
                                                              LevelError& e) {
    NormalRow<Quad>::measure(given, decoded, width, n, e);
}
#endif

// The error of `decoded` (offset + scale * unorm) against `given`, one row of `width` texels, added to e
// texel by texel: two channels are a normal's x and y, whose angle is measured too.
void measureRow(const float* given, const float* decoded, int width, int channels, const Normalisation& n, LevelError& e) {
    if (channels == 1) {
        const double offset = n.offset, scale = n.scale;
        for (int x = 0; x < width; ++x) {
            const double d = std::fabs((offset + scale * double(decoded[x])) - double(given[x]));
            e.worst = std::max(e.worst, d);
            e.squares += d * d;
            e.count += 1.0;
        }
        return;
    }
#if defined(__x86_64__)
    static const bool avx2 = __builtin_cpu_supports("avx2");
    if (avx2) return measureNormalRowAvx2(given, decoded, width, n, e);
#endif
    measureNormalRowPortable(given, decoded, width, n, e);
}

// The error the level's blocks decode with against its values, a row of blocks at a time on all threads:
// the values refilled and the blocks decoded a band at a time (no second and third copy of the level),
// the rows' sums added in row order so they are the same on any thread count. ASTC is decoded whole first
// (astcenc decodes an image, not a block).
LevelError measureLevel(const ChainToWrite& content, int layer, int level, int w, int h, const std::vector<std::uint8_t>& blocks,
                        BlockFormat format, int channels, const Normalisation& n, int threads) {
    std::vector<LevelError> rows(static_cast<size_t>(h));
    const int side = blockSide(format), down = (h + side - 1) / side, across = (w + side - 1) / side;
    const std::optional<Image> whole = isAstc(format) ? std::optional(decodeBlocks(blocks.data(), w, h, format, channels))
                                                      : std::nullopt;
    parallelFor(down, threads, [&](int begin, int end) {
        std::vector<float> given(size_t(side) * size_t(w) * size_t(channels)), decoded(given.size());
        for (int by = begin; by < end; ++by) {
            const int y0 = by * side, bandRows = std::min(side, h - y0);
            fillLayerRows(content, layer, level, y0, bandRows, given.data());
            const float* back = decoded.data();
            if (whole) {
                back = whole->row(y0);
            } else {
                float v[16];
                for (int bx = 0; bx < across; ++bx)
                    for (int c = 0; c < channels; ++c) {
                        decodeBc4Block(blocks.data() + (size_t(by) * size_t(across) + size_t(bx)) * size_t(blockBytes(format)) + size_t(c) * 8, v);
                        for (int i = 0; i < 16; ++i) {
                            const int x = bx * 4 + i % 4, y = i / 4;
                            if (x < w && y < bandRows) decoded[(size_t(y) * size_t(w) + size_t(x)) * size_t(channels) + size_t(c)] = v[i];
                        }
                    }
            }
            const size_t rowValues = size_t(w) * size_t(channels);
            for (int r = 0; r < bandRows; ++r)
                measureRow(given.data() + size_t(r) * rowValues, back + size_t(r) * rowValues, w, channels, n, rows[size_t(y0 + r)]);
        }
    });
    LevelError total;
    for (const LevelError& r : rows) {
        total.worst = std::max(total.worst, r.worst);
        total.squares += r.squares;
        total.count += r.count;
        total.worstDegrees = std::max(total.worstDegrees, r.worstDegrees);
        total.squareDegrees += r.squareDegrees;
    }
    return total;
}

}  // namespace

Result<BlockLevels> encodeBlockLevels(const std::string& path, const ChainToWrite& content, const EncodePlan& plan,
                                      int threads) {
    const BlockFormat format = blockFormatOf(plan.format);
    const int channels = isAstc(format) ? plan.format.channels : blockChannels(format);
    if (isAstcHdr(format) && plan.sourceChannels != 1)
        return cannotWrite(path, "ASTC HDR holds one channel (plain heights), this texture has " + std::to_string(plan.sourceChannels),
                           "store plain heights in ASTC HDR, or xy normals in LDR ASTC");
    if (isAstc(format) && plan.sourceChannels != channels)
        return cannotWrite(path, "ASTC holds one channel (plain heights) or two (xy normals), this texture has " +
                                     std::to_string(plan.sourceChannels),
                           "store plain heights or xy normals in ASTC, or choose another pixel type");
    if (plan.sourceChannels != channels)
        return cannotWrite(path,
                           std::string(format == BlockFormat::Bc4 ? "BC4" : "BC5") + " holds " +
                               (channels == 1 ? "one channel" : "two channels") + ", this texture has " +
                               std::to_string(plan.sourceChannels),
                           channels == 1 ? "store plain heights in bc4, or choose another pixel type"
                                         : "store xy normals in bc5, or choose another pixel type");
    const Normalisation n = plan.normalisation.value_or(Normalisation{});
    BlockLevels out;
    out.levels = plan.levels;
    std::vector<LevelError> errors(static_cast<size_t>(plan.levels));
    std::unique_ptr<float[]> unorm;  // level 0's size: every level after it is smaller
    for (int layer = 0; layer < content.layerCount(); ++layer)
        for (int level = 0; level < plan.levels; ++level) {
            const int w = mipLevelSide(content.width, level), h = mipLevelSide(content.height, level);
            // The level's values in the blocks' units, converted where they are filled: measureLevel fills
            // them again, a band at a time, rather than keeping a second copy of the level. One buffer for
            // every level (each fills all it uses), not zeroed first: its pages are first written, and
            // mapped, on all threads.
            const size_t rowValues = size_t(w) * size_t(channels);
            if (!unorm) unorm.reset(new float[rowValues * size_t(h)]);
            std::vector<char> finite(static_cast<size_t>(h));
            parallelFor(h, threads, [&](int a, int b) {
                fillLayerRows(content, layer, level, a, b - a, unorm.get() + size_t(a) * rowValues);
                for (int r = a; r < b; ++r) {
                    float* row = unorm.get() + size_t(r) * rowValues;
                    finite[size_t(r)] = allFinite(row, rowValues);
                    for (float* v = row; v < row + rowValues; ++v) *v = float((double(*v) - n.offset) / n.scale);
                }
            });
            if (std::find(finite.begin(), finite.end(), 0) != finite.end()) return nonFiniteLevel(path, level);
            // Two channels are xy normals: chosen together by the angle, in the normal's units (ASTC by
            // astcenc's normal-map mode).
            const std::optional<NormalUnits> normals =
                channels == 2 ? std::optional(NormalUnits{n.offset, n.scale}) : std::nullopt;
            out.images.push_back(encodeBlocks(ImageView(unorm.get(), w, h, channels), format, threads, normals));
            if (out.images.back().size() != blockImageBytes(w, h, format))
                return Error{ErrorKind::Internal, path, "internal error: the ASTC encoder failed", "please report this"};
            const LevelError e = measureLevel(content, layer, level, w, h, out.images.back(), format, channels, n, threads);
            LevelError& sum = errors[size_t(level)];
            sum.worst = std::max(sum.worst, e.worst);
            sum.squares += e.squares;
            sum.count += e.count;
            sum.worstDegrees = std::max(sum.worstDegrees, e.worstDegrees);
            sum.squareDegrees += e.squareDegrees;
        }
    for (const LevelError& e : errors) {
        out.worst.push_back(e.worst);
        out.rms.push_back(std::sqrt(e.squares / std::max(e.count, 1.0)));
        if (channels == 2) {
            out.worstDegrees.push_back(e.worstDegrees);
            out.rmsDegrees.push_back(std::sqrt(e.squareDegrees / std::max(e.count / 2.0, 1.0)));
        }
    }
    return out;
}

}  // namespace heightpack::detail
