// BC4/BC5 blocks: the decoder against blocks built by hand from the Khronos Data Format Specification's
// RGTC table, and the encoder's properties (values a block can hold come back exactly; the bytes do not
// depend on the thread count). Its accuracy against nvcompress is judged by nvdecompress in
// tests/io/block_format_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "bc4_quick.hpp"
#include "heightpack/core/block_compression.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// A BC4 block with endpoints red0, red1 and texel i's 3-bit code codes[i], bits laid out as the
// specification says: bits = bits_0 + 256 * (bits_1 + ...), code(x, y) = bits[3 (4y + x) + 2 .. 3 (4y + x)].
std::vector<std::uint8_t> block(int red0, int red1, const int codes[16]) {
    std::uint64_t bits = 0;
    for (int i = 0; i < 16; ++i) bits += std::uint64_t(codes[i]) << (3 * i);
    std::vector<std::uint8_t> b = {std::uint8_t(red0), std::uint8_t(red1)};
    for (int i = 0; i < 6; ++i) b.push_back(std::uint8_t((bits >> (8 * i)) & 0xff));
    return b;
}

// The squared error of the plainest BC4 encoder: per block and channel, endpoints the extremes rounded to
// 8 bits, the eight-value palette (6 e0 + e1) / 7 ..., each texel its nearest entry. Edge blocks repeat
// the edge texels, which add no error of their own.
double minMaxSquaredError(const Image& image) {
    double total = 0.0;
    for (int by = 0; by < (image.height + 3) / 4; ++by)
        for (int bx = 0; bx < (image.width + 3) / 4; ++bx)
            for (int c = 0; c < image.channels; ++c) {
                std::vector<float> v;
                for (int y = by * 4; y < std::min(by * 4 + 4, image.height); ++y)
                    for (int x = bx * 4; x < std::min(bx * 4 + 4, image.width); ++x) v.push_back(image.at(x, y, c));
                const double hi = std::round(*std::max_element(v.begin(), v.end()) * 255.0) / 255.0;
                const double lo = std::round(*std::min_element(v.begin(), v.end()) * 255.0) / 255.0;
                for (const float value : v) {
                    double best = 1e9;
                    for (int k = 0; k < 8; ++k) best = std::min(best, std::fabs(value - (hi + (lo - hi) * k / 7.0)));
                    total += best * best;
                }
            }
    return total;
}

}  // namespace

TEST(BlockCompression, DecodesBothModesAsTheSpecificationTabulates) {
    const int codes[16] = {0, 1, 2, 3, 4, 5, 6, 7, 7, 6, 5, 4, 3, 2, 1, 0};
    float v[16];
    // red0 > red1: eight values, (8 - k) RED_0 + (k - 1) RED_1 over 7 for codes 2..7.
    decodeBc4Block(block(210, 70, codes).data(), v);
    const double r0 = 210 / 255.0, r1 = 70 / 255.0;
    const double eight[8] = {r0, r1, (6 * r0 + r1) / 7, (5 * r0 + 2 * r1) / 7, (4 * r0 + 3 * r1) / 7,
                             (3 * r0 + 4 * r1) / 7, (2 * r0 + 5 * r1) / 7, (r0 + 6 * r1) / 7};
    for (int i = 0; i < 16; ++i) EXPECT_NEAR(v[i], eight[codes[i]], 1e-6) << i;
    // red0 <= red1: six values, then 0.0 and 1.0.
    decodeBc4Block(block(70, 210, codes).data(), v);
    const double s0 = 70 / 255.0, s1 = 210 / 255.0;
    const double six[8] = {s0, s1, (4 * s0 + s1) / 5, (3 * s0 + 2 * s1) / 5, (2 * s0 + 3 * s1) / 5, (s0 + 4 * s1) / 5,
                           0.0, 1.0};
    for (int i = 0; i < 16; ++i) EXPECT_NEAR(v[i], six[codes[i]], 1e-6) << i;
}

