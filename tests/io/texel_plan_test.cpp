// planTexelStorage reads the range from the plain chains when a job hands them over (ChainValues) rather
// than filling the content's rows: the plan must be the one the rows give, value for value, including
// which zero ends the range and which value an error names, and the row-at-a-time rounding must be the
// value-at-a-time one bit for bit. The content here holds the chain's values in another order (each
// level's rows reversed), so an answer that depends on order shows.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "heightpack/core/mip.hpp"
#include "heightpack/io/texture_write.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

ChainToWrite reversedRows(const std::vector<Image>& chain) {
    ChainToWrite c;
    c.width = chain[0].width;
    c.height = chain[0].height;
    c.channelNames = {"Y"};
    c.fillRows = [&chain](int level, int y0, int rows, float* dst) {
        const Image& l = chain[size_t(level)];
        for (int y = y0; y < y0 + rows; ++y, dst += l.width) std::copy_n(l.row(l.height - 1 - y), l.width, dst);
    };
    return c;
}

Result<TexelStorage> plan(const std::vector<Image>& chain, PixelType type, bool fromChains, float gridSpan = 0.0f) {
    TextureWriteOptions options;
    options.storage.pixelType = type;
    options.threads = 3;
    options.gridOrigin = gridSpan > 0.0f ? -0.5f : 0.0f;
    options.gridSpan = gridSpan;
    options.levels = int(chain.size());
    const ChainToWrite content = reversedRows(chain);
    return planTexelStorage({"t.ktx2", Container::Ktx2}, content, options, fromChains ? ChainValues{&chain} : ChainValues{});
}

std::uint32_t bits(float v) {
    std::uint32_t b;
    std::memcpy(&b, &v, 4);
    return b;
}

}  // namespace

TEST(TexelPlan, ChainsGiveTheNormalisationTheContentsRowsGive) {
    const std::vector<Image> chain = generateMipChain(randomImage(64, 32, 7, -2.0f, 5.0f), Filter::Kaiser);
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (const Image& level : chain)
        for (float v : level.pixels) lo = std::min(lo, v), hi = std::max(hi, v);
    for (const float gridSpan : {0.0f, 7.0f}) {
        auto fromRows = plan(chain, PixelType::Uint16, false, gridSpan);
        auto fromChains = plan(chain, PixelType::Uint16, true, gridSpan);
        ASSERT_TRUE(fromRows.ok() && fromChains.ok());
        ASSERT_TRUE(fromRows->normalisation && fromChains->normalisation);
        EXPECT_EQ(bits(fromChains->normalisation->offset), bits(fromRows->normalisation->offset)) << gridSpan;
        EXPECT_EQ(bits(fromChains->normalisation->scale), bits(fromRows->normalisation->scale)) << gridSpan;
        if (gridSpan == 0.0f) {  // the range itself: value = offset + scale * u / 65535
            EXPECT_EQ(fromChains->normalisation->offset, lo);
            EXPECT_EQ(fromChains->normalisation->scale, float(double(hi) - double(lo)));
        }
    }
    EXPECT_TRUE(plan(chain, PixelType::Half, true).ok());
}

TEST(TexelPlan, AZeroEndingTheRangeIsTheFirstMetInTheContentsOrder) {
    // Level 0's top row holds -0; its bottom row, which the content meets first, -0 too, then +0. With
    // one zero alone its sign is the offset's; with both, the chains cannot say which comes first (the
    // least by bits, -0, is not) and the rows decide.
    for (const bool both : {false, true}) {
        std::vector<Image> chain = generateMipChain(randomImage(16, 16, 3, 0.5f, 2.0f), Filter::Box);
        chain[0].pixels[3] = -0.0f;
        chain[0].pixels[chain[0].pixels.size() - 5] = both ? 0.0f : -0.0f;
        auto fromRows = plan(chain, PixelType::Uint16, false);
        auto fromChains = plan(chain, PixelType::Uint16, true);
        ASSERT_TRUE(fromRows.ok() && fromChains.ok());
        EXPECT_EQ(std::signbit(fromRows->normalisation->offset), !both);
        EXPECT_EQ(bits(fromChains->normalisation->offset), bits(fromRows->normalisation->offset)) << both;
        EXPECT_EQ(bits(fromChains->normalisation->scale), bits(fromRows->normalisation->scale)) << both;
    }
}

TEST(TexelPlan, TheValueAnErrorNamesIsTheFirstInTheContentsOrder) {
    std::vector<Image> chain = generateMipChain(randomImage(16, 16, 5), Filter::Box);
    chain[0].pixels[1] = 70000.0f;                            // first in the chain's order
    chain[0].pixels[chain[0].pixels.size() - 2] = 80000.0f;  // first in the content's
    auto fromRows = plan(chain, PixelType::Half, false);
    auto fromChains = plan(chain, PixelType::Half, true);
    ASSERT_FALSE(fromRows.ok());
    ASSERT_FALSE(fromChains.ok());
    EXPECT_NE(fromRows.error().what.find("80000"), std::string::npos) << fromRows.error().what;
    EXPECT_EQ(fromChains.error().what, fromRows.error().what);
    EXPECT_EQ(fromChains.error().kind, fromRows.error().kind);
    chain[0].pixels[1] = std::numeric_limits<float>::infinity();  // not finite: the internal error, as before
    EXPECT_EQ(plan(chain, PixelType::Uint16, true).error().what, plan(chain, PixelType::Uint16, false).error().what);
}

TEST(TexelPlan, RowRoundingIsTheValueRoundingBitForBit) {
    // Half: ties and near-ties, subnormals, the ends of its range. uint16 over [-2, 1]: values half a code
    // apart, each a near-tie. Lengths that leave a tail after any vector width.
    std::vector<float> halves = {0.0f, -0.0f, 1.0f, 6.0e-8f, -3.0e-5f, 65504.0f, -65519.0f, 1.0f + 1.0f / 2048.0f};
    for (int i = 0; i < 20003; ++i) halves.push_back(float(std::ldexp(std::sin(i * 12.9898) * 1.9, (i % 30) - 20)));
    std::vector<float> codes = {-2.0f, 1.0f, 0.0f, -0.0f};
    for (int code = 0; code < 4001; ++code) codes.push_back(float(-2.0 + 3.0 * (code * 0.5 + 0.25) / 65535.0));
    for (const PixelType type : {PixelType::Half, PixelType::Uint16}) {
        const std::vector<float>& values = type == PixelType::Half ? halves : codes;
        std::vector<Image> chain = {Image(int(values.size()), 1, 1)};
        chain[0].pixels = values;
        auto storage = plan(chain, type, true);
        ASSERT_TRUE(storage.ok());
        std::vector<float> rows(values.size());
        storage->storeAndReadRow(values.data(), values.size(), rows.data());
        for (size_t i = 0; i < values.size(); ++i)
            ASSERT_EQ(bits(rows[i]), bits(storage->storeAndRead(values[i])))
                << pixelTypeName(type) << " value " << values[i];
    }
}
