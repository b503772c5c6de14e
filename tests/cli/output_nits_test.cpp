// What a person notices in the text the commands print (issue 35, item 11): numbers without a signed
// zero, an echo never below 0, columns that line up under their headings whatever the status, one line
// for a sequence, the channels as written, and recorded numbers in their shortest exact form.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

std::vector<std::string> linesOf(const std::string& text) {
    std::istringstream in(text);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

// The words of a line with the column just past each one's last letter.
std::vector<std::pair<std::string, size_t>> wordsWithEnds(const std::string& line) {
    std::vector<std::pair<std::string, size_t>> words;
    for (size_t i = 0; i < line.size();) {
        if (line[i] == ' ') {
            ++i;
            continue;
        }
        const size_t start = i;
        while (i < line.size() && line[i] != ' ') ++i;
        words.emplace_back(line.substr(start, i - start), i);
    }
    return words;
}

// A number printed as a person reads it: a rounded zero carries no sign.
void expectNoSignedZero(const std::string& word, const std::string& where) {
    if (word.empty() || word[0] != '-') return;
    EXPECT_NE(std::strtod(word.c_str(), nullptr), 0.0) << "'" << word << "' in: " << where;
}

nlohmann::json jsonRun(const std::vector<std::string>& args) {
    const ProcessResult run = heightpackRun(args);
    EXPECT_TRUE(run.code == 0 || run.code == 1) << run.err;
    return run.out.empty() ? nlohmann::json::object() : nlohmann::json::parse(run.out);
}

std::string example(const std::string& name) { return std::string(HEIGHTPACK_SOURCE_DIR) + "/examples/maps/" + name; }

}  // namespace

// check's table: every score ends in the column its heading ("value", "slope") ends in, "(too small)"
// spans both, FAIL follows a failing pair, and each score is --json's rounded, never "-0.0".
TEST(OutputNits, CheckScoresLineUpUnderTheirHeadingsWithoutSignedZeros) {
    for (const std::string& map : {example("ripple.png"), example("painted_not_tileable.png"), example("swell.png")}) {
        SCOPED_TRACE(map);
        const ProcessResult text = heightpackRun({"check", map});
        ASSERT_TRUE(text.code == 0 || text.code == 1) << text.err;
        const nlohmann::json j = jsonRun({"check", map, "--json"});
        const std::vector<std::string> lines = linesOf(text.out);
        ASSERT_GT(lines.size(), 2u);
        const std::string& heading = lines[1];
        ASSERT_NE(heading.find("level"), std::string::npos) << text.out;
        std::vector<size_t> valueEnds, slopeEnds;
        for (const auto& [word, end] : wordsWithEnds(heading)) {
            if (word == "value") valueEnds.push_back(end);
            if (word == "slope") slopeEnds.push_back(end);
        }
        ASSERT_EQ(valueEnds.size(), 2u) << heading;
        ASSERT_EQ(slopeEnds.size(), 2u) << heading;
        const nlohmann::json& levels = j["levels"];
        ASSERT_LE(levels.size() + 2, lines.size());
        for (size_t i = 0; i < levels.size(); ++i) {
            const std::string& row = lines[2 + i];
            auto words = wordsWithEnds(row);
            ASSERT_GE(words.size(), 4u) << row;
            EXPECT_EQ(words[0].first, std::to_string(i)) << row;
            words.erase(words.begin(), words.begin() + 2);  // level, size
            size_t at = 0;
            for (int edge = 0; edge < 2; ++edge) {
                const nlohmann::json& score = levels[i][edge == 0 ? "leftRight" : "topBottom"];
                ASSERT_LT(at, words.size()) << row;
                if (!score["measured"].get<bool>()) {
                    ASSERT_LT(at + 1, words.size()) << row;
                    EXPECT_EQ(words[at].first + " " + words[at + 1].first, "(too small)") << row;
                    EXPECT_EQ(words[at + 1].second, slopeEnds[edge]) << row;
                    at += 2;
                    continue;
                }
                ASSERT_LT(at + 1, words.size()) << row;
                const std::pair<std::string, size_t> shown[2] = {words[at], words[at + 1]};
                const char* names[2] = {"value", "slope"};
                for (int k = 0; k < 2; ++k) {
                    EXPECT_EQ(shown[k].second, (k == 0 ? valueEnds : slopeEnds)[edge]) << names[k] << " in: " << row;
                    expectNoSignedZero(shown[k].first, row);
                    const nlohmann::json& exact = score[names[k]];
                    if (!exact.is_number()) continue;  // "inf"
                    const size_t point = shown[k].first.find('.');
                    const int decimals = point == std::string::npos ? 0 : int(shown[k].first.size() - point - 1);
                    EXPECT_NEAR(std::strtod(shown[k].first.c_str(), nullptr), exact.get<double>(),
                                0.5 * std::pow(10.0, -decimals) + 1e-12)
                        << row;
                }
                at += 2;
                const bool fails = !score["pass"].get<bool>();
                EXPECT_EQ(at < words.size() && words[at].first == "FAIL", fails) << row;
                if (fails) ++at;
            }
            EXPECT_EQ(at, words.size()) << row;
        }
    }
}