TEST(BlockCompression, ValuesABlockHoldsComeBackExactlyInEitherMode) {
    // Over a family of endpoint pairs: a 4x4 image of palette values (eight-value mode; the six-value mode
    // with 0 and 1) is encoded to a block that decodes to the same values, within float rounding.
    int failures = 0, cases = 0;
    for (int a = 3; a < 256; a += 23)
        for (int b = 0; b < 256; b += 37) {
            if (a == b) continue;
            const int codes[16] = {0, 1, 2, 3, 4, 5, 6, 7, 2, 3, 4, 5, 6, 7, 0, 1};
            float palette[16];
            decodeBc4Block(block(a, b, codes).data(), palette);
            Image image(4, 4, 1);
            for (int i = 0; i < 16; ++i) image.pixels[size_t(i)] = palette[i];
            const std::vector<std::uint8_t> bytes = encodeBlocks(image, BlockFormat::Bc4, 1);
            const Image back = decodeBlocks(bytes.data(), 4, 4, BlockFormat::Bc4);
            double worst = 0.0;
            for (int i = 0; i < 16; ++i) worst = std::max(worst, double(std::fabs(back.pixels[size_t(i)] - palette[i])));
            failures += worst > 1e-6;
            ++cases;
        }
    EXPECT_EQ(failures, 0) << "of " << cases;
}

TEST(BlockCompression, SameBytesOnAnyThreadCountAndPaddedEdges) {
    const Image image = randomImage(70, 37, 7);  // neither side a multiple of 4
    Image two(70, 37, 2);
    for (size_t t = 0; t < image.texelCount(); ++t) two.pixels[2 * t] = image.pixels[t], two.pixels[2 * t + 1] = 1 - image.pixels[t];
    for (const BlockFormat f : {BlockFormat::Bc4, BlockFormat::Bc5}) {
        const Image& in = f == BlockFormat::Bc4 ? image : two;
        const std::vector<std::uint8_t> one = encodeBlocks(in, f, 1);
        EXPECT_EQ(one.size(), size_t(18 * 10 * blockBytes(f)));
        EXPECT_EQ(one, encodeBlocks(in, f, 2));
        EXPECT_EQ(one, encodeBlocks(in, f, 3));
        if (f == BlockFormat::Bc5) {  // x and y chosen together, as normals in [-0.9, 0.9]
            const NormalUnits units{-0.9, 1.8};
            const std::vector<std::uint8_t> joint = encodeBlocks(in, f, 1, units);
            EXPECT_EQ(joint, encodeBlocks(in, f, 2, units));
            EXPECT_EQ(joint, encodeBlocks(in, f, 3, units));
        }
        // No worse, in squared error, than the plain encoder written here: each block's extremes rounded
        // to 8 bits as endpoints, eight values between, each texel the nearest.
        const Image back = decodeBlocks(one.data(), in.width, in.height, f);
        double ours = 0.0;
        for (size_t i = 0; i < in.pixels.size(); ++i) ours += std::pow(back.pixels[i] - in.pixels[i], 2);
        EXPECT_LE(ours, minMaxSquaredError(in)) << int(f);
    }
}

