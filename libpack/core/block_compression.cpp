// The BC4/BC5 encoder from float values: each channel's endpoint search is bc4_fit.cpp's; BC5 normals
// choose x and y together, by the angle (see encodeBc5Block).
#include "heightpack/core/block_compression.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "bc4_fit.hpp"
#include "bc4_quick.hpp"
#include "heightpack/core/astc_compression.hpp"
#include "heightpack/core/parallel.hpp"
#include "lanes.hpp"

namespace heightpack {

namespace {

// A block's pair in the thorough pass: the one choose takes (the worst error first).
void encodeBc4Block(const float v[16], std::uint8_t* out) {
    float clamped[16];
    for (int i = 0; i < 16; ++i) clamped[i] = std::clamp(v[i], 0.0f, 1.0f);
    bc4::Candidates candidates;
    candidates.onlyChoosable = true;
    bc4::search(clamped, candidates);
    const bc4::Tried& best = bc4::choose(candidates);
    bc4::writeBlock(best.e0, best.e1, bc4::codesOf(clamped, best.e0, best.e1), out);
}

// BC5 normals: each channel's candidates of least squared error, paired by the decoded normal's angle.
// Not only those within a quarter code of the channel's least worst: a steep normal's rebuilt z turns a
// small error in x or y into a large angle, so the worst angle is not where either channel's worst error is.
// 8 a channel: 16 brings the family's worst angles down by another 4% in twice the time. (The quick pass
// takes each channel's least squared error alone: its medians stay below nvcompress's and squish's.)
constexpr int kJointFits = 8;
// The pair's cost: the block's summed angle (as the chord between the unit normals) plus 4 times its
// worst, which on the family of tests/io/block_format_test.cpp lowers the worst angles without raising
// the medians.
constexpr float kWorstAngleWeight = 4.0f;

// A channel's `count` candidates of least squared error (the first tried of equals first), with
// their codes and their 16 decoded values as normal components: offset + scale * u.
struct JointFit {  // no member initialisers: a block makes 16 and fills one or a few
    const bc4::Tried* tried;
    std::array<std::uint8_t, 16> codes;
    lanes::Lanes component[4];
};

int leastSquaredFits(const float v[16], const bc4::Candidates& c, const NormalUnits& units, int count, JointFit out[kJointFits]) {
    const float offset = float(units.offset), scale = float(units.scale);
    std::array<int, 96> order;  // the first c.count filled
    const int n = std::min(c.count, count);
    for (int i = 0; i < c.count; ++i) order[size_t(i)] = i;
    std::partial_sort(order.begin(), order.begin() + n, order.begin() + c.count, [&](int a, int b) {
        const float ea = c.tried[size_t(a)].error, eb = c.tried[size_t(b)].error;
        return ea < eb || (ea == eb && a < b);
    });
    for (int i = 0; i < n; ++i) {
        JointFit& f = out[i];
        f.tried = &c.tried[size_t(order[size_t(i)])];
        float decoded[16];
        f.codes = bc4::codesOf(v, f.tried->e0, f.tried->e1, decoded);
        for (int t = 0; t < 16; ++t) decoded[t] = offset + scale * decoded[t];
        for (int r = 0; r < 4; ++r) f.component[r] = lanes::Rows(decoded).row[r];
    }
    return n;
}

// The unit normal of x, y with z rebuilt (x, y past the unit circle: on it, z = 0), as a shader rebuilds it.
struct Normals {
    lanes::Lanes x, y, z;
};
Normals rebuilt(lanes::Lanes x, lanes::Lanes y) {
    using namespace lanes;
    const Lanes rr = x * x + y * y;
    const Lanes z = sqrt(max(1.0f - rr, splat(0.0f)));
    if (largest(rr) <= 1.0f) return {x, y, z};
    const Lanes s = rr > 1.0f ? 1.0f / sqrt(rr) : splat(1.0f);
    return {x * s, y * s, z};
}

// The texels whose angle is at least this share of the block's worst are given joint codes (below).
// (0.5 raises the components' RMS error by 5% on rough maps for no smaller worst angle.)
constexpr float kJointShare = 0.9f;
// How much a pair's components' squared error counts against its squared chord (jointCodes): 3 keeps the
// components' RMS error within 1% of nvcompress's on the family of tests/io/block_format_test.cpp, 0.1
// raises it by 7% there, 10 gives back part of the worst angle.
constexpr float kComponentWeight = 3.0f;

// The pair of codes (x's and y's) whose decoded normal is nearest the given one, for each texel whose
// angle decides the block's worst: the pair need not be each channel's nearest value, since a steep
// normal's rebuilt z weighs x and y together. A texel's angle never grows; the other texels keep the
// channels' nearest values. 64 pairs a texel: for thorough blocks only.
void jointCodes(const float ux[16], const float uy[16], JointFit& fx, JointFit& fy, const Normals given[4], const NormalUnits& units) {
    const std::array<float, 8> px = bc4::palette(fx.tried->e0, fx.tried->e1), py = bc4::palette(fy.tried->e0, fy.tried->e1);
    const float offset = float(units.offset), scale = float(units.scale);
    float xs[8], ys[8];
    for (int k = 0; k < 8; ++k) xs[k] = offset + scale * px[size_t(k)], ys[k] = offset + scale * py[size_t(k)];
    auto squaredChord = [&](int t, float x, float y) {
        const Normals& g = given[t / 4];
        const float rr = x * x + y * y, z = std::sqrt(std::max(1.0f - rr, 0.0f));
        const float s = rr > 1.0f ? 1.0f / std::sqrt(rr) : 1.0f;
        const float dx = x * s - g.x[t % 4], dy = y * s - g.y[t % 4], dz = z - g.z[t % 4];
        return dx * dx + dy * dy + dz * dz;
    };
    float chords[16], worst = 0.0f;
    for (int t = 0; t < 16; ++t) {
        chords[t] = squaredChord(t, xs[fx.codes[size_t(t)]], ys[fy.codes[size_t(t)]]);
        worst = std::max(worst, chords[t]);
    }
    const float deciding = kJointShare * kJointShare * worst;
    for (int t = 0; t < 16; ++t) {
        if (chords[t] >= deciding) {
            // Of the pairs no farther in angle, the one of least chord plus kComponentWeight times the
            // components' squared error: past the unit circle, codes farther out still give the same
            // direction, and would only add to the components' error.
            const float gx = offset + scale * ux[t], gy = offset + scale * uy[t];
            auto cost = [&](float chord, int a, int b) {
                return chord + kComponentWeight * ((xs[a] - gx) * (xs[a] - gx) + (ys[b] - gy) * (ys[b] - gy));
            };
            const float limit = chords[t];
            float least = cost(limit, fx.codes[size_t(t)], fy.codes[size_t(t)]);
            for (int a = 0; a < 8; ++a)
                for (int b = 0; b < 8; ++b) {
                    const float c = squaredChord(t, xs[a], ys[b]);
                    if (c > limit) continue;
                    const float j = cost(c, a, b);
                    if (j < least) least = j, fx.codes[size_t(t)] = std::uint8_t(a), fy.codes[size_t(t)] = std::uint8_t(b);
                }
        }
    }
}

void encodeBc5Block(const float x[16], const float y[16], const NormalUnits& units, std::uint8_t* out) {
    using namespace lanes;
    float cx[16], cy[16];
    for (int i = 0; i < 16; ++i) cx[i] = std::clamp(x[i], 0.0f, 1.0f), cy[i] = std::clamp(y[i], 0.0f, 1.0f);
    bc4::Candidates candX, candY;
    bc4::search(cx, candX);
    bc4::search(cy, candY);
    JointFit fx[kJointFits], fy[kJointFits];
    const int nx = leastSquaredFits(cx, candX, units, kJointFits, fx), ny = leastSquaredFits(cy, candY, units, kJointFits, fy);
    const float offset = float(units.offset), scale = float(units.scale);
    Normals given[4];
    const Rows gx(cx), gy(cy);
    for (int r = 0; r < 4; ++r) given[r] = rebuilt(offset + scale * gx.row[r], offset + scale * gy.row[r]);
    // A pair stops being summed once what it has is no less than the best cost: the rest only adds.
    float best = 1e30f;
    int bi = 0, bj = 0;
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) {
            Lanes sumChord = splat(0.0f), worst = splat(0.0f);
            bool beaten = false;
            for (int r = 0; r < 4 && !beaten; ++r) {
                const Normals n = rebuilt(fx[i].component[r], fy[j].component[r]);
                const Lanes dx = n.x - given[r].x, dy = n.y - given[r].y, dz = n.z - given[r].z;
                const Lanes chord = sqrt(dx * dx + dy * dy + dz * dz);
                sumChord += chord;
                worst = max(worst, chord);
                beaten = sum(sumChord) + kWorstAngleWeight * largest(worst) >= best;
            }
            if (beaten) continue;
            best = sum(sumChord) + kWorstAngleWeight * largest(worst);
            bi = i, bj = j;
        }
    jointCodes(cx, cy, fx[bi], fy[bj], given, units);
    bc4::writeBlock(fx[bi].tried->e0, fx[bi].tried->e1, fx[bi].codes, out);
    bc4::writeBlock(fy[bj].tried->e0, fy[bj].tried->e1, fy[bj].codes, out + 8);
}

// Every block is encoded quickly, then again thoroughly those whose worst error (chord for normals) is
// within this share of the image's worst: the few blocks that decide the worst error reported for the
// image get the search that lowers it, the rest keep their smaller squared error.
constexpr float kThoroughShare = 0.75f;

}  // namespace

