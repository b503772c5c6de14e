// Files made to break the readers underneath (issue 21), found by fuzzing (tests/io/hostile/README.md):
// each is refused as bad input naming the file, or loads whole, and never reaches a reader that would
// read out of bounds or allocate what its header claims. Run under AddressSanitizer in CI, where the
// JPEG that made OpenImageIO's IPTC parser read past its buffer is the regression test for that.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <tuple>

#include <sys/resource.h>

#include "heightpack/io/info.hpp"
#include "heightpack/io/gpu_texture.hpp"
#include "heightpack/io/read.hpp"

#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
namespace fs = std::filesystem;

namespace {

const std::string kHostile = std::string(HEIGHTPACK_SOURCE_DIR) + "/tests/io/hostile/";

TEST(HostileInput, EveryFuzzFindingIsRefusedNamingTheFileOrLoadsWhole) {
    int refused = 0;
    for (const auto& e : fs::directory_iterator(kHostile)) {
        const std::string path = e.path().string();
        if (e.path().extension() == ".md") continue;
        auto heights = loadHeightMap(path);
        auto texture = readTextureFile(path);
        if (e.path().filename() == "iptc_overflow.jpg" || e.path().filename() == "iptc_between_scans.jpg") {
            // Their malformed IPTC segments (before the first scan; between a progressive file's scans) are
            // dropped before OpenImageIO parses them; the pixels are fine.
            ASSERT_TRUE(heights) << heights.error().what;
            EXPECT_EQ(heights->heights.width, 8);
            for (float v : heights->heights.pixels) EXPECT_TRUE(std::isfinite(v) && v >= 0 && v <= 1);
            EXPECT_TRUE(texture);
            continue;
        }
        ++refused;
        ASSERT_FALSE(heights) << path;
        EXPECT_EQ(heights.error().kind, ErrorKind::BadInput) << path;
        EXPECT_EQ(heights.error().path, path);
        ASSERT_FALSE(texture) << path;
        EXPECT_EQ(texture.error().kind, ErrorKind::BadInput) << path;
    }
    EXPECT_EQ(refused, 11);
}

// What the readers refuse and why, one file each, made here from a good file.
class HostileHeaders : public ::testing::Test {
protected:
    ScratchDir dir;
    std::string good(const std::string& name, int size = 64) {
        const std::string path = dir.file(name);
        writeImage(path, randomImage(size, size, 7), name.ends_with(".exr") ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
        return path;
    }
    std::string refusal(const std::vector<unsigned char>& bytes, const std::string& name) {
        writeBytes(dir.file(name), bytes);
        auto loaded = loadHeightMap(dir.file(name));
        if (loaded) return "loaded";
        EXPECT_EQ(loaded.error().kind, ErrorKind::BadInput);
        return loaded.error().what;
    }
};

TEST_F(HostileHeaders, FormatsHeightpackDoesNotReadAreRefusedByTheirMagicNotTheirName) {
    // A DPX header, named .png: OpenImageIO would try its DPX reader once the PNG reader refused it.
    std::vector<unsigned char> dpx = {'S', 'D', 'P', 'X'};
    dpx.resize(2048, 0);
    EXPECT_NE(refusal(dpx, "dpx.png").find("DPX"), std::string::npos);
    EXPECT_NE(refusal({'G', 'I', 'F', '8', '9', 'a', 1, 0, 1, 0, 0, 0, 0}, "a.gif").find("GIF"), std::string::npos);
    EXPECT_NE(refusal({'h', 'e', 'l', 'l', 'o'}, "hello.tif").find("not an image in a format heightpack reads"),
              std::string::npos);
    // A good PNG named .exr still loads: the bytes decide, not the name.
    const std::string png = good("real.png");
    fs::copy_file(png, dir.file("real_png.exr"));
    EXPECT_TRUE(loadHeightMap(dir.file("real_png.exr")));
}

TEST_F(HostileHeaders, AnExrAttributeLongerThanTheFileIsRefusedBeforeOpenExrAllocatesIt) {
    std::vector<unsigned char> bytes = readBytes(good("a.exr"));
    ASSERT_TRUE(loadHeightMap(dir.file("a.exr")));
    // The first attribute's size field follows its name and type names, 8 bytes into the file.
    size_t at = 8;
    while (bytes[at]) ++at;
    ++at;
    while (bytes[at]) ++at;
    ++at;
    bytes[at] = 0xF0, bytes[at + 1] = 0xFF, bytes[at + 2] = 0xFF, bytes[at + 3] = 0x3F;  // ~1 GB
    EXPECT_NE(refusal(bytes, "long.exr").find("claims more bytes than the file holds"), std::string::npos);
}

TEST_F(HostileHeaders, AnExrWhoseOffsetTableCannotFitInTheFileIsRefused) {
    std::vector<unsigned char> bytes = readBytes(good("b.exr", 8));
    // Widen the data window to 16384x16384 (within the size limits): its 1024 zip chunks would need an
    // offset table of 8 KiB, which OpenEXR allocates before reading it from a file of a few hundred bytes.
    const std::string key("dataWindow\0box2i\0", 17);
    const auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
    ASSERT_NE(at, bytes.end());
    const size_t window = size_t(at - bytes.begin()) + key.size() + 4;
    for (size_t corner : {window + 8, window + 12}) {
        bytes[corner] = 0xFF, bytes[corner + 1] = 0x3F, bytes[corner + 2] = 0, bytes[corner + 3] = 0;
    }
    ASSERT_LT(bytes.size(), 8192u);
    const std::string why = refusal(bytes, "wide.exr");
    EXPECT_NE(why.find("chunks"), std::string::npos) << why;
}

TEST_F(HostileHeaders, ATinyFileClaimingAHugeImageIsRefusedFromItsHeader) {
    // tiff_huge_alloc.tif's shape: a valid TIFF header claiming hundreds of channels in a few hundred bytes.
    const std::string why = refusal(readBytes(kHostile + "tiff_huge_alloc.tif"), "huge.tif");
    EXPECT_NE(why.find("bytes can hold"), std::string::npos) << why;
}

// A KTX2 of one zstd level: vkFormat, side x side, the frame as its only level, raw the level's bytes.
std::vector<unsigned char> zstdKtx2(uint32_t vkFormat, uint32_t typeSize, uint32_t width, uint32_t height,
                                    const std::vector<unsigned char>& frame, uint64_t raw) {
    std::vector<unsigned char> b = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
    auto put32 = [&](uint32_t v) { for (int i = 0; i < 4; ++i) b.push_back((v >> (8 * i)) & 0xff); };
    auto put64 = [&](uint64_t v) { for (int i = 0; i < 8; ++i) b.push_back((v >> (8 * i)) & 0xff); };
    for (uint32_t v : {vkFormat, typeSize, width, height, 0u, 0u, 1u, 1u, 2u /* zstd */, 0u, 0u, 0u, 0u}) put32(v);
    put64(0);
    put64(0);
    put64(104);  // the level: after the 80-byte header and the 24-byte index
    put64(frame.size());
    put64(raw);
    b.insert(b.end(), frame.begin(), frame.end());
    return b;
}

// `bytes` zero bytes as one zstd frame, streamed (never held whole); its size stated or not.
std::vector<unsigned char> zstdZeros(uint64_t bytes, bool statesSize) {
    ZSTD_CCtx* c = ZSTD_createCCtx();
    if (statesSize) ZSTD_CCtx_setPledgedSrcSize(c, bytes);
    std::vector<unsigned char> zeros(1 << 20, 0), frame(bytes / 1024 + 4096);
    ZSTD_outBuffer out{frame.data(), frame.size(), 0};
    for (uint64_t done = 0; done < bytes;) {
        const size_t n = size_t(std::min<uint64_t>(zeros.size(), bytes - done));
        ZSTD_inBuffer in{zeros.data(), n, 0};
        while (in.pos < in.size) EXPECT_FALSE(ZSTD_isError(ZSTD_compressStream2(c, &out, &in, ZSTD_e_continue)));
        done += n;
    }
    ZSTD_inBuffer end{nullptr, 0, 0};
    // Without a stated size, the frame is flushed and ended with no content size in its header.
    while (ZSTD_compressStream2(c, &out, &end, ZSTD_e_end) != 0) {}
    frame.resize(out.pos);
    ZSTD_freeCCtx(c);
    return frame;
}

long peakResidentKiB() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss;
}

TEST_F(HostileHeaders, AKtx2LevelClaimingMoreThanItsZstandardFrameCanHoldIsRefusedBeforeItIsAllocated) {
    // A 16384^2 RGBA float level (4 GiB) whose zstd frame does not state its size and holds 64 bytes:
    // refused from the header, where the level used to be allocated first.
    std::vector<unsigned char> frame(1024);
    {
        ZSTD_CCtx* c = ZSTD_createCCtx();
        std::vector<unsigned char> raw(64, 7);
        ZSTD_inBuffer in{raw.data(), raw.size(), 0};
        ZSTD_outBuffer out{frame.data(), frame.size(), 0};
        ASSERT_FALSE(ZSTD_isError(ZSTD_compressStream2(c, &out, &in, ZSTD_e_flush)));
        ZSTD_inBuffer none{nullptr, 0, 0};
        ASSERT_EQ(ZSTD_compressStream2(c, &out, &none, ZSTD_e_end), 0u);
        frame.resize(out.pos);
        ZSTD_freeCCtx(c);
    }
    ASSERT_EQ(ZSTD_getFrameContentSize(frame.data(), frame.size()), ZSTD_CONTENTSIZE_UNKNOWN);
    const uint32_t side = 16384;
    writeBytes(dir.file("huge.ktx2"), zstdKtx2(109 /* R32G32B32A32_SFLOAT */, 4, side, side, frame, uint64_t(side) * side * 16));
    auto texture = readGpuTextureFile(dir.file("huge.ktx2"));
    ASSERT_FALSE(texture);
    EXPECT_EQ(texture.error().kind, ErrorKind::BadInput);
    EXPECT_NE(texture.error().what.find("more than its Zstandard frame can hold"), std::string::npos) << texture.error().what;
}

TEST_F(HostileHeaders, AFewKilobytesOfZstandardBlocksNeverDecodeToGigabytesOfFloats) {
    // ASTC 8x8 stores 0.25 bytes a texel and decodes to 4 (a float each), and zeros inflate 32768-fold: a
    // 4 KB frame that honestly holds a 32768 x 16384 level's 128 MiB of blocks would become 2 GiB of floats.
    // Refused from the header (more texels than a height map's load takes), before the frame is inflated;
    // so is the same texels turned on their side in a frame that does not state its size.
    for (const auto& [width, height, statesSize] : {std::tuple{32768u, 16384u, true}, std::tuple{16384u, 32768u, false}}) {
        const uint64_t blocks = uint64_t(width / 8) * (height / 8) * 16;
        const std::vector<unsigned char> frame = zstdZeros(blocks, statesSize);
        EXPECT_LT(frame.size(), blocks / 16384) << "zeros compress to a few bytes a Zstandard block";
        const std::string path = dir.file("astc" + std::to_string(width) + ".ktx2");
        writeBytes(path, zstdKtx2(171 /* ASTC_8x8_UNORM */, 1, width, height, frame, blocks));
        const long before = peakResidentKiB();
        auto texture = readGpuTextureFile(path);
        ASSERT_FALSE(texture) << width;
        EXPECT_EQ(texture.error().kind, ErrorKind::BadInput);
        EXPECT_EQ(texture.error().path, path);
        EXPECT_NE(texture.error().what.find("more than heightpack reads"), std::string::npos) << texture.error().what;
        EXPECT_LT(peakResidentKiB() - before, 64 * 1024) << "the reader allocated the level before refusing it";
    }
}

// The segments a file holds, each as [0xFF, marker, ...] up to the next marker, the scans' coded data
// with the segment it follows: enough to put a segment between a progressive file's scans.
std::vector<size_t> markerOffsetsAfterFirstScan(const std::vector<unsigned char>& b) {
    std::vector<size_t> at;
    bool inScans = false;
    for (size_t i = 2; i + 1 < b.size(); ++i) {
        if (b[i] != 0xFF || b[i + 1] == 0x00 || b[i + 1] == 0xFF || (b[i + 1] >= 0xD0 && b[i + 1] <= 0xD7)) continue;
        if (inScans) at.push_back(i);
        if (b[i + 1] == 0xDA) inScans = true;
        if (b[i + 1] != 0xD9) i += 1 + (size_t(b[i + 2]) << 8 | b[i + 3]);
    }
    return at;
}

std::vector<unsigned char> segment(unsigned char marker, const std::string& payload) {
    std::vector<unsigned char> s = {0xFF, marker, static_cast<unsigned char>((payload.size() + 2) >> 8),
                                    static_cast<unsigned char>(payload.size() + 2)};
    s.insert(s.end(), payload.begin(), payload.end());
    return s;
}

std::vector<float> decodedByOpenImageIO(const std::string& path, int width, int height) {
    auto in = OIIO::ImageInput::open(path);
    std::vector<float> pixels(size_t(width) * height);
    if (!in || !in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, pixels.data())) pixels.clear();
    return pixels;
}

