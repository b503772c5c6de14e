// Issue 12, input/output safety: nothing a command is given may lose a file or write a wrong one.
// Each test runs the heightpack binary end to end on tiny inputs made here and checks independent
// facts: exit codes, one-line errors, file bytes and inodes unchanged, what OpenImageIO reads back.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <utility>

#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
namespace fs = std::filesystem;

namespace {

ProcessResult hp(const std::vector<std::string>& args) {
    // Under timeout(1): a command that hangs on its input fails the test instead of stopping it.
    std::vector<std::string> argv = {"timeout", "60", HEIGHTPACK_EXE};
    argv.insert(argv.end(), args.begin(), args.end());
    return runProcess(argv);
}


ino_t inodeOf(const std::string& path) {
    struct stat st {};
    return ::lstat(path.c_str(), &st) == 0 ? st.st_ino : 0;
}

// A PNG from chunks, CRCs filled in.
struct PngBuilder {
    std::vector<unsigned char> bytes;
    PngBuilder() {
        const char* signature = "\x89PNG\r\n\x1a\n";
        bytes.assign(signature, signature + 8);
    }
    void be32(std::vector<unsigned char>& v, unsigned x) {
        for (int s = 24; s >= 0; s -= 8) v.push_back(static_cast<unsigned char>(x >> s));
    }
    void chunk(const char* type, const std::vector<unsigned char>& data) {
        be32(bytes, static_cast<unsigned>(data.size()));
        std::vector<unsigned char> body(type, type + 4);
        body.insert(body.end(), data.begin(), data.end());
        bytes.insert(bytes.end(), body.begin(), body.end());
        be32(bytes, static_cast<unsigned>(crc32(0, body.data(), static_cast<uInt>(body.size()))));
    }
    void header(unsigned w, unsigned h, unsigned char depth) {
        std::vector<unsigned char> d;
        be32(d, w);
        be32(d, h);
        d.insert(d.end(), {depth, 0, 0, 0, 0});
        chunk("IHDR", d);
    }
};

// The zlib stream of a w x h 8-bit grey image (filter 0 rows) of value(x, y).
std::vector<unsigned char> greyStream(int w, int h, int (*value)(int, int)) {
    std::vector<unsigned char> raw;
    for (int y = 0; y < h; ++y) {
        raw.push_back(0);
        for (int x = 0; x < w; ++x) raw.push_back(static_cast<unsigned char>(value(x, y)));
    }
    std::vector<unsigned char> packed(compressBound(static_cast<uLong>(raw.size())));
    uLongf n = static_cast<uLongf>(packed.size());
    compress(packed.data(), &n, raw.data(), static_cast<uLong>(raw.size()));
    packed.resize(n);
    return packed;
}

int ramp(int x, int y) { return (x * 7 + y * 3) & 255; }

// A pid that no process has: a child that has exited and been reaped.
pid_t deadPid() {
    const pid_t pid = fork();
    if (pid == 0) _exit(0);
    int status = 0;
    waitpid(pid, &status, 0);
    return pid;
}

// Writes a mip-mapped, tiled float EXR of one channel Y with OpenEXR itself, every level from f.
void writeMipExr(const std::string& path, int size, const std::function<float(int, int, int)>& f) {
    Imf::Header header(size, size);
    header.setTileDescription(Imf::TileDescription(16, 16, Imf::MIPMAP_LEVELS, Imf::ROUND_DOWN));
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    Imf::TiledOutputFile file(path.c_str(), header);
    for (int level = 0; level < file.numLevels(); ++level) {
        const int w = file.levelWidth(level), h = file.levelHeight(level);
        std::vector<float> px(size_t(w) * h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) px[size_t(y) * w + x] = f(level, x, y);
        Imf::FrameBuffer frame;
        frame.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px.data()), sizeof(float), sizeof(float) * w));
        file.setFrameBuffer(frame);
        file.writeTiles(0, file.numXTiles(level) - 1, 0, file.numYTiles(level) - 1, level);
    }
}

}  // namespace

