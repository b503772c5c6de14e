// What pack decides for an array texture (issue 25) and what `info` reports of it: --pixel-type auto
// judges every layer, not the heights alone; sourceHash covers every channel the file was made from
// (XXH3 of the decoded values, computed here with libxxhash); info names the layers and their channels,
// with statistics equal to the EXR's (OpenImageIO); the bytes do not depend on --threads.
#include <gtest/gtest.h>
#include <xxhash.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/exr_levels.hpp"
#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
using nlohmann::json;

namespace {

json runJson(const std::vector<std::string>& args) {
    const ProcessResult r = heightpackRun(args);
    EXPECT_EQ(r.code, 0) << r.err;
    return r.code == 0 ? json::parse(r.out) : json();
}

// XXH3 of values as 16 hex digits, as docs/formats.md says sourceHash is.
std::string xxh3(const std::vector<float>& values) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx",
                  static_cast<unsigned long long>(XXH3_64bits(values.data(), values.size() * sizeof(float))));
    return text;
}

}  // namespace

// Heights within 1e-3 of 0 fit half or uint16 within 1e-4; Dx of +-100 fit neither (half steps of 1/16
// there, uint16 steps of 200/65535): with Dx, auto must fall back to float, in every container.
TEST(ArrayChoices, AutoPixelTypeJudgesEveryLayer) {
    ScratchDir dir;
    const Image y = randomImage(16, 16, 3, 0.0f, 1e-3f), dx = randomImage(16, 16, 4, -100.0f, 100.0f);
    const Image dy = randomImage(16, 16, 5, -1e-3f, 1e-3f);
    writeChannels(dir.file("sea.exr"), {"Y", "Dx", "Dy"}, {&y, &dx, &dy});
    for (const char* ext : {".ktx2", ".dds", ".exr"}) {
        SCOPED_TRACE(ext);
        const auto packJson = [&](const std::string& name, bool displacement) {
            std::vector<std::string> args = {"pack", dir.file("sea.exr"), "--pixel-type", "auto", "--tolerance", "1e-4",
                                             "--json", "-o", dir.file(name + ext)};
            if (displacement) args.push_back("--shift");
            return runJson(args);
        };
        const json heights = packJson("heights", false), whole = packJson("whole", true);
        EXPECT_NE(heights["pixelType"], "float") << heights.dump();
        EXPECT_EQ(whole["pixelType"], "float") << whole.dump();
        // What info reads back: the array's texel format is float too.
        const json info = runJson({"info", dir.file(std::string("whole") + ext), "--json"});
        EXPECT_EQ(info["pixelType"], "float");
    }
    // A tolerance Dx's halves meet (|Dx| < 128: half steps of 1/16, errors below 1/32): two bytes again.
    const json half = runJson({"pack", dir.file("sea.exr"), "--shift", "--pixel-type", "auto", "--tolerance", "0.04",
                               "--json", "-o", dir.file("half.ktx2")});
    EXPECT_NE(half["pixelType"], "float") << half.dump();
}

// sourceHash: of the heights alone without companions; of the heights, then Dx and Dy interleaved, then
// the foam, with them, so a change to Dx alone changes it.
TEST(ArrayChoices, SourceHashCoversEveryChannel) {
    ScratchDir dir;
    const Image y = randomImage(16, 8, 11), dx = randomImage(16, 8, 12, -1.0f, 1.0f), dy = randomImage(16, 8, 13, -1.0f, 1.0f);
    const Image foam = randomImage(16, 8, 14);
    Image dx2 = dx;
    dx2.pixels[5] += 0.25f;
    writeChannels(dir.file("a.exr"), {"Y", "Dx", "Dy", "Foam"}, {&y, &dx, &dy, &foam});
    writeChannels(dir.file("b.exr"), {"Y", "Dx", "Dy", "Foam"}, {&y, &dx2, &dy, &foam});
    const auto hashOf = [&](const std::string& input, const std::string& output, std::vector<std::string> extra) {
        std::vector<std::string> args = {"pack", dir.file(input), "-o", dir.file(output), "-q"};
        args.insert(args.end(), extra.begin(), extra.end());
        EXPECT_EQ(heightpackRun(args).code, 0) << output;
        return runJson({"info", dir.file(output), "--json"})["attributes"].value("heightpack:sourceHash", "");
    };
    std::vector<float> heights = y.pixels, all = y.pixels;
    for (size_t i = 0; i < dx.texelCount(); ++i) all.insert(all.end(), {dx.pixels[i], dy.pixels[i]});
    all.insert(all.end(), foam.pixels.begin(), foam.pixels.end());
    EXPECT_EQ(hashOf("a.exr", "alone.ktx2", {}), xxh3(heights));
    const std::string whole = hashOf("a.exr", "whole.ktx2", {"--shift", "--foam"});
    EXPECT_EQ(whole, xxh3(all));
    EXPECT_EQ(hashOf("a.exr", "whole.exr", {"--shift", "--foam"}), whole) << "every container records the same hash";
    EXPECT_NE(hashOf("b.exr", "changed.ktx2", {"--shift", "--foam"}), whole) << "Dx changed alone";
}