void decodeBc4Block(const std::uint8_t* block, float values[16]) {
    const std::array<float, 8> p = bc4::palette(block[0], block[1]);
    std::uint64_t bits = 0;
    for (int i = 0; i < 6; ++i) bits |= std::uint64_t(block[2 + i]) << (8 * i);
    for (int i = 0; i < 16; ++i) values[i] = p[size_t((bits >> (3 * i)) & 7)];
}

std::vector<std::uint8_t> encodeBlocks(ImageView image, BlockFormat format, int threads, std::optional<NormalUnits> normals) {
    if (isAstc(format)) return encodeAstc(image, format, threads, normals.has_value());
    const int channels = blockChannels(format), bytes = blockBytes(format);
    const int across = (image.width + 3) / 4, down = (image.height + 3) / 4;
    std::vector<std::uint8_t> out(blockImageBytes(image.width, image.height, format));
    std::vector<float> worst(size_t(across) * size_t(down));
    // Quickly: eight blocks of a row of blocks side by side (bc4_quick.hpp; past the row's end, its last
    // block again). A block's texels past the image repeat its edge texels.
    parallelFor(down, threads, [&](int begin, int end) {
        bc4::QuickBlocks quick[2];
        for (int by = begin; by < end; ++by)
            for (int bx = 0; bx < across; bx += bc4::kQuickBlocks) {
                // Eight whole blocks inside the image are read from it; at its edges, texel by texel.
                const bool inside = (bx + bc4::kQuickBlocks) * 4 <= image.width && by * 4 + 4 <= image.height;
                for (int c = 0; c < channels; ++c) {
                    quick[c].step = channels;
                    for (int r = 0; r < 4; ++r) quick[c].source[r] = inside ? &image.pixels[(size_t(by * 4 + r) * size_t(image.width) + size_t(bx * 4)) * size_t(channels) + size_t(c)] : nullptr;
                }
                if (!inside)
                    for (int lane = 0; lane < bc4::kQuickBlocks; ++lane)
                        for (int t = 0; t < 16; ++t) {
                            const int x = std::min(std::min(bx + lane, across - 1) * 4 + t % 4, image.width - 1);
                            const int y = std::min(by * 4 + t / 4, image.height - 1);
                            for (int c = 0; c < channels; ++c) quick[c].value[t][lane] = image.at(x, y, c);
                        }
                for (int c = 0; c < channels; ++c) bc4::quickSearch(quick[c]);
                float chords[bc4::kQuickBlocks];
                if (channels == 2 && normals) bc4::quickWorstChords(quick[0], quick[1], float(normals->offset), float(normals->scale), chords);
                for (int lane = 0; lane < bc4::kQuickBlocks && bx + lane < across; ++lane) {
                    const size_t at = size_t(by) * size_t(across) + size_t(bx + lane);
                    worst[at] = 0.0f;
                    for (int c = 0; c < channels; ++c) {
                        std::array<std::uint8_t, 16> codes;
                        for (int t = 0; t < 16; ++t) codes[size_t(t)] = quick[c].code[t][lane];
                        bc4::writeBlock(quick[c].e0[lane], quick[c].e1[lane], codes, out.data() + at * size_t(bytes) + size_t(c) * 8);
                        worst[at] = std::max(worst[at], quick[c].worst[lane]);
                    }
                    if (channels == 2 && normals) worst[at] = chords[lane];
                }
            }
    });
    // Thoroughly: block (bx, by) encoded again into out.
    auto encode = [&](int bx, int by) {
        float v[16], w[16];
        for (int i = 0; i < 16; ++i) {
            const int x = std::min(bx * 4 + i % 4, image.width - 1), y = std::min(by * 4 + i / 4, image.height - 1);
            v[i] = image.at(x, y, 0);
            if (channels == 2) w[i] = image.at(x, y, 1);
        }
        std::uint8_t* block = out.data() + (size_t(by) * size_t(across) + size_t(bx)) * size_t(bytes);
        if (channels == 2 && normals) {
            encodeBc5Block(v, w, *normals, block);
        } else {
            encodeBc4Block(v, block);
            if (channels == 2) encodeBc4Block(w, block + 8);
        }
    };
    const float threshold = kThoroughShare * *std::max_element(worst.begin(), worst.end());
    parallelFor(down, threads, [&](int begin, int end) {
        for (int by = begin; by < end; ++by)
            for (int bx = 0; bx < across; ++bx)
                if (worst[size_t(by) * size_t(across) + size_t(bx)] >= threshold) encode(bx, by);
    });
    return out;
}

Image decodeBlocks(const std::uint8_t* bytes, int width, int height, BlockFormat format, int channels) {
    if (isAstc(format)) return decodeAstc(bytes, width, height, format, channels);
    channels = blockChannels(format);
    const int blockSize = blockBytes(format);
    const int across = (width + 3) / 4;
    Image image(width, height, channels);
    float v[16];
    for (int by = 0; by < (height + 3) / 4; ++by)
        for (int bx = 0; bx < across; ++bx)
            for (int c = 0; c < channels; ++c) {
                decodeBc4Block(bytes + (size_t(by) * across + bx) * size_t(blockSize) + size_t(c) * 8, v);
                for (int i = 0; i < 16; ++i) {
                    const int x = bx * 4 + i % 4, y = by * 4 + i / 4;
                    if (x < width && y < height) image.at(x, y, c) = v[i];
                }
            }
    return image;
}

}  // namespace heightpack
