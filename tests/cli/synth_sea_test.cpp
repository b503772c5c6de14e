// synth's sea states end to end (issue 15): the report against the files read back, foam, cascades,
// thread-count independence, and the usage errors of the new options.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "support/spectral_derivative.hpp"
#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

using CliRun = ProcessResult;

struct Channels {
    int size = 0;
    std::vector<std::string> names;
    std::vector<float> pixels;  // interleaved
    OIIO::ImageSpec spec;
    float at(int x, int y, int c) const { return pixels[(size_t(y) * size + x) * names.size() + c]; }
};

Channels readExr(const std::string& path) {
    Channels out;
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    if (!in) return out;
    out.spec = in->spec();
    out.size = out.spec.width;
    out.names = out.spec.channelnames;
    out.pixels.resize(size_t(out.size) * out.size * out.names.size());
    EXPECT_TRUE(in->read_image(0, 0, 0, -1, OIIO::TypeDesc::FLOAT, out.pixels.data()));
    return out;
}

int channel(const Channels& c, const char* name) {
    const auto it = std::find(c.names.begin(), c.names.end(), name);
    return it == c.names.end() ? -1 : int(it - c.names.begin());
}

// d/dx (axis 0) or d/dy (axis 1) of one channel, by the test's own DFT.
cv::Mat derivative(const Channels& c, int ch, int axis, double tileSize) {
    return spectralDerivative([&](int x, int y) { return c.at(x, y, ch); }, c.size, axis, tileSize);
}

const std::vector<std::string> kSea = {"synth", "--spectrum", "jonswap", "--wind", "20m/s", "--fetch", "300km",
                                       "--swell", "1.5m,11s,200deg", "--depth", "40m", "--spreading", "donelan-banner",
                                       "--tile-size", "128m", "--size", "64", "--loop", "10s", "--frames", "4",
                                       "--choppiness", "4"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

}  // namespace

TEST(SynthSea, TheReportIsWhatTheFilesHold) {
    ScratchDir dir;
    const CliRun run = heightpackRun(with(kSea, {"--foam", "--json", "-o", dir.file("sea.exr")}));
    ASSERT_EQ(run.code, 0) << run.err;
    const auto j = nlohmann::json::parse(run.out);
    const auto& report = j["report"];
    const double lambda = 4.0, tile = 128.0;
    double folds = 0, texels = 0, moved = 0;
    for (int f = 0; f < 4; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "sea.%04d.exr", f);
        const Channels c = readExr(dir.file(name));
        ASSERT_EQ(c.names.size(), 4u) << name;
        const int y = channel(c, "Y"), dx = channel(c, "Dx"), dy = channel(c, "Dy"), foam = channel(c, "Foam");
        ASSERT_TRUE(y >= 0 && dx >= 0 && dy >= 0 && foam >= 0) << name;
        if (f == 0) {
            double sum = 0, sq = 0;
            const double n = double(c.size) * c.size;
            for (int t = 0; t < c.size * c.size; ++t) sum += c.pixels[t * 4 + y];
            for (int t = 0; t < c.size * c.size; ++t) sq += std::pow(c.pixels[t * 4 + y] - sum / n, 2);
            EXPECT_NEAR(report["significantWaveHeight"].get<double>(), 4 * std::sqrt(sq / n), 1e-4);
        }
        const cv::Mat xx = derivative(c, dx, 0, tile), yy = derivative(c, dy, 1, tile), xy = derivative(c, dx, 1, tile);
        for (int py = 0; py < c.size; ++py)
            for (int px = 0; px < c.size; ++px) {
                const double jac = (1 + lambda * xx.at<double>(py, px)) * (1 + lambda * yy.at<double>(py, px)) -
                                   lambda * lambda * std::pow(xy.at<double>(py, px), 2);
                folds += jac < 0, texels += 1;
                moved = std::max(moved, lambda * std::hypot(c.at(px, py, dx), c.at(px, py, dy)));
                const float cover = c.at(px, py, foam);
                ASSERT_TRUE(cover >= 0.0f && cover < 1.0f) << cover;
            }
        // The header carries the same numbers as the JSON.
        EXPECT_FLOAT_EQ(c.spec.get_float_attribute("heightpack:foldFraction"), report["foldFraction"].get<float>());
        EXPECT_FLOAT_EQ(c.spec.get_float_attribute("heightpack:significantWaveHeight"), report["significantWaveHeight"].get<float>());
        EXPECT_FLOAT_EQ(c.spec.get_float_attribute("heightpack:peakPeriod"), report["peakPeriod"].get<float>());
        EXPECT_FLOAT_EQ(c.spec.get_float_attribute("heightpack:displacementBound"), report["displacementBound"].get<float>());
        EXPECT_EQ(c.spec.get_string_attribute("heightpack:spreading"), "donelan-banner");
    }
    // A sea that folds somewhere, counted alike (a texel whose J is within rounding of 0 may differ).
    EXPECT_GT(folds, 0);
    EXPECT_NEAR(report["foldFraction"].get<double>(), folds / texels, 3.0 / texels);
    EXPECT_NEAR(report["maxDisplacement"].get<double>(), moved, 1e-4 * moved);
    EXPECT_GE(report["displacementBound"].get<double>(), moved);
    // Steepness is Hs over the peak wavelength at this depth (40 m: w^2 = g k tanh(k d)).
    const double tp = report["peakPeriod"].get<double>(), w = 2 * std::numbers::pi / tp;
    double k = w * w / 9.81;
    for (int i = 0; i < 100; ++i) k = w * w / (9.81 * std::tanh(k * 40.0));
    EXPECT_NEAR(report["peakWavelength"].get<double>(), 2 * std::numbers::pi / k, 1e-3 * 2 * std::numbers::pi / k);
    EXPECT_NEAR(report["steepness"].get<double>(),
                report["expectedSignificantWaveHeight"].get<double>() / report["peakWavelength"].get<double>(), 1e-9);
}