// An echo is what a tile adds to its source's: never below 0, in --json and in the text; and --force on a
// map that tiles names no seam it does not have.
TEST(OutputNits, TileEchoIsNeverNegative) {
    ScratchDir dir;
    // ripple tiles already, and echoes itself a little: --force re-synthesises its bands, which echo less.
    const nlohmann::json j = jsonRun({"tile", example("ripple.png"), "--force", "-o", dir.file("t.png"), "--json"});
    ASSERT_TRUE(j["look"]["measured"].get<bool>());
    EXPECT_GT(j["look"]["echoBaseline"].get<double>(), 0.0);
    EXPECT_GE(j["look"]["echo"].get<double>(), 0.0);
    const ProcessResult text = heightpackRun({"tile", example("ripple.png"), "--force", "-o", dir.file("u.png")});
    ASSERT_EQ(text.code, 0) << text.err;
    const size_t echo = text.out.find("echo ");
    ASSERT_NE(echo, std::string::npos) << text.out;
    const std::string figure = text.out.substr(echo + 5, text.out.find_first_of(" ,(", echo + 5) - echo - 5);
    EXPECT_EQ(figure.find('-'), std::string::npos) << text.out;
    EXPECT_GE(std::strtod(figure.c_str(), nullptr), 0.0) << text.out;
    EXPECT_EQ(text.out.find("level -"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("tiles at every level; --force applies periodic anyway"), std::string::npos) << text.out;
}

// build's status column is as wide as its widest status: an output's name starts in the same column
// whether it was rebuilt, restored from the cache or up to date.
TEST(OutputNits, BuildColumnsHoldEveryStatus) {
    ScratchDir dir;
    const std::string manifest = std::string(HEIGHTPACK_SOURCE_DIR) + "/examples/ocean.toml";
    const std::string cache = dir.file("cache");
    std::map<std::string, std::vector<size_t>> fileColumns;  // status -> where the output's name starts
    for (const char* out : {"first", "second", "second"}) {
        const ProcessResult run = heightpackRun({"build", manifest, "-o", dir.file(out), "--cache", cache});
        ASSERT_EQ(run.code, 0) << run.err;
        for (const std::string& line : linesOf(run.out)) {
            const size_t exr = line.find(".exr ");
            if (line.rfind("  ", 0) != 0 || exr == std::string::npos) continue;
            const size_t start = line.rfind(' ', exr) + 1;
            fileColumns[line.substr(2, line.find_last_not_of(' ', start - 1) - 1)].push_back(start);
        }
    }
    for (const char* status : {"rebuilt", "restored from cache", "up to date"})
        EXPECT_EQ(fileColumns[status].size(), 4u) << status << ": the example has four outputs";
    std::set<size_t> columns;
    for (const auto& [status, starts] : fileColumns) columns.insert(starts.begin(), starts.end());
    EXPECT_EQ(columns.size(), 1u) << "the outputs' names start in " << columns.size() << " different columns";
}

// pack over a sequence says one line, as synth does: the first and last outputs and the count.
TEST(OutputNits, PackOverASequenceSaysOneLine) {
    ScratchDir dir;
    const int frames = 6;
    for (int f = 0; f < frames; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "sea.%04d.png", f);
        writeImage(dir.file(name), makeImage(16, 16, [f](int x, int y) { return smoothWave(x + f, y); }), OIIO::TypeDesc::UINT8);
    }
    const ProcessResult pack = heightpackRun({"pack", dir.file("sea.####.png"), "-o", dir.file("p.exr")});
    ASSERT_EQ(pack.code, 0) << pack.err;
    const std::vector<std::string> lines = linesOf(pack.out);
    ASSERT_EQ(lines.size(), 1u) << pack.out;
    EXPECT_EQ(lines[0].rfind("wrote " + dir.file("p.0000.exr") + " .. " + dir.file("p.0005.exr") + ": 6 frames, ", 0), 0u)
        << lines[0];
    for (int f = 0; f < frames; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "p.%04d.exr", f);
        EXPECT_TRUE(std::filesystem::exists(dir.file(name))) << name;
    }
    const ProcessResult synth = heightpackRun({"synth", "--wind", "8", "--tile-size", "16m", "--size", "16", "--frames", "6",
                                               "--loop", "4s", "-o", dir.file("s.exr")});
    ASSERT_EQ(synth.code, 0) << synth.err;
    EXPECT_EQ(linesOf(synth.out).size(), 1u) << synth.out;
    // With the plain twins: a line for each set.
    const ProcessResult twins =
        heightpackRun({"pack", dir.file("sea.####.png"), "--emit-plain", dir.file("plain.exr"), "-o", dir.file("q.exr")});
    ASSERT_EQ(twins.code, 0) << twins.err;
    ASSERT_EQ(linesOf(twins.out).size(), 2u) << twins.out;
    EXPECT_NE(twins.out.find("wrote " + dir.file("plain.0000.exr") + " .. " + dir.file("plain.0005.exr")),
              std::string::npos)
        << twins.out;
}

