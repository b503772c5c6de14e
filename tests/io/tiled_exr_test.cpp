// The tiled EXR writer on OpenEXRCore (none, zip, zips): rows of tiles are filled, checked and deflated by
// several workers at once and written in file order as they are done. Read back by OpenEXR's own C++
// reader against the values the source gives; the same bytes and the same refusal at any thread count.
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfTiledInputFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "heightpack/io/exr_write.hpp"

#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// A source of two channels whose every texel of every level differs: a value that names its place.
float valueAt(int level, int x, int y, int c) { return float(level * 1000000 + y * 1000 + x) + 0.25f * c; }

ChainToWrite numberedChain(int width, int height) {
    ChainToWrite content;
    content.width = width, content.height = height;
    content.channelNames = {"Y", "Dx"};
    content.fillRows = [width](int level, int y0, int rows, float* dst) {
        const int w = std::max(1, width >> level);
        for (int y = y0; y < y0 + rows; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 2; ++c) *dst++ = valueAt(level, x, y, c);
    };
    return content;
}

// The same source with its runs too (ChainToWrite::fillRun), which the writer then takes instead of rows.
ChainToWrite withRuns(ChainToWrite content) {
    const int width = content.width;
    content.fillRun = [width](int level, int y, int x0, int count, int channel, float* dst) {
        for (int x = x0; x < x0 + count; ++x) *dst++ = valueAt(level, x, y, channel);
    };
    return content;
}

}  // namespace

TEST(TiledExrWriter, EveryRowOfEveryLevelIsWrittenInPlaceOnAnyThreadCount) {
    ScratchDir dir;
    const int width = 160, height = 96;  // 10 x 6 tiles of 16 at level 0, 8 levels: many rows in flight
    const ChainToWrite content = numberedChain(width, height);
    for (Compression compression : {Compression::Zip, Compression::Zips, Compression::None}) {
        std::vector<std::vector<unsigned char>> files;
        for (int threads : {1, 2, 5}) {
            ExrWriteOptions options;
            options.compression = compression;
            options.tileSize = 16;
            options.threads = threads;
            std::vector<double> reported;
            options.progress = [&](double f) { reported.push_back(f); };
            const std::string path = dir.file("t" + std::to_string(threads) + ".exr");
            ASSERT_TRUE(writeTiledExr(path, content, options).ok());
            files.push_back(readBytes(path));
            ASSERT_FALSE(reported.empty());
            for (size_t i = 1; i < reported.size(); ++i) EXPECT_GT(reported[i], reported[i - 1]) << threads;
            EXPECT_DOUBLE_EQ(reported.back(), 1.0);

            Imf::TiledInputFile exr(path.c_str());
            ASSERT_EQ(exr.numLevels(), 8);
            for (int level = 0; level < exr.numLevels(); ++level) {
                const int w = exr.levelWidth(level), h = exr.levelHeight(level);
                std::vector<float> y(size_t(w) * h), dx(y.size());
                Imf::FrameBuffer frame;
                frame.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(y.data()), sizeof(float), sizeof(float) * w));
                frame.insert("Dx", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(dx.data()), sizeof(float), sizeof(float) * w));
                exr.setFrameBuffer(frame);
                exr.readTiles(0, exr.numXTiles(level) - 1, 0, exr.numYTiles(level) - 1, level);
                for (int r = 0; r < h; ++r)
                    for (int x = 0; x < w; ++x) {
                        ASSERT_EQ(y[size_t(r) * w + x], valueAt(level, x, r, 0)) << level << " " << x << "," << r;
                        ASSERT_EQ(dx[size_t(r) * w + x], valueAt(level, x, r, 1)) << level << " " << x << "," << r;
                    }
            }
        }
        EXPECT_EQ(files[0], files[1]);
        EXPECT_EQ(files[0], files[2]);
    }
}

TEST(TiledExrWriter, TheFirstNonFiniteLevelInFileOrderIsNamedOnAnyThreadCount) {
    // Levels 1 and 3 hold an infinity (level 1 in its last row, which a worker may reach after level 3's):
    // the refusal names level 1 whatever the thread count, from rows or from runs, and no file is left.
    ScratchDir dir;
    ChainToWrite content = numberedChain(128, 128);
    const auto numbered = content.fillRows;
    content.fillRows = [numbered](int level, int y0, int rows, float* dst) {
        numbered(level, y0, rows, dst);
        const int last = (128 >> level) - 1;
        if ((level == 1 || level == 3) && y0 + rows - 1 == last)
            dst[size_t(rows - 1) * (128 >> level) * 2] = std::numeric_limits<float>::infinity();
    };
    ChainToWrite runs = withRuns(content);
    const auto numberedRun = runs.fillRun;
    runs.fillRun = [numberedRun](int level, int y, int x0, int count, int channel, float* dst) {
        numberedRun(level, y, x0, count, channel, dst);
        if ((level == 1 || level == 3) && y == (128 >> level) - 1 && x0 == 0 && channel == 0)
            dst[0] = std::numeric_limits<float>::infinity();
    };
    for (const ChainToWrite* source : {&content, &runs})
        for (int threads : {1, 2, 4}) {
            ExrWriteOptions options;
            options.tileSize = 16;
            options.threads = threads;
            const Status written = writeTiledExr(dir.file("inf.exr"), *source, options);
            ASSERT_FALSE(written.ok());
            EXPECT_EQ(written.error().kind, ErrorKind::Internal);
            EXPECT_NE(written.error().what.find("level 1 "), std::string::npos) << threads << ": " << written.error().what;
            EXPECT_TRUE(dir.listing().empty()) << threads;
        }
}

TEST(TiledExrWriter, ChannelRunsGiveTheBytesThatRowsGive) {
    // A source that also gives each channel's runs is written from them (no band of interleaved rows):
    // the file must be the one written from its rows, float or half, deflated or not, on any thread count.
    ScratchDir dir;
    const ChainToWrite rows = numberedChain(96, 160), runs = withRuns(rows);
    for (Compression compression : {Compression::Zip, Compression::None})
        for (bool half : {false, true}) {
            ExrWriteOptions options;
            options.compression = compression;
            options.tileSize = 32;
            options.half = half;
            options.threads = 1;
            ASSERT_TRUE(writeTiledExr(dir.file("rows.exr"), rows, options).ok());
            for (int threads : {1, 3}) {
                options.threads = threads;
                ASSERT_TRUE(writeTiledExr(dir.file("runs.exr"), runs, options).ok());
                EXPECT_EQ(readBytes(dir.file("runs.exr")), readBytes(dir.file("rows.exr"))) << half << " " << threads;
            }
        }
}
