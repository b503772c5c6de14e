// Planning a block-compressed chain: the blocks are encoded once, when the plan is made, so the error
// they decode with is known before anything is written and the writer stores exactly what was measured.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "heightpack/core/normal_angle.hpp"
#include "heightpack/core/parallel.hpp"
#include "texel_encode.hpp"

namespace heightpack::detail {

namespace {

struct LevelError {
    double worst = 0.0, squares = 0.0, count = 0.0;
    double worstDegrees = 0.0, squareDegrees = 0.0;
};

// The error decoded (offset + scale * unorm) makes against given, row by row on all threads, summed in
// row order so the sums are the same on any thread count.
LevelError measure(const Image& given, const Image& decoded, const Normalisation& n, int threads) {
    std::vector<LevelError> rows(static_cast<size_t>(given.height));
    parallelFor(given.height, threads, [&](int begin, int end) {
        for (int y = begin; y < end; ++y) {
            LevelError& e = rows[size_t(y)];
            for (int x = 0; x < given.width; ++x) {
                double value[2] = {0, 0}, back[2] = {0, 0};
                for (int c = 0; c < given.channels; ++c) {
                    value[c] = given.at(x, y, c);
                    back[c] = double(n.offset) + double(n.scale) * double(decoded.at(x, y, c));
                    const double d = std::fabs(back[c] - value[c]);
                    e.worst = std::max(e.worst, d);
                    e.squares += d * d;
                    e.count += 1.0;
                }
                if (given.channels == 2) {
                    double a[3], b[3];
                    normalFromXy(value[0], value[1], a);
                    normalFromXy(back[0], back[1], b);
                    const double degrees = angleBetween(a, b) * kDegreesPerRadian;
                    e.worstDegrees = std::max(e.worstDegrees, degrees);
                    e.squareDegrees += degrees * degrees;
                }
            }
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
    for (int layer = 0; layer < content.layerCount(); ++layer)
        for (int level = 0; level < plan.levels; ++level) {
            const int w = mipLevelSide(content.width, level), h = mipLevelSide(content.height, level);
            Image given(w, h, channels);
            fillLayerRows(content, layer, level, 0, h, given.pixels.data());
            for (const float v : given.pixels)
                if (!std::isfinite(v)) return nonFiniteLevel(path, level);
            Image unorm = given;
            for (float& v : unorm.pixels) v = float((double(v) - n.offset) / n.scale);
            // Two channels are xy normals: chosen together by the angle, in the normal's units (ASTC by
            // astcenc's normal-map mode).
            const std::optional<NormalUnits> normals =
                channels == 2 ? std::optional(NormalUnits{n.offset, n.scale}) : std::nullopt;
            out.images.push_back(encodeBlocks(unorm, format, threads, normals));
            if (out.images.back().size() != blockImageBytes(w, h, format))
                return Error{ErrorKind::Internal, path, "internal error: the ASTC encoder failed", "please report this"};
            const Image decoded = decodeBlocks(out.images.back().data(), w, h, format, channels);
            const LevelError e = measure(given, decoded, n, threads);
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