// The quick pass's eight blocks side by side (bc4_quick.hpp) over families of blocks: spread, narrow,
// near 0 and 1 (the six-value mode), exactly 0 and 1, flat, two-valued. Whatever the instruction set
// (AVX2 here where the processor has it, against the four-lane code every processor runs) and wherever
// the values are read from (a copy, or an image's channel), every output, BC5's worst chords too, is the
// same bit for bit; each block's recorded codes decode (decodeBc4Block, the specification's
// table) to the recorded values, within their recorded squared and worst error; and the pair is never
// worse than the plainest encoder's, the values' extremes rounded to codes (minMaxSquaredError's).
TEST(BlockCompression, QuickSearchIsTheSameOnEveryInstructionSetAndWithinWhatItRecords) {
    std::mt19937 random(29);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int blocks = 0, sixValueBlocks = 0;
    for (int group = 0; group < 3000; ++group) {
        bc4::QuickBlocks fast, portable;
        for (int lane = 0; lane < bc4::kQuickBlocks; ++lane) {
            const int family = (group * bc4::kQuickBlocks + lane) % 6;
            const float centre = unit(random), spread = family == 1 ? 0.02f * unit(random) : unit(random);
            for (int t = 0; t < 16; ++t) {
                float v = centre + spread * (unit(random) - 0.5f);
                if (family == 2) v = unit(random) < 0.5f ? 0.03f * unit(random) : 1.0f - 0.03f * unit(random);
                if (family == 3) v = unit(random) < 0.3f ? float(random() % 2) : v;
                if (family == 4) v = centre;
                if (family == 5) v = t % 3 ? centre : centre * 0.5f;
                fast.value[t][lane] = std::clamp(v, 0.0f, 1.0f);
            }
        }
        portable = fast;
        // The same blocks read from an image (its second channel), side by side, as the encoder reads them.
        Image strip(4 * bc4::kQuickBlocks, 4, 2);
        for (int t = 0; t < 16; ++t)
            for (int lane = 0; lane < bc4::kQuickBlocks; ++lane) strip.at(4 * lane + t % 4, t / 4, 1) = fast.value[t][lane];
        bc4::QuickBlocks fromImage;
        fromImage.step = 2;
        for (int r = 0; r < 4; ++r) fromImage.source[r] = &strip.pixels[size_t(r) * size_t(strip.width) * 2 + 1];
        bc4::quickSearch(fast);
        bc4::quickSearchPortable(portable);
        bc4::quickSearch(fromImage);
        auto same = [](const auto& a, const auto& b) { return std::memcmp(&a, &b, sizeof a) == 0; };
        ASSERT_TRUE(same(fast.e0, portable.e0) && same(fast.e1, portable.e1) && same(fast.code, portable.code) &&
                    same(fast.decoded, portable.decoded) && same(fast.error, portable.error) && same(fast.worst, portable.worst))
            << "group " << group;
        ASSERT_TRUE(same(fast.value, fromImage.value) && same(fast.e0, fromImage.e0) && same(fast.e1, fromImage.e1) &&
                    same(fast.code, fromImage.code) && same(fast.worst, fromImage.worst))
            << "group " << group << " read from an image";
        // BC5's worst chords (x from this group, y its block order reversed) on both instruction sets.
        bc4::QuickBlocks y = fast;
        for (int t = 0; t < 16; ++t) std::reverse(y.decoded[t], y.decoded[t] + bc4::kQuickBlocks);
        float chords[bc4::kQuickBlocks], portableChords[bc4::kQuickBlocks];
        bc4::quickWorstChords(fast, y, -1.0f, 2.0f, chords);
        bc4::quickWorstChordsPortable(fast, y, -1.0f, 2.0f, portableChords);
        ASSERT_EQ(std::memcmp(chords, portableChords, sizeof chords), 0) << "group " << group << " chords";
        for (int lane = 0; lane < bc4::kQuickBlocks; ++lane, ++blocks) {
            int codes[16];
            Image values(4, 4, 1);
            for (int t = 0; t < 16; ++t) codes[t] = fast.code[t][lane], values.pixels[size_t(t)] = fast.value[t][lane];
            float decoded[16];
            decodeBc4Block(block(fast.e0[lane], fast.e1[lane], codes).data(), decoded);
            double squares = 0.0, worst = 0.0;
            for (int t = 0; t < 16; ++t) {
                EXPECT_NEAR(decoded[t], fast.decoded[t][lane], 1e-6) << "group " << group << " lane " << lane;
                const double d = std::fabs(double(decoded[t]) - values.pixels[size_t(t)]);
                squares += d * d, worst = std::max(worst, d);
            }
            EXPECT_NEAR(squares, fast.error[lane], 1e-5) << "group " << group << " lane " << lane;
            EXPECT_NEAR(worst, fast.worst[lane], 1e-6) << "group " << group << " lane " << lane;
            EXPECT_LE(squares, minMaxSquaredError(values) + 1e-5) << "group " << group << " lane " << lane;
            sixValueBlocks += fast.e0[lane] <= fast.e1[lane];
        }
    }
    EXPECT_GT(sixValueBlocks, blocks / 20);  // the families reach both modes
}