TEST(SynthSea, SameBytesWhateverTheThreadCount) {
    ScratchDir dir;
    for (const char* threads : {"1", "3"}) {
        const CliRun run = heightpackRun(with(kSea, {"--foam", "--cascades", "2", "--threads", threads, "-q", "-o",
                                                     dir.file(std::string("t") + threads + ".exr")}));
        ASSERT_EQ(run.code, 0) << run.err;
    }
    for (const char* c : {"_c0", "_c1"})
        for (const char* f : {".0000", ".0003"})
            EXPECT_EQ(readBytes(dir.file(std::string("t1") + c + f + ".exr")), readBytes(dir.file(std::string("t3") + c + f + ".exr")))
                << c << f;
}

TEST(SynthSea, WritesUncompressedByDefaultAndZipOrZipsWhenAsked) {
    // Float heights and displacement are noise that deflate barely shrinks: none is the default, and zip
    // or zips hold the very same floats.
    ScratchDir dir;
    const std::vector<std::string> sea = {"synth", "--spectrum", "jonswap", "--wind", "12m/s", "--tile-size", "128m",
                                          "--size", "64", "--foam", "-q", "-o"};
    std::vector<Channels> read;
    for (const char* compression : {"", "zip", "zips"}) {
        std::vector<std::string> args = with(sea, {dir.file(std::string("c") + compression + ".exr")});
        if (*compression) args.insert(args.end(), {"--compression", compression});
        const CliRun run = heightpackRun(args);
        ASSERT_EQ(run.code, 0) << run.err;
        read.push_back(readExr(dir.file(std::string("c") + compression + ".exr")));
        EXPECT_EQ(read.back().spec.get_string_attribute("compression"), *compression ? compression : "none");
        EXPECT_EQ(read.back().pixels, read.front().pixels) << compression;
    }
    EXPECT_EQ(heightpackRun(with(sea, {dir.file("bad.exr"), "--compression", "piz"})).code, 2);
}

TEST(SynthSea, CascadesAreNamedAndCarryTheirBands) {
    ScratchDir dir;
    const CliRun run = heightpackRun({"synth", "--spectrum", "pierson-moskowitz", "--wind", "9m/s", "--tile-size", "512m",
                                      "--size", "32", "--cascades", "3", "--json", "-o", dir.file("sea.png")});
    ASSERT_EQ(run.code, 0) << run.err;
    const auto j = nlohmann::json::parse(run.out);
    ASSERT_EQ(j["cascades"].size(), 3u);
    double previousHigh = 0.0, variance = 0.0;
    for (int c = 0; c < 3; ++c) {
        const auto& t = j["cascades"][c];
        EXPECT_EQ(t["outputs"][0], dir.file("sea_c" + std::to_string(c) + ".png"));
        EXPECT_DOUBLE_EQ(t["bandLow"].get<double>(), previousHigh);
        EXPECT_NEAR(t["tileSize"].get<double>(), 512.0 * std::pow(17.0 / 61.0, c), 1e-9);
        previousHigh = t["bandHigh"].get<double>();
        variance += std::pow(t["significantWaveHeight"].get<double>(), 2);
        auto in = OIIO::ImageInput::open(dir.file("sea_c" + std::to_string(c) + ".png"));
        ASSERT_TRUE(in);
        EXPECT_EQ(in->spec().get_string_attribute("heightpack:cascade"), std::to_string(c) + "/3");
    }
    EXPECT_NEAR(j["significantWaveHeight"].get<double>(), std::sqrt(variance), 1e-9);
    EXPECT_FALSE(std::filesystem::exists(dir.file("sea.png")));
}

TEST(SynthSea, RefusesBadSeaStatesBeforeWritingAnything) {
    // The rules this command adds (CLI11's own range and choice checks are the sweep's business).
    ScratchDir dir;
    const std::string out = dir.file("s.exr");
    const std::vector<std::string> base = {"synth", "--wind", "10m/s", "--tile-size", "64m", "--size", "32"};
    const std::vector<std::vector<std::string>> bad = {
        with(base, {"--foam", "-o", dir.file("s.png")}),
        with(base, {"--swell", "2.5m,12s", "-o", out}),
        with(base, {"--spreading-s", "20", "-o", out}),
        with(base, {"--depth", "0m", "-o", out}),
        with(base, {"--cascades", "5", "-o", out}),
        {"synth", "--wind", "10m/s", "--tile-size", "64m", "--size", "16", "--cascades", "2", "-o", out},
    };
    for (const auto& args : bad) {
        const CliRun run = heightpackRun(args);
        EXPECT_EQ(run.code, 2) << run.err;
        EXPECT_EQ(run.err.rfind("heightpack: error: ", 0), 0u) << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}
