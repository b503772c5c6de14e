// planEncoding: the texel format and, for uint16, the normalisation, from one pass over a chain's values.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "heightpack/core/parallel.hpp"
#include "texel_encode.hpp"

namespace heightpack::detail {

namespace {

// A float's bits as a signed integer that orders like the float (-0 just below +0, NaNs beyond the
// infinities). Integer minima and maxima vectorise; float ones do not, since they must keep the first of
// two equal zeros.
std::int32_t orderKey(float v) {
    std::int32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return bits ^ ((bits >> 31) & 0x7fffffff);
}
float fromOrderKey(std::int32_t key) {
    const std::int32_t bits = key ^ ((key >> 31) & 0x7fffffff);
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}
constexpr std::int32_t kPlusZeroKey = 0, kMinusZeroKey = -1;

// The range of a run of values and its first value that cannot be stored, as a loop with std::min and
// std::max over doubles, stopping at that value, finds them.
struct Scan {
    double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
    size_t bad = SIZE_MAX;  // index into the run
};

// The largest magnitude (exclusive) a pixel type holds: halfCanHold's bound, or any finite value.
float limitOf(PixelType type) { return type == PixelType::Half ? 65520.0f : std::numeric_limits<float>::infinity(); }

Scan scanValues(const float* v, size_t n, float limit) {
    std::int32_t lo = std::numeric_limits<std::int32_t>::max(), hi = std::numeric_limits<std::int32_t>::min();
    for (size_t i = 0; i < n; ++i) {
        const std::int32_t key = orderKey(v[i]);
        lo = std::min(lo, key);
        hi = std::max(hi, key);
    }
    Scan scan;
    if (n == 0) return scan;
    if (lo <= orderKey(-limit) || hi >= orderKey(limit)) {
        // Rare: a value beyond the type (or not finite). The loop replaced, value by value, finds the first.
        for (size_t i = 0; i < n; ++i) {
            if (!std::isfinite(v[i]) || !(std::fabs(v[i]) < limit)) {
                scan.bad = i;
                break;
            }
            scan.lo = std::min<double>(scan.lo, v[i]);
            scan.hi = std::max<double>(scan.hi, v[i]);
        }
        return scan;
    }
    // Equal floats are equal bits, except +0 and -0: std::min and std::max kept the first zero met.
    auto firstZero = [&] { return *std::find(v, v + n, 0.0f); };
    const float low = fromOrderKey(lo), high = fromOrderKey(hi);
    scan.lo = low == 0.0f ? firstZero() : low;
    scan.hi = high == 0.0f ? firstZero() : high;
    return scan;
}

// The range of content's values in file order (every layer, then every level, then row by row), as
// doubles that keep the first of two equal zeros met; or the error for the first value the type cannot
// hold. Each level's rows are filled and scanned on all threads, each thread its own rows a band at a
// time; the rows' results are then taken in order, so the first bad value is the same on any thread count.
Status scanContent(const std::string& path, const ChainToWrite& content, const EncodePlan& plan,
                   const TextureWriteOptions& options, double& lo, double& hi) {
    const float limit = limitOf(options.storage.pixelType);
    for (int pass = 0; pass < content.layerCount() * plan.levels; ++pass) {
        const int layer = pass / plan.levels, level = pass % plan.levels;
        const int w = mipLevelSide(content.width, level), h = mipLevelSide(content.height, level);
        const size_t rowValues = size_t(w) * plan.sourceChannels;
        std::vector<Scan> scans(static_cast<size_t>(h));
        std::vector<std::vector<float>> badRows(static_cast<size_t>(h));  // a row with a bad value, kept to name it
        parallelFor(h, options.threads, [&](int begin, int end) {
            std::vector<float> band;
            for (int y0 = begin; y0 < end; y0 += kBandRows) {
                const int rows = std::min(kBandRows, end - y0);
                band.resize(size_t(rows) * rowValues);
                fillLayerRows(content, layer, level, y0, rows, band.data());
                for (int r = 0; r < rows; ++r) {
                    const float* row = band.data() + size_t(r) * rowValues;
                    Scan& scan = scans[size_t(y0 + r)] = scanValues(row, rowValues, limit);
                    if (scan.bad != SIZE_MAX) badRows[size_t(y0 + r)].assign(row, row + rowValues);
                }
            }
        });
        for (size_t y = 0; y < scans.size(); ++y) {
            const Scan& scan = scans[y];
            if (scan.bad != SIZE_MAX) {
                const float v = badRows[y][scan.bad];
                if (!std::isfinite(v)) return nonFiniteLevel(path, level);
                const std::string where =
                    content.layerNames.empty() ? "" : "layer " + content.layerNames[size_t(layer)] + ", ";
                return badInput(path,
                                where + "level " + std::to_string(level) + " holds " + floatText(v) +
                                    ", beyond the largest half float (65504); nothing was written",
                                "store float or uint16 pixels, or scale the heights down");
            }
            lo = std::min(lo, scan.lo);
            hi = std::max(hi, scan.hi);
        }
    }
    return Done{};
}

// What scanning chains' values finds: the extreme keys, whether both zeros occur, whether any value is
// one the type cannot hold.
struct KeyRange {
    std::int32_t lo = std::numeric_limits<std::int32_t>::max(), hi = std::numeric_limits<std::int32_t>::min();
    bool plusZero = false, minusZero = false;
};

KeyRange keyRange(const float* v, size_t n) {
    KeyRange r;
    std::int32_t plus = 0, minus = 0;
    for (size_t i = 0; i < n; ++i) {
        const std::int32_t key = orderKey(v[i]);
        r.lo = std::min(r.lo, key);
        r.hi = std::max(r.hi, key);
        plus |= std::int32_t(key == kPlusZeroKey);
        minus |= std::int32_t(key == kMinusZeroKey);
    }
    r.plusZero = plus != 0;
    r.minusZero = minus != 0;
    return r;
}

// The range of the values of chains' first `levels` levels, when it is certainly the range content's
// scan in file order finds: false when a value cannot be stored (the content scan then names the first
// in file order) or when a zero is an extreme and both signed zeros occur (which one comes first is a
// matter of order). Rows on all threads, each level once.
bool rangeOfChains(const ChainValues& chains, int levels, float limit, int threads, double& lo, double& hi) {
    KeyRange all;
    for (const std::vector<Image>* chain : chains) {
        if (!chain || int(chain->size()) < levels) return false;
        for (int level = 0; level < levels; ++level) {
            const Image& image = (*chain)[size_t(level)];
            std::vector<KeyRange> rows(static_cast<size_t>(image.height));
            const size_t rowValues = size_t(image.width) * image.channels;
            parallelFor(image.height, threads, [&](int begin, int end) {
                for (int y = begin; y < end; ++y) rows[size_t(y)] = keyRange(image.row(y), rowValues);
            });
            for (const KeyRange& r : rows) {
                all.lo = std::min(all.lo, r.lo);
                all.hi = std::max(all.hi, r.hi);
                all.plusZero |= r.plusZero;
                all.minusZero |= r.minusZero;
            }
        }
    }
    if (all.lo > all.hi) return false;  // no values
    if (all.lo <= orderKey(-limit) || all.hi >= orderKey(limit)) return false;
    const float low = fromOrderKey(all.lo), high = fromOrderKey(all.hi);
    if ((low == 0.0f || high == 0.0f) && all.plusZero && all.minusZero) return false;
    lo = low;
    hi = high;
    return true;
}

// The uint16 normalisation of values in [lo, hi] (see TextureWriteOptions::gridOrigin).
Normalisation normalisationOf(double lo, double hi, int sourceChannels, const TextureWriteOptions& options) {
    if (sourceChannels == 3) hi = std::max(hi, 1.0), lo = std::min(lo, 1.0);  // the alpha of 1 we add
    Normalisation n{static_cast<float>(lo), static_cast<float>(hi - lo)};
    if (options.gridSpan > 0.0f) {
        // A painted map's values lie on origin + k * step. Start on that grid, below the chain's
        // minimum, and split each step into the most whole sub-steps that still reach the maximum:
        // level 0 then reads back exactly, and at least half of the 65536 codes are used.
        const double step = double(options.gridSpan) / 65535.0;
        const double base = options.gridOrigin + std::floor((lo - options.gridOrigin) / step + 1e-3) * step;
        const double steps = std::max((hi - base) / step, 1.0);
        const double split = std::floor(65535.0 / steps + 1e-9);
        if (split >= 1.0) n = {static_cast<float>(base), static_cast<float>(double(options.gridSpan) / split)};
    }
    if (!(n.scale > 0.0f)) n.scale = 1.0f;  // a flat chain: every texel 0 decodes to offset
    return n;
}

}  // namespace

EncodePlan encodePlanOf(const ChainToWrite& content, const TextureWriteOptions& options, const WritePlan& decided) {
    EncodePlan plan;
    plan.sourceChannels = static_cast<int>(content.channelNames.size());
    plan.format = texelFormatInfo(texelFormatFor(plan.sourceChannels, decided.pixelType));
    plan.levels = mipLevelCount(content.width, content.height);
    if (options.levels > 0) plan.levels = std::min(plan.levels, options.levels);
    plan.normalisation = decided.normalisation;
    plan.blocks = decided.blocks;
    return plan;
}

Result<EncodePlan> planEncoding(const std::string& path, const ChainToWrite& content,
                                const TextureWriteOptions& options, const ChainValues& sameValues) {
    EncodePlan plan = encodePlanOf(content, options, WritePlan{options.storage.pixelType, std::nullopt, nullptr});
    if (options.storage.pixelType == PixelType::Float) return plan;

    // One pass over the chain, every layer of an array: the range (uint16: one normalisation for the
    // whole texture, as a DDS header has room for one) and what a half cannot hold.
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    const float limit = limitOf(options.storage.pixelType);
    if (sameValues.empty() || !rangeOfChains(sameValues, plan.levels, limit, options.threads, lo, hi)) {
        lo = std::numeric_limits<double>::infinity(), hi = -lo;
        if (Status s = scanContent(path, content, plan, options, lo, hi); !s) return s.error();
    }
    if (plan.format.kind == ComponentKind::Unorm16) plan.normalisation = normalisationOf(lo, hi, plan.sourceChannels, options);
    if (plan.format.isBlock()) {
        // Block endpoints have 8 bits: the 16-bit grid buys nothing, the range alone spans the codes.
        TextureWriteOptions rangeOnly;
        plan.normalisation = normalisationOf(lo, hi, plan.sourceChannels, rangeOnly);
    }
    return plan;
}

}  // namespace heightpack::detail
