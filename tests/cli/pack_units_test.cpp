// pack keeps what its source records of the world (issue 35, item 1): a synthesised sea's tile size, the
// metres of its heights and its loop period, in every container pack writes, so the viewer (and an
// engine) can take them from the packed file. Each header is read as its format defines it: OpenImageIO
// for EXR, KTX2's key/value data and heightpack's DDS record (docs/formats.md, "GPU containers") decoded from the
// bytes here, not through heightpack's readers.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <string>

#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

// What a file records of the world, as far as its container can say it.
struct Recorded {
    std::optional<double> tileWidth, heightRange, loopPeriod, time;
};

std::optional<double> number(const std::map<std::string, std::string>& values, const std::string& key) {
    const auto it = values.find(key);
    if (it == values.end()) return std::nullopt;
    return std::stod(it->second);
}

Recorded fromExr(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    Recorded r;
    if (!in) return r;
    auto get = [&](const char* name) -> std::optional<double> {
        const OIIO::ParamValue* p = in->spec().find_attribute(name);
        if (!p) return std::nullopt;
        EXPECT_EQ(p->type(), OIIO::TypeFloat) << name;
        return p->get_float();
    };
    r.tileWidth = get("heightpack:tileWidth");
    r.heightRange = get("heightpack:heightRange");
    r.loopPeriod = get("heightpack:loopPeriod");
    r.time = get("heightpack:time");
    return r;
}

// KTX 2.0: kvdByteOffset and kvdByteLength at bytes 56 and 60 of the header; each entry its byte length,
// then the key, NUL, the value (NUL-terminated text here), padded to four bytes.
Recorded fromKtx2(const std::string& path) {
    const std::vector<unsigned char> b = readBytes(path);
    std::map<std::string, std::string> values;
    const size_t offset = le32(b, 56), end = offset + le32(b, 60);
    for (size_t at = offset; at + 4 <= end;) {
        const size_t n = le32(b, at);
        const std::string entry(reinterpret_cast<const char*>(b.data() + at + 4), n);
        const size_t nul = entry.find('\0');
        values[entry.substr(0, nul)] = entry.substr(nul + 1, n - nul - 2);
        at += 4 + (n + 3) / 4 * 4;
    }
    return {number(values, "heightpack:tileWidth"), number(values, "heightpack:heightRange"),
            number(values, "heightpack:loopPeriod"), number(values, "heightpack:time")};
}

// DDS: after the magic, DDS_HEADER word i at byte 4 + 4i. heightpack's record in dwReserved1 (words 7..):
// 'HPCK', version 1, ..., flags in its word 6; bits 4, 5, 6 flag the tile width in dwCaps3 (word 28), the
// height range in dwCaps4 (word 29) and the loop period in dwReserved2 (word 30), as floats.
Recorded fromDds(const std::string& path) {
    const std::vector<unsigned char> b = readBytes(path);
    Recorded r;
    EXPECT_EQ(le32(b, 4 + 4 * 7), 0x4b435048u) << path << ": 'HPCK'";
    EXPECT_EQ(le32(b, 4 + 4 * 8), 1u) << path;
    const std::uint32_t flags = le32(b, 4 + 4 * 13);
    auto word = [&](std::uint32_t flag, int w) { return flags & flag ? std::optional<double>(leFloat(b, 4 + 4 * w)) : std::nullopt; };
    r.tileWidth = word(16, 28);
    r.heightRange = word(32, 29);
    r.loopPeriod = word(64, 30);
    return r;
}

Recorded recordedIn(const std::string& path) {
    const std::string ext = std::filesystem::path(path).extension().string();
    return ext == ".exr" ? fromExr(path) : ext == ".ktx2" ? fromKtx2(path) : fromDds(path);
}

}  // namespace

TEST(PackUnits, EveryContainerKeepsTheSeasTileSizeMetresAndLoop) {
    // Two frames of an 8 s loop of a 256 m sea, heights in metres (a float EXR: heightScale 1).
    ScratchDir dir;
    const ProcessResult synth = heightpackRun({"synth", "--spectrum", "jonswap", "--wind", "12m/s", "--tile-size", "256m",
                                               "--size", "32", "--frames", "2", "--loop", "8s", "-q", "-o", dir.file("sea.exr")});
    ASSERT_EQ(synth.code, 0) << synth.err;
    for (const std::string ext : {".exr", ".ktx2", ".dds"}) {
        // As packed: a stored unit is a metre. Scaled by 0.5: a stored unit is 2 m. --height says it outright.
        for (const auto& [extra, metres] : {std::pair<std::vector<std::string>, double>{{}, 1.0},
                                            {{"--scale", "0.5"}, 2.0},
                                            {{"--height", "3m"}, 3.0}}) {
            std::vector<std::string> args = {"pack", dir.file("sea.exr"), "-q", "-o", dir.file("p" + ext)};
            args.insert(args.end(), extra.begin(), extra.end());
            const ProcessResult packed = heightpackRun(args);
            ASSERT_EQ(packed.code, 0) << packed.err;
            const std::string frame = dir.file("p.0001" + ext);
            const Recorded r = recordedIn(frame);
            ASSERT_TRUE(r.tileWidth && r.heightRange && r.loopPeriod) << frame;
            EXPECT_EQ(*r.tileWidth, 256.0) << frame;
            EXPECT_EQ(*r.heightRange, metres) << frame << (extra.empty() ? "" : " " + extra[0]);
            EXPECT_EQ(*r.loopPeriod, 8.0) << frame;
            if (ext != ".dds") {  // a DDS has no room for a frame's time; its place in the sequence says it
                ASSERT_TRUE(r.time) << frame;
                EXPECT_EQ(*r.time, 4.0) << frame << ": the second of two frames of 8 s";
            }
        }
    }
}

TEST(PackUnits, AnIntegerSeaKeepsItsMetresAndAPaintedMapClaimsNone) {
    // synth's PNG holds the heights mapped onto [0, 1]: metres = heightOffset + heightScale * value.
    ScratchDir dir;
    ASSERT_EQ(heightpackRun({"synth", "--wind", "9m/s", "--tile-size", "48m", "--size", "32", "-q", "-o", dir.file("sea.png")}).code, 0);
    auto in = OIIO::ImageInput::open(dir.file("sea.png"));
    ASSERT_TRUE(in);
    const double heightScale = std::stod(in->spec().get_string_attribute("heightpack:heightScale"));
    in.reset();
    ASSERT_GT(heightScale, 0.1);
    // Painted: no units at all, so none are claimed.
    writeImage(dir.file("painted.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT16);
    for (const std::string ext : {".exr", ".ktx2", ".dds"}) {
        ASSERT_EQ(heightpackRun({"pack", dir.file("sea.png"), "--scale", "2", "-q", "-o", dir.file("sea" + ext)}).code, 0);
        const Recorded sea = recordedIn(dir.file("sea" + ext));
        ASSERT_TRUE(sea.tileWidth && sea.heightRange) << ext;
        EXPECT_EQ(*sea.tileWidth, 48.0) << ext;
        EXPECT_NEAR(*sea.heightRange, heightScale / 2, 1e-6 * heightScale) << ext << ": stored = 2 x value";
        ASSERT_EQ(heightpackRun({"pack", dir.file("painted.png"), "-q", "-o", dir.file("painted" + ext)}).code, 0);
        const Recorded painted = recordedIn(dir.file("painted" + ext));
        EXPECT_FALSE(painted.tileWidth || painted.heightRange || painted.loopPeriod) << ext;
    }
}