// normal names the channels it wrote: as many letters (rgb, rgba, xy) as the file has channels.
TEST(OutputNits, NormalNamesTheChannelsWritten) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(32, 32, smoothWave), OIIO::TypeDesc::UINT8);
    const std::vector<std::vector<std::string>> cases = {
        {"-o", dir.file("rgb.exr")},
        {"--height-in-alpha", "-o", dir.file("height.exr")},
        {"--variance-in-alpha", "-o", dir.file("variance.exr")},
        {"--layout", "xy", "-o", dir.file("xy.exr")},
        {"--height-in-alpha", "-o", dir.file("height.png")},
    };
    for (const auto& extra : cases) {
        std::vector<std::string> args = {"normal", dir.file("map.png"), "--tile-size", "8m", "--height", "0.2m"};
        args.insert(args.end(), extra.begin(), extra.end());
        const ProcessResult run = heightpackRun(args);
        ASSERT_EQ(run.code, 0) << run.err;
        const size_t deg = run.out.find(" deg, ");
        ASSERT_NE(deg, std::string::npos) << run.out;
        const std::string word = run.out.substr(deg + 6, run.out.find_first_of(" ,", deg + 6) - deg - 6);
        const nlohmann::json info = jsonRun({"info", extra.back(), "--json"});
        EXPECT_EQ(word.size(), info["channels"].size()) << run.out;
        EXPECT_EQ(word == "rgba", run.out.find(" in alpha)") != std::string::npos) << run.out;
    }
}

// A number a file records as text (KTX2 key/values, PNG text) is the shortest that reads back as the
// same float: "1.333", not "1.33299994".
TEST(OutputNits, RecordedNumbersAreTheShortestExactText) {
    ScratchDir dir;
    auto shortest = [](float v) {
        char text[32];
        for (int digits = 1; digits <= 9; ++digits) {
            std::snprintf(text, sizeof text, "%.*g", digits, double(v));
            if (std::strtof(text, nullptr) == v) break;
        }
        return std::string(text);
    };
    for (const double ior : {1.333, 2.4177, 1.0001})
        for (const char* ext : {".png", ".ktx2"}) {  // a PNG's text chunks, a KTX2's key/values
            const std::string path = dir.file("f" + std::to_string(ior) + ext);
            ASSERT_EQ(heightpackRun({"fresnel", "--ior", std::to_string(ior), "-o", path}).code, 0);
            const nlohmann::json info = jsonRun({"info", path, "--json"});
            EXPECT_EQ(info["attributes"]["heightpack:ior"], shortest(float(ior))) << path;
        }
    const ProcessResult text = heightpackRun({"info", dir.file("f" + std::to_string(1.333) + ".png")});
    EXPECT_NE(text.out.find("  ior           1.333\n"), std::string::npos) << text.out;
    writeImage(dir.file("map.png"), makeImage(16, 16, smoothWave), OIIO::TypeDesc::UINT8);
    ASSERT_EQ(heightpackRun({"pack", dir.file("map.png"), "--height", "0.15m", "-o", dir.file("p.ktx2")}).code, 0);
    EXPECT_EQ(jsonRun({"info", dir.file("p.ktx2"), "--json"})["attributes"]["heightpack:heightRange"], "0.15");
}