// Item 1: an output that is an input (by any name) is refused with exit 2 and the input is untouched.
TEST(IoSafety, OutputOverAnInputIsRefusedWhateverItsName) {
    ScratchDir dir;
    writeImage(dir.file("in.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
    writeImage(dir.file("in.exr"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::FLOAT);
    ASSERT_EQ(::link(dir.file("in.exr").c_str(), dir.file("hard.exr").c_str()), 0);
    const auto png = readBytes(dir.file("in.png")), exr = readBytes(dir.file("in.exr"));
    const ino_t pngInode = inodeOf(dir.file("in.png")), exrInode = inodeOf(dir.file("in.exr"));
    const std::string dotted = (dir.path() / "." / "in.png").string();

    const std::vector<std::vector<std::string>> cases = {
        {"pack", dir.file("in.exr"), "-o", dir.file("in.exr")},
        {"pack", dir.file("in.exr"), "-o", dir.file("hard.exr")},
        {"pack", dir.file("in.exr"), "-o", (dir.path() / "." / "in.exr").string()},
        {"pack", dir.file("in.png"), "-o", dir.file("out.exr"), "--emit-plain", dotted},
        {"pack", dir.file("in.exr"), "-o", dir.file("out.exr"), "--emit-plain", dir.file("hard.exr")},
        {"normal", dir.file("in.png"), "--tile-size", "8m", "--height", "1m", "-o", dotted},
        {"normal", dir.file("in.exr"), "--tile-size", "8m", "--height", "1m", "-o", dir.file("hard.exr")},
        {"tile", dir.file("in.png"), "-o", dir.file("in.png")},
        {"tile", dir.file("in.png"), "-o", dotted, "--force"},
        {"check", dir.file("in.png"), "--preview", dotted},
    };
    for (const auto& args : cases) {
        const ProcessResult run = hp(args);
        EXPECT_EQ(run.code, 2) << args[0] << " " << args.back() << ": " << run.err;
        expectOneLineError(run, "");
        EXPECT_NE(run.err.find("the input"), std::string::npos) << run.err;
    }
    EXPECT_EQ(readBytes(dir.file("in.png")), png);
    EXPECT_EQ(readBytes(dir.file("in.exr")), exr);
    EXPECT_EQ(inodeOf(dir.file("in.png")), pngInode);
    EXPECT_EQ(inodeOf(dir.file("in.exr")), exrInode);
    EXPECT_EQ(dir.listing(), (std::vector<std::string>{"hard.exr", "in.exr", "in.png"}));
}

// Item 2: a name whose format a command does not write is refused, naming what it writes.
TEST(IoSafety, OutputNamesMustSayTheFormatWritten) {
    ScratchDir dir;
    writeImage(dir.file("in.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"pack", dir.file("in.png"), "-o", dir.file("x.png")}, ".exr"},
        {{"pack", dir.file("in.png"), "-o", dir.file("x.tif")}, ".exr"},
        {{"pack", dir.file("in.png"), "-o", dir.file("x.exr"), "--emit-plain", dir.file("p.png")}, ".exr"},
        {{"tile", dir.file("in.png"), "-o", dir.file("x.jpg")}, ".png"},
        {{"tile", dir.file("in.png"), "-o", dir.file("out")}, ".png"},
        {{"normal", dir.file("in.png"), "--tile-size", "8m", "--height", "1m", "-o", dir.file("x.tif")}, ".exr"},
        {{"fresnel", "-o", dir.file("x.jpg")}, ".exr"},
        {{"synth", "--wind", "10", "--tile-size", "64m", "--size", "16", "-o", dir.file("x.jpg")}, ".exr"},
        {{"check", dir.file("in.png"), "--preview", dir.file("x.jpg")}, ".png"},
    };
    for (const auto& [args, named] : cases) {
        const ProcessResult run = hp(args);
        EXPECT_EQ(run.code, 2) << args[0] << ": " << run.err;
        expectOneLineError(run, "");
        EXPECT_NE(run.err.find(named), std::string::npos) << run.err;
        EXPECT_EQ(run.err.find(".hptmp"), std::string::npos) << "names a temporary file: " << run.err;
    }
    EXPECT_EQ(dir.listing(), (std::vector<std::string>{"in.png"}));
}

// Item 3: a TIFF with missing strips is damaged input in every command, never zeros.
TEST(IoSafety, TruncatedTiffIsBadInputEverywhere) {
    ScratchDir dir;
    writeImage(dir.file("full.tif"), randomImage(256, 256, 3), OIIO::TypeDesc::UINT16);
    auto bytes = readBytes(dir.file("full.tif"));
    bytes.resize(bytes.size() / 2);
    writeBytes(dir.file("cut.tif"), bytes);
    const std::string cut = dir.file("cut.tif");
    const std::vector<std::vector<std::string>> cases = {
        {"pack", cut, "-o", dir.file("o.exr")},
        {"normal", cut, "--tile-size", "8m", "--height", "1m", "-o", dir.file("o.exr")},
        {"tile", cut, "-o", dir.file("o.tif")},
        {"info", cut},
        {"check", cut},
    };
    for (const auto& args : cases) {
        const ProcessResult run = hp(args);
        EXPECT_EQ(run.code, 3) << args[0] << ": " << run.err;
        expectOneLineError(run, cut);
        EXPECT_NE(run.err.find("damaged"), std::string::npos) << run.err;
    }
    EXPECT_EQ(dir.listing(), (std::vector<std::string>{"cut.tif", "full.tif"}));
}

// Item 4: numbers that are not finite, or absurd, are usage errors; nothing is written.
TEST(IoSafety, NonFiniteAndAbsurdOptionValuesAreUsageErrors) {
    ScratchDir dir;
    writeImage(dir.file("in.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
    const std::string in = dir.file("in.png"), out = dir.file("o.exr");
    const std::vector<std::string> synth = {"synth", "--tile-size", "64m", "--size", "16", "-o", out};
    auto with = [](std::vector<std::string> base, std::initializer_list<std::string> more) {
        base.insert(base.end(), more);
        return base;
    };
    const std::vector<std::vector<std::string>> cases = {
        with(synth, {"--wind", "10", "--direction", "nan"}),
        with(synth, {"--wind", "10", "--direction", "inf"}),
        with(synth, {"--wind", "10", "--gamma", "nan"}),
        with(synth, {"--wind", "1e300"}),
        {"synth", "--wind", "10", "--tile-size", "1e300", "--size", "16", "-o", out},
        with(synth, {"--wind", "10", "--fetch", "1e300"}),
        {"fresnel", "--ior", "nan", "-o", out},
        {"normal", in, "--tile-size", "8m", "--height", "1e300", "-o", out},
        {"normal", in, "--tile-size", "1e300,8", "--height", "1", "-o", out},
        {"check", in, "--threshold", "nan"},
        {"tile", in, "--threshold", "nan", "-o", dir.file("t.png")},
        {"pack", in, "--scale", "1e300", "-o", out},
        {"pack", in, "--offset", "nan", "-o", out},
    };
    for (const auto& args : cases) {
        const ProcessResult run = hp(args);
        std::string line;
        for (const auto& a : args) line += a + " ";
        EXPECT_EQ(run.code, 2) << line << ": " << run.err;
        expectOneLineError(run, "");
    }
    EXPECT_EQ(dir.listing(), (std::vector<std::string>{"in.png"}));
}

// Item 4, manifests: a value out of range is bad input at FILE:LINE.
TEST(IoSafety, ManifestValuesMustBeSane) {
    ScratchDir dir;
    writeImage(dir.file("a.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
    const std::string head = "format = 1\nname = \"sea\"\n\n[[displacement]]\nsource = \"a.png\"\n";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {head + "name = \"a\"\ntile_size = 64.0\n\n[normals]\nsource = \"a.png\"\ntile_size = 8.0\nheight = 1e300\n",
         ":12"},
        {head + "name = \"a\"\ntile_size = 1e300\n", ":7"},
        {head + "name = \"a\"\ntile_size = 64.0\n" + std::string(200000, 'k') + " = 1\n", ":8"},
    };
    for (const auto& [text, line] : cases) {
        std::ofstream(dir.file("m.toml")) << text;
        const ProcessResult run = hp({"build", dir.file("m.toml"), "-o", dir.file("out")});
        EXPECT_EQ(run.code, 3) << run.err.substr(0, 300);
        expectOneLineError(run, dir.file("m.toml") + line);
        EXPECT_LT(run.err.size(), 600u) << "a long key is echoed whole";
    }
    EXPECT_FALSE(fs::exists(dir.file("out")));
}

// Item 5: RLE BMPs (which OpenImageIO 2.4 decodes wrongly) are refused with a hint.
TEST(IoSafety, RleBmpIsRefusedWithAHint) {
    ScratchDir dir;
    // 4x2 8-bit BMP, BI_RLE8, grey palette: each row one run of 4 texels, then end of line / bitmap.
    std::vector<unsigned char> bmp;
    auto le = [&](unsigned v, int n) {
        for (int i = 0; i < n; ++i) bmp.push_back(static_cast<unsigned char>(v >> (8 * i)));
    };
    const std::vector<unsigned char> rle = {4, 10, 0, 0, 4, 200, 0, 1};
    const unsigned offset = 14 + 40 + 256 * 4;
    bmp.push_back('B');
    bmp.push_back('M');
    le(offset + static_cast<unsigned>(rle.size()), 4);
    le(0, 4);
    le(offset, 4);
    le(40, 4);
    le(4, 4);
    le(2, 4);
    le(1, 2);
    le(8, 2);
    le(1, 4);  // BI_RLE8
    le(static_cast<unsigned>(rle.size()), 4);
    le(2835, 4);
    le(2835, 4);
    le(256, 4);
    le(0, 4);
    for (unsigned i = 0; i < 256; ++i) le(i | i << 8 | i << 16, 4);
    bmp.insert(bmp.end(), rle.begin(), rle.end());
    writeBytes(dir.file("rle.bmp"), bmp);
    for (const std::vector<std::string>& args : {std::vector<std::string>{"pack", dir.file("rle.bmp"), "-o", dir.file("o.exr")},
                                                 std::vector<std::string>{"info", dir.file("rle.bmp")}}) {
        const ProcessResult run = hp(args);
        EXPECT_EQ(run.code, 3) << run.err;
        expectOneLineError(run, dir.file("rle.bmp"));
        EXPECT_NE(run.err.find("RLE"), std::string::npos) << run.err;
        EXPECT_NE(run.err.find("PNG"), std::string::npos) << run.err;
    }
    EXPECT_EQ(dir.listing(), (std::vector<std::string>{"rle.bmp"}));
}

// Item 6: a FIFO or a device as input is refused at once, never read (it would hang).
TEST(IoSafety, FifoAndDevicesAreNotReadAsInput) {
    ScratchDir dir;
    ASSERT_EQ(::mkfifo(dir.file("pipe.png").c_str(), 0644), 0);
    for (const std::string& input : {dir.file("pipe.png"), std::string("/dev/zero")}) {
        const std::vector<std::vector<std::string>> cases = {
            {"pack", input, "-o", dir.file("o.exr")},
            {"normal", input, "--tile-size", "8m", "--height", "1m", "-o", dir.file("o.exr")},
            {"tile", input, "-o", dir.file("o.png")},
            {"check", input},
            {"info", input},
        };
        for (const auto& args : cases) {
            const ProcessResult run = hp(args);
            EXPECT_EQ(run.code, 3) << args[0] << " " << input << ": " << run.err;
            expectOneLineError(run, input);
            EXPECT_NE(run.err.find("not a regular file"), std::string::npos) << run.err;
        }
    }
    EXPECT_EQ(dir.listing(), (std::vector<std::string>{"pipe.png"}));
}

// Item 7: a header claiming a huge image is bad input, judged before anything is allocated.
TEST(IoSafety, HugeHeadersAreBadInputInEveryReader) {
    ScratchDir dir;
    writeBytes(dir.file("huge.png"), pngWithClaimedSize(100000, 100000));
    writeBytes(dir.file("big.png"), pngWithClaimedSize(32768, 32768));
    // A small TIFF whose header is patched to claim 60000 x 60000 texels.
    writeImage(dir.file("small.tif"), makeImage(8, 8, smoothWave), OIIO::TypeDesc::UINT8);
    auto tif = readBytes(dir.file("small.tif"));
    ASSERT_EQ(tif[0], 'I');  // little-endian, as OpenImageIO writes on x86
    auto le16 = [&](size_t at) { return unsigned(tif[at]) | unsigned(tif[at + 1]) << 8; };
    const size_t ifd = tif[4] | tif[5] << 8 | tif[6] << 16 | size_t(tif[7]) << 24;
    for (unsigned i = 0, n = le16(ifd); i < n; ++i) {
        const size_t e = ifd + 2 + 12 * i;
        if (le16(e) == 256 || le16(e) == 257) {  // ImageWidth, ImageLength
            const unsigned v = 60000;
            tif[e + 8] = v & 255;
            tif[e + 9] = v >> 8;
            if (le16(e + 2) == 4) tif[e + 10] = tif[e + 11] = 0;
        }
    }
    writeBytes(dir.file("huge.tif"), tif);
    for (const char* name : {"huge.png", "big.png", "huge.tif"}) {
        for (const char* command : {"check", "info"}) {
            const ProcessResult run = hp({command, dir.file(name)});
            EXPECT_EQ(run.code, 3) << command << " " << name << ": " << run.err;
            expectOneLineError(run, dir.file(name));
            EXPECT_NE(run.err.find("larger than heightpack accepts"), std::string::npos) << run.err;
        }
    }
}

// Issue 34: every fuzz finding (tests/io/hostile) is refused within a small margin of the memory a command
// needs to start, measured against info on good files of the same size: an EXR (read without
// OpenImageIO) and a TIFF (which maps OpenImageIO's module, tens of MB under the sanitizers). The EXR whose
// channel list ran past its size made OpenEXR allocate 2 GB before it failed.
TEST(IoSafety, InfoOnEveryHostileInputStaysNearItsStartUpMemory) {
    ScratchDir dir;
    ProcessResult baseline;
    for (const char* good : {"good.exr", "good.tif"}) {
        writeImage(dir.file(good), makeImage(8, 8, smoothWave), OIIO::TypeDesc::FLOAT);
        const ProcessResult run = hp({"info", dir.file(good)});
        ASSERT_EQ(run.code, 0) << run.err;
        ASSERT_GT(run.peakKiB, 0);
        if (run.peakKiB > baseline.peakKiB) baseline = run;
    }
    const long marginKiB = 32 * 1024;
    int files = 0;
    for (const auto& e : fs::directory_iterator(std::string(HEIGHTPACK_SOURCE_DIR) + "/tests/io/hostile")) {
        if (e.path().extension() == ".md") continue;
        const ProcessResult run = hp({"info", e.path().string()});
        EXPECT_LE(run.peakKiB, baseline.peakKiB + marginKiB)
            << e.path().filename() << ": " << run.peakKiB << " KiB against " << baseline.peakKiB << " KiB for a good file";
        EXPECT_TRUE(run.code == 0 || run.code == 3) << e.path() << ": " << run.err;
        ++files;
    }
    EXPECT_GE(files, 12);
}

// Item 8: an output that exists and is not a regular file, or is a link, is refused (exit 4).
TEST(IoSafety, OutputsThatAreNotRegularFilesAreRefused) {
    ScratchDir dir;
    writeImage(dir.file("in.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
    ASSERT_EQ(::mkfifo(dir.file("node.exr").c_str(), 0644), 0);
    writeBytes(dir.file("target.exr"), {'o', 'l', 'd'});
    ASSERT_EQ(::symlink("target.exr", dir.file("link.exr").c_str()), 0);
    for (const char* output : {"node.exr", "link.exr"}) {
        const ProcessResult run = hp({"pack", dir.file("in.png"), "-o", dir.file(output)});
        EXPECT_EQ(run.code, 4) << output << ": " << run.err;
        expectOneLineError(run, dir.file(output));
    }
    struct stat st {};
    ASSERT_EQ(::lstat(dir.file("node.exr").c_str(), &st), 0);
    EXPECT_TRUE(S_ISFIFO(st.st_mode));
    ASSERT_EQ(::lstat(dir.file("link.exr").c_str(), &st), 0);
    EXPECT_TRUE(S_ISLNK(st.st_mode));
    EXPECT_EQ(readBytes(dir.file("target.exr")), (std::vector<unsigned char>{'o', 'l', 'd'}));
    // A device: /dev/full, which no command may replace.
    const ProcessResult full = hp({"fresnel", "-o", "/dev/full"});
    EXPECT_EQ(full.code, 4) << full.err;
    expectOneLineError(full, "/dev/full");
}

// Item 9: chunk orders that libpng refuses are not decoded by the fast PNG path either.
TEST(IoSafety, FastPngDecoderFollowsChunkOrder) {
    ScratchDir dir;
    const auto stream = greyStream(16, 16, ramp);
    PngBuilder good;
    good.header(16, 16, 8);
    good.chunk("IDAT", stream);
    good.chunk("IEND", {});
    writeBytes(dir.file("good.png"), good.bytes);
    PngBuilder second;  // a second IHDR, 16-bit, after the data
    second.header(16, 16, 8);
    second.chunk("IDAT", stream);
    second.header(16, 16, 16);
    second.chunk("IEND", {});
    writeBytes(dir.file("second.png"), second.bytes);
    PngBuilder split;  // the IDAT run interrupted by a text chunk
    split.header(16, 16, 8);
    const size_t half = stream.size() / 2;
    split.chunk("IDAT", {stream.begin(), stream.begin() + half});
    split.chunk("tEXt", {'a', 0, 'b'});
    split.chunk("IDAT", {stream.begin() + half, stream.end()});
    split.chunk("IEND", {});
    writeBytes(dir.file("split.png"), split.bytes);

    const ProcessResult ok = hp({"pack", dir.file("good.png"), "-o", dir.file("good.exr"), "--json"});
    EXPECT_EQ(ok.code, 0) << ok.err;
    EXPECT_NE(ok.out.find("heightpack-png"), std::string::npos) << "the fast path should take a plain PNG";
    for (const char* name : {"second.png", "split.png"}) {
        const ProcessResult run = hp({"pack", dir.file(name), "-o", dir.file("o.exr"), "--json"});
        EXPECT_EQ(run.out.find("heightpack-png"), std::string::npos) << name << " was decoded by the fast path";
        if (run.code != 0) {
            EXPECT_EQ(run.code, 3) << run.err;
            expectOneLineError(run, dir.file(name));
        }
    }
}

// The fast PNG path takes the file's bytes and frees them as it inflates: a PNG whose chunks are whole
// (every CRC right) around image data that does not inflate, or whose rows name no PNG filter, is read
// again by OpenImageIO and refused as any damaged PNG is, naming the file.
TEST(IoSafety, FastPngDataThatDoesNotDecodeIsReadAgainAndRefused) {
    ScratchDir dir;
    std::vector<unsigned char> cut = greyStream(16, 16, ramp);
    cut.resize(cut.size() / 2);  // a zlib stream that ends early
    std::vector<unsigned char> raw;
    for (int y = 0; y < 16; ++y) {
        raw.push_back(9);  // filter types stop at 4
        for (int x = 0; x < 16; ++x) raw.push_back(static_cast<unsigned char>(ramp(x, y)));
    }
    std::vector<unsigned char> badFilter(compressBound(static_cast<uLong>(raw.size())));
    uLongf n = static_cast<uLongf>(badFilter.size());
    compress(badFilter.data(), &n, raw.data(), static_cast<uLong>(raw.size()));
    badFilter.resize(n);
    for (const auto& [name, stream] : {std::pair{"cut.png", cut}, std::pair{"filter.png", badFilter}}) {
        PngBuilder png;
        png.header(16, 16, 8);
        png.chunk("IDAT", stream);
        png.chunk("IEND", {});
        writeBytes(dir.file(name), png.bytes);
        const ProcessResult run = hp({"pack", dir.file(name), "-o", dir.file("o.exr")});
        EXPECT_EQ(run.code, 3) << name << ": " << run.err;
        expectOneLineError(run, dir.file(name));
        EXPECT_FALSE(fs::exists(dir.file("o.exr"))) << name;
    }
}

// Item 10: a writer's temporaries left by a killed run (dead pid) are removed by the next write.
TEST(IoSafety, StaleTemporariesOfAnOutputAreRemovedByTheNextWrite) {
    ScratchDir dir;
    writeImage(dir.file("in.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
    const std::string pid = std::to_string(deadPid());
    const std::string mine = ".out.hptmp-" + pid + "-0.exr", other = ".other.hptmp-" + pid + "-0.exr";
    const std::string live = ".out.hptmp-" + std::to_string(::getpid()) + "-0.exr";  // a writer still running
    for (const std::string& name : {mine, other, live}) writeBytes(dir.file(name), std::vector<unsigned char>(100, 1));
    const std::vector<std::vector<std::string>> writes = {
        {"pack", dir.file("in.png"), "-o", dir.file("out.exr")},
        {"fresnel", "-o", dir.file("out.exr")},
        {"tile", dir.file("in.png"), "-o", dir.file("out.exr")},
    };
    for (const auto& args : writes) {
        writeBytes(dir.file(mine), std::vector<unsigned char>(100, 1));
        const ProcessResult run = hp(args);
        EXPECT_EQ(run.code, 0) << args[0] << ": " << run.err;
        EXPECT_FALSE(fs::exists(dir.file(mine))) << args[0] << " left its stale temporary";
    }
    EXPECT_TRUE(fs::exists(dir.file(other)));
    EXPECT_TRUE(fs::exists(dir.file(live)));
}

// Item 11: the finished file is flushed before it is renamed, and the folder after.
TEST(IoSafety, OutputsAreFlushedBeforeAndAfterTheRename) {
    if (std::system("strace -V > /dev/null 2>&1") != 0) HEIGHTPACK_WITHOUT_ORACLE("strace is not installed");
    ScratchDir dir;
    writeImage(dir.file("in.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
    const ProcessResult run = runProcess({"strace", "-f", "-e", "trace=fsync,rename,renameat,renameat2", "-o",
                                          dir.file("trace"), HEIGHTPACK_EXE, "pack", dir.file("in.png"), "-o",
                                          dir.file("out.exr")});
    if (run.code != 0 && !fs::exists(dir.file("out.exr"))) GTEST_SKIP() << "strace cannot trace here: " << run.err;
    std::ifstream in(dir.file("trace"));
    std::string line, calls;
    while (std::getline(in, line)) {
        if (line.find("fsync(") != std::string::npos) calls += "F";
        if (line.find("rename") != std::string::npos && line.find("out.exr") != std::string::npos) calls += "R";
    }
    EXPECT_NE(calls.find("FRF"), std::string::npos) << calls;
}

// Item 12: check on a mip-mapped EXR holding NaN is bad input naming the NaN, not a seam verdict.
TEST(IoSafety, CheckOnAMipMappedExrHoldingNanIsBadInput) {
    ScratchDir dir;
    writeMipExr(dir.file("nan.exr"), 64, [](int level, int x, int y) {
        return level == 1 && x == 3 && y == 5 ? std::numeric_limits<float>::quiet_NaN() : smoothWave(x, y);
    });
    const ProcessResult run = hp({"check", dir.file("nan.exr")});
    EXPECT_EQ(run.code, 3) << run.out << run.err;
    expectOneLineError(run, dir.file("nan.exr"));
    EXPECT_NE(run.err.find("level 1 holds NaN at texel 3,5"), std::string::npos) << run.err;

    // A mip-mapped EXR missing its last level is damaged, not judged on level 0 alone.
    writeMipExr(dir.file("good.exr"), 64, [](int, int x, int y) { return smoothWave(x, y); });
    auto bytes = readBytes(dir.file("good.exr"));
    bytes.resize(bytes.size() - 8);
    writeBytes(dir.file("cut.exr"), bytes);
    const ProcessResult cut = hp({"check", dir.file("cut.exr")});
    EXPECT_EQ(cut.code, 3) << cut.out << cut.err;
    expectOneLineError(cut, dir.file("cut.exr"));
    EXPECT_NE(cut.err.find("damaged"), std::string::npos) << cut.err;
}

// Item 13: the rough messages: permission denied, empty output path.
TEST(IoSafety, MessagesSayWhatIsWrong) {
    ScratchDir dir;
    writeImage(dir.file("in.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);

    const ProcessResult empty = hp({"pack", dir.file("in.png"), "-o", ""});
    EXPECT_EQ(empty.code, 2) << empty.err;
    expectOneLineError(empty, "-o ''");

    if (::geteuid() == 0 && std::system("setpriv --help > /dev/null 2>&1") == 0) {
        writeImage(dir.file("secret.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
        ::chmod(dir.file("secret.png").c_str(), 0600);
        ::chmod(dir.path().c_str(), 0755);
        const ProcessResult run = runProcess({"setpriv", "--reuid=65534", "--regid=65534", "--clear-groups",
                                              HEIGHTPACK_EXE, "info", dir.file("secret.png")});
        EXPECT_EQ(run.code, 3) << run.err;
        expectOneLineError(run, dir.file("secret.png"));
        EXPECT_NE(run.err.find("permission denied"), std::string::npos) << run.err;
        EXPECT_EQ(run.err.find("export it as"), std::string::npos) << run.err;
        const ProcessResult full = runProcess({"setpriv", "--reuid=65534", "--regid=65534", "--clear-groups",
                                               HEIGHTPACK_EXE, "fresnel", "-o", "/dev/full"});
        EXPECT_EQ(full.code, 4) << full.err;
        expectOneLineError(full, "/dev/full");
    }
}

// A PNG's heightpack:loopPeriod text that is no number (hand-edited, or another tool's) was read with
// std::stof when packing: an uncaught exception, exit 70. It is damaged metadata: exit 3, nothing written;
// a real number is carried into the packed file.
// A packed texture whose recorded height scale was damaged (issue 38's example): info refuses it, as pack
// and the viewer do, where it printed 'heightScale x' and exited 0.
TEST(IoSafety, InfoRefusesADamagedRecordedNumber) {
    ScratchDir dir;
    const std::string packed = dir.file("s.ktx2");
    ASSERT_EQ(hp({"pack", std::string(HEIGHTPACK_SOURCE_DIR) + "/examples/maps/ripple.png", "-o", packed, "-q"}).code, 0);
    ASSERT_EQ(hp({"info", packed}).code, 0);
    std::vector<unsigned char> bytes = readBytes(packed);
    const std::string key("heightpack:heightScale\0", 23);
    const auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
    ASSERT_NE(at, bytes.end());
    ASSERT_TRUE(std::isdigit(at[23]));
    at[23] = 'x';
    writeBytes(dir.file("bad.ktx2"), bytes);
    const ProcessResult run = hp({"info", dir.file("bad.ktx2")});
    EXPECT_EQ(run.code, 3) << run.out;
    expectOneLineError(run, dir.file("bad.ktx2"));
    EXPECT_NE(run.err.find("heightScale"), std::string::npos) << run.err;
}

TEST(IoSafety, LoopPeriodMetadataThatIsNoNumberIsBadInput) {
    ScratchDir dir;
    for (const auto& [text, good] : {std::pair<std::string, bool>{"abc", false}, {"12.5x", false}, {"12.5", true}}) {
        const std::string png = dir.file("seq.png"), out = dir.file("seq.exr");
        auto writer = OIIO::ImageOutput::create(png);
        ASSERT_TRUE(writer);
        OIIO::ImageSpec spec(16, 16, 1, OIIO::TypeDesc::UINT8);
        spec.attribute("heightpack:loopPeriod", text);
        std::vector<unsigned char> pixels(256);
        for (int i = 0; i < 256; ++i) pixels[i] = static_cast<unsigned char>(i);
        ASSERT_TRUE(writer->open(png, spec) && writer->write_image(OIIO::TypeDesc::UINT8, pixels.data()) && writer->close());
        const ProcessResult run = hp({"pack", png, "-o", out});
        if (good) {
            EXPECT_EQ(run.code, 0) << run.err;
            auto in = OIIO::ImageInput::open(out);
            ASSERT_TRUE(in);
            EXPECT_FLOAT_EQ(in->spec().get_float_attribute("heightpack:loopPeriod"), 12.5f);
        } else {
            EXPECT_EQ(run.code, 3) << text << ": " << run.err;
            expectOneLineError(run, png);
            EXPECT_FALSE(fs::exists(out)) << text;
        }
        fs::remove(out);
    }
}

TEST(IoSafety, ASequenceWithABadFrameLeavesTheOutputsOfAnEarlierRunAsTheyWere) {
    // Three frames; a first run writes every output. Then frame 2 is damaged: each command fails on it
    // (exit 3) and the folder must be byte for byte what the first run left, no frame of the new run in it.
    ScratchDir dir;
    for (int f = 0; f < 3; ++f)
        writeImage(dir.file("seq.000" + std::to_string(f) + ".png"), randomImage(16, 16, 40 + f), OIIO::TypeDesc::UINT16);
    const std::string seq = dir.file("seq.png");
    const std::vector<std::vector<std::string>> commands = {
        {"pack", seq, "-o", dir.file("p.exr"), "--emit-plain", dir.file("plain.exr")},
        {"normal", seq, "--tile-size", "8m", "--height", "1m", "-o", dir.file("n.exr")},
        {"check", seq, "--preview", dir.file("c.png")},
    };
    for (const auto& args : commands) ASSERT_EQ(hp(args).code, 0) << args[0];
    // Frame 2 becomes another map, so a second run would write different frames 0 and 1 too... if it wrote.
    for (int f = 0; f < 2; ++f)
        writeImage(dir.file("seq.000" + std::to_string(f) + ".png"), randomImage(16, 16, 90 + f), OIIO::TypeDesc::UINT16);
    auto bytes = readBytes(dir.file("seq.0002.png"));
    bytes.resize(bytes.size() / 2);
    writeBytes(dir.file("seq.0002.png"), bytes);
    std::map<std::string, std::vector<unsigned char>> before;
    for (const std::string& name : dir.listing()) before[name] = readBytes(dir.file(name));
    for (const auto& args : commands) {
        const ProcessResult run = hp(args);
        EXPECT_EQ(run.code, 3) << args[0] << ": " << run.err;
        expectOneLineError(run, "seq.0002.png");
        EXPECT_EQ(run.out.find("wrote"), std::string::npos) << args[0] << " says it wrote what it did not: " << run.out;
        EXPECT_EQ(run.out.find("preview:"), std::string::npos) << args[0] << ": " << run.out;
    }
    std::vector<std::string> names;
    for (const auto& [name, content] : before) {
        names.push_back(name);
        EXPECT_EQ(readBytes(dir.file(name)), content) << name << " changed";
    }
    EXPECT_EQ(dir.listing(), names);  // and no temporary left behind
    EXPECT_EQ(names.size(), 3u + 6u + 3u + 3u);
}