// Dropping a JPEG's metadata segments changes no pixel: heightpack's heights are OpenImageIO's decode of
// the same file, for baseline and progressive JPEGs with EXIF, IPTC and comments as oiiotool and cameras
// write them, and for progressive ones with a comment and an IPTC segment between every two scans (where
// libjpeg saves them for OpenImageIO too: the file that made its IPTC parser overflow again had one there).
TEST_F(HostileHeaders, JpegsLoadTheSamePixelsWithoutTheirMetadata) {
    // A Photoshop resource block holding one IPTC record (2:120, the caption) of 7 bytes, sizes as written.
    static const char kIptc[] = "Photoshop 3.0\0" "8BIM\x04\x04\0\0\0\0\0\x0C" "\x1C\x02\x78\0\x07" "caption";
    const std::string iptc(kIptc, sizeof kIptc - 1);
    int betweenScans = 0;
    for (int progressive : {0, 1}) {
        for (int quality : {50, 95}) {
            const std::string path = dir.file("q" + std::to_string(quality) + "p" + std::to_string(progressive) + ".jpg");
            const Image source = randomImage(48, 40, quality + progressive);
            auto out = OIIO::ImageOutput::create(path);
            OIIO::ImageSpec spec(48, 40, 1, OIIO::TypeDesc::UINT8);
            spec.attribute("CompressionQuality", quality);
            spec.attribute("jpeg:progressive", progressive);
            spec.attribute("ImageDescription", "a comment that becomes a COM segment");
            spec.attribute("Exif:ImageHistory", "an EXIF field in APP1");
            spec.attribute("IPTC:Caption", "an IPTC caption in APP13");
            ASSERT_TRUE(out->open(path, spec));
            ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, source.pixels.data()));
            out->close();
            const std::vector<float> reference = decodedByOpenImageIO(path, 48, 40);
            ASSERT_FALSE(reference.empty()) << path;
            auto loaded = loadHeightMap(path);
            ASSERT_TRUE(loaded) << loaded.error().what;
            EXPECT_EQ(loaded->heights.pixels, reference) << path;
            if (!progressive) continue;

            std::vector<unsigned char> bytes = readBytes(path);
            const std::vector<size_t> offsets = markerOffsetsAfterFirstScan(bytes);
            ASSERT_GE(offsets.size(), 4u) << "a progressive file has several scans";
            std::vector<unsigned char> inserted = segment(0xFE, "a comment between scans");
            const std::vector<unsigned char> app13 = segment(0xED, iptc);
            inserted.insert(inserted.end(), app13.begin(), app13.end());
            for (auto at = offsets.rbegin(); at != offsets.rend(); ++at, ++betweenScans)
                bytes.insert(bytes.begin() + std::ptrdiff_t(*at), inserted.begin(), inserted.end());
            const std::string between = dir.file("between" + std::to_string(quality) + ".jpg");
            writeBytes(between, bytes);
            EXPECT_EQ(decodedByOpenImageIO(between, 48, 40), reference) << "the segments change nothing OpenImageIO decodes";
            auto loadedBetween = loadHeightMap(between);
            ASSERT_TRUE(loadedBetween) << loadedBetween.error().what;
            EXPECT_EQ(loadedBetween->heights.pixels, reference) << between;
        }
    }
    EXPECT_GE(betweenScans, 8);
}

}  // namespace