// info reads an array back: its layers, its sixteen channels named as the EXR's, per level statistics
// equal to the EXR's channels, and the bytes every layer takes on the GPU.
TEST(ArrayChoices, InfoReportsTheLayers) {
    ScratchDir dir;
    const Image y = randomImage(32, 16, 21), dx = randomImage(32, 16, 22, -1.0f, 1.0f), dy = randomImage(32, 16, 23, -1.0f, 1.0f);
    const Image foam = randomImage(32, 16, 24);
    writeChannels(dir.file("sea.exr"), {"Y", "Dx", "Dy", "Foam"}, {&y, &dx, &dy, &foam});
    ASSERT_EQ(heightpackRun({"pack", dir.file("sea.exr"), "--shift", "--foam", "-q", "-o", dir.file("p.exr")}).code, 0);
    const std::vector<Level> exr = readLevels(dir.file("p.exr"));
    for (const char* out : {"p.ktx2", "p.dds"}) {
        SCOPED_TRACE(out);
        const json packed = runJson({"pack", dir.file("sea.exr"), "--shift", "--foam", "--json", "-o", dir.file(out)});
        const json info = runJson({"info", dir.file(out), "--json"});
        EXPECT_EQ(packed["gpuBytes"], info["gpuBytes"]) << "pack and info count every layer";
        EXPECT_EQ(info["layers"], json({"heights", "Dx", "Dy", "Foam"}));
        EXPECT_EQ(info["channels"], json(exr[0].names));
        EXPECT_EQ(info["attributes"]["heightpack:layers"], "heights,Dx,Dy,Foam");
        EXPECT_EQ(info["attributes"]["heightpack:displacement"], "neighbour4");
        EXPECT_EQ(info["attributes"]["heightpack:foam"], "neighbour4");
        ASSERT_EQ(info["levels"].size(), exr.size());
        size_t gpuBytes = 0;
        for (size_t level = 0; level < exr.size(); ++level) {
            const json& l = info["levels"][level];
            EXPECT_EQ(l["gpuBytes"], size_t(exr[level].width) * exr[level].height * 4 * 16) << "four RGBA32F layers";
            gpuBytes += l["gpuBytes"].get<size_t>();
            for (size_t c = 0; c < exr[level].names.size(); ++c) {
                const std::string& name = exr[level].names[c];
                double lo = INFINITY, hi = -INFINITY;
                for (size_t i = c; i < exr[level].pixels.size(); i += exr[level].names.size())
                    lo = std::min<double>(lo, exr[level].pixels[i]), hi = std::max<double>(hi, exr[level].pixels[i]);
                EXPECT_EQ(l["channels"][c]["name"], name);
                EXPECT_EQ(l["channels"][c]["min"].get<double>(), lo) << name << " level " << level;
                EXPECT_EQ(l["channels"][c]["max"].get<double>(), hi) << name << " level " << level;
            }
        }
        EXPECT_EQ(info["gpuBytes"], gpuBytes);
        const ProcessResult text = heightpackRun({"info", dir.file(out)});
        EXPECT_NE(text.out.find("an array of 4 layers: heights, Dx, Dy, Foam"), std::string::npos) << text.out;
    }
}

// The same array, byte for byte, whatever --threads (zstd KTX2 and DDS; bands of 64 rows, two of them).
TEST(ArrayChoices, SameBytesWhateverTheThreadCount) {
    ScratchDir dir;
    const Image y = randomImage(64, 128, 31), dx = randomImage(64, 128, 32, -1.0f, 1.0f), foam = randomImage(64, 128, 33);
    writeChannels(dir.file("sea.exr"), {"Y", "Dx", "Dy", "Foam"}, {&y, &dx, &dx, &foam});
    for (const char* ext : {".ktx2", ".dds"}) {
        std::vector<std::vector<unsigned char>> files;
        for (const char* threads : {"1", "3"}) {
            const std::string out = dir.file(std::string("t") + threads + ext);
            std::vector<std::string> args = {"pack", dir.file("sea.exr"), "--shift", "--foam", "--pixel-type", "uint16",
                                             "--threads", threads, "-q", "-o", out};
            if (std::string(ext) == ".ktx2") args.insert(args.end(), {"--compression", "zstd"});
            ASSERT_EQ(heightpackRun(args).code, 0) << out;
            files.push_back(readBytes(out));
        }
        EXPECT_TRUE(files[0] == files[1]) << ext;
    }
}
