// The first hour of a new user (issue 35): what --help promises holds (items 3, 10) and a file a person
// naturally hands to info is described (item 7).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "heightpack/io/read.hpp"

#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;

namespace {

std::string mm(double metres) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6gmm", metres * 1000);
    return text;
}

nlohmann::json jsonOf(const ProcessResult& run) {
    EXPECT_EQ(run.code, 0) << run.err;
    return run.code == 0 ? nlohmann::json::parse(run.out) : nlohmann::json::object();
}

// A number of material.json as a person reads it: JSON's shortest text, without the ".0" of a whole one.
std::string shown(const nlohmann::json& number) {
    std::string text = number.dump();
    if (text.size() > 2 && text.compare(text.size() - 2, 2, ".0") == 0) text.resize(text.size() - 2);
    return text;
}

std::string fileText(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// The README and the docs/ pages it links, as one text: a table may live on either.
std::string documentation() {
    const std::filesystem::path source(HEIGHTPACK_SOURCE_DIR);
    std::vector<std::filesystem::path> pages{source / "README.md"};
    for (const auto& e : std::filesystem::directory_iterator(source / "docs"))
        if (e.path().extension() == ".md") pages.push_back(e.path());
    std::sort(pages.begin() + 1, pages.end());
    std::string text;
    for (const auto& page : pages) text += fileText(page.string()) + "\n";
    return text;
}

// The line of text that contains marker (whole, without its newline); "" when none does.
std::string lineWith(const std::string& text, const std::string& marker) {
    const size_t at = text.find(marker);
    if (at == std::string::npos) return {};
    const size_t start = text.rfind('\n', at) + 1;  // npos + 1 = 0
    return text.substr(start, text.find('\n', at) - start);
}

// The text between the first `from` and the next `to` after it in text; "" when either is missing.
std::string between(const std::string& text, const std::string& from, const std::string& to) {
    const size_t a = text.find(from);
    if (a == std::string::npos) return {};
    const size_t b = text.find(to, a + from.size());
    return b == std::string::npos ? std::string() : text.substr(a + from.size(), b - a - from.size());
}

std::vector<std::string> split(const std::string& text, const std::string& separator) {
    std::vector<std::string> parts;
    for (size_t from = 0;;) {
        const size_t at = text.find(separator, from);
        parts.push_back(text.substr(from, at - from));
        if (at == std::string::npos) return parts;
        from = at + separator.size();
    }
}

}  // namespace

// normal --help: --tolerance takes a length when --height is given. It does: a height error across one
// texel (the tile's size over the map's texels, the longer side of a texel) tilts the normal by that
// error / the texel's size, and the pixel type is chosen within that many normal units.
TEST(FirstHour, NormalTakesALengthToleranceWithHeight) {
    ScratchDir dir;
    const std::string square = dir.file("square.png"), wide = dir.file("wide.png");
    writeImage(square, makeImage(64, 64, smoothWave), OIIO::TypeDesc::UINT16);
    writeImage(wide, makeImage(64, 32, smoothWave), OIIO::TypeDesc::UINT16);
    struct Case {
        std::string map, tileSize;
        double texel;  // the longer side of a texel, in metres
    };
    for (const Case& c : {Case{square, "8m", 8.0 / 64}, Case{wide, "8m,16m", 16.0 / 32}}) {
        const auto half = jsonOf(heightpackRun({"normal", c.map, "--tile-size", c.tileSize, "--height", "0.15m",
                                                "--pixel-type", "half", "-o", dir.file("half.exr"), "--json"}));
        const double halfError = half["lookupError"]["worst"].get<double>();
        ASSERT_GT(halfError, 0.0) << "half rounds some normal";
        // A length that tilts twice half's error allows half; one that tilts half of it needs float.
        for (const double factor : {2.0, 0.5}) {
            const std::string tolerance = mm(halfError * c.texel * factor);
            const ProcessResult run = heightpackRun({"normal", c.map, "--tile-size", c.tileSize, "--pixel-type", "auto",
                                                     "--tolerance", tolerance, "--height", "0.15m", "-o",
                                                     dir.file("auto.exr"), "--json"});
            const auto j = jsonOf(run);
            if (run.code != 0) continue;
            EXPECT_EQ(j["pixelType"], factor > 1 ? "half" : "float") << tolerance << " on " << c.map;
            EXPECT_NEAR(j["tolerance"].get<double>(), halfError * factor, 1e-5 * halfError) << tolerance;
            EXPECT_LE(j["lookupError"]["worst"].get<double>(), j["tolerance"].get<double>());
        }
    }
    // A plain number stays in normal units, as before; a length is not mistaken for one.
    const auto plain = jsonOf(heightpackRun({"normal", square, "--tile-size", "8m", "--height", "0.15m", "--pixel-type",
                                             "auto", "--tolerance", "0.01", "-o", dir.file("plain.exr"), "--json"}));
    EXPECT_EQ(plain["tolerance"], 0.01);
    const ProcessResult bad = heightpackRun({"normal", square, "--tile-size", "8m", "--height", "0.15m", "--pixel-type",
                                             "auto", "--tolerance", "1furlong", "-o", dir.file("bad.exr")});
    EXPECT_EQ(bad.code, 2);
    expectOneLineError(bad, "");
}

// info on the material a build wrote describes it: every texture with the parameters material.json gives.
TEST(FirstHour, InfoDescribesAMaterialAndPointsAManifestAtBuild) {
    ScratchDir dir;
    const std::string manifest = std::string(HEIGHTPACK_SOURCE_DIR) + "/examples/ocean.toml";
    const ProcessResult build = heightpackRun({"build", manifest, "-o", dir.file("ocean"), "--quiet"});
    ASSERT_EQ(build.code, 0) << build.err;
    const std::string path = dir.file("ocean/material.json");
    const auto file = nlohmann::json::parse(fileText(path));

    // --json: what the file says, as it says it.
    const auto j = jsonOf(heightpackRun({"info", path, "--json"}));
    EXPECT_EQ(j["command"], "info");
    EXPECT_EQ(j["material"], file);

    // Text: a line per texture naming its file, size and the parameters a renderer needs.
    const ProcessResult text = heightpackRun({"info", path});
    ASSERT_EQ(text.code, 0) << text.err;
    EXPECT_TRUE(text.err.empty()) << text.err;
    EXPECT_NE(text.out.find("material '" + file["name"].get<std::string>() + "'"), std::string::npos) << text.out;
    std::istringstream lines(text.out);
    std::vector<std::string> all;
    for (std::string line; std::getline(lines, line);) all.push_back(line);
    auto lineOf = [&](const std::string& kind, const nlohmann::json& layer) {
        for (const std::string& line : all)
            if (line.find(kind + " '" + layer["name"].get<std::string>() + "'") != std::string::npos) return line;
        ADD_FAILURE() << "no line for " << kind << " " << layer["name"] << " in " << text.out;
        return std::string();
    };
    auto size = [](const nlohmann::json& t) {
        return t["file"].get<std::string>() + ", " + std::to_string(t["width"].get<int>()) + "x" +
               std::to_string(t["height"].get<int>()) + ", " + std::to_string(t["levels"].get<int>()) + " levels";
    };
    ASSERT_FALSE(file["displacement"].empty());
    for (const auto& d : file["displacement"]) {
        const std::string line = lineOf("displacement", d);
        EXPECT_NE(line.find(size(d["texture"])), std::string::npos) << line;
        // The layout and what the texels are stored as (float where material.json names no type).
        EXPECT_NE(line.find(", " + d["layout"].get<std::string>() + ", " + d["texture"].value("pixelType", "float") + ";"),
                  std::string::npos) << line;
        EXPECT_NE(line.find("tile " + shown(d["tileSize"]) + " m"), std::string::npos) << line;
        EXPECT_NE(line.find("amplitude " + shown(d["amplitude"]) + " m"), std::string::npos) << line;
        EXPECT_NE(line.find("scroll " + shown(d["scroll"][0]) + "," + shown(d["scroll"][1])), std::string::npos) << line;
    }
    ASSERT_TRUE(file.contains("fresnel"));
    const std::string fresnel = lineOf("fresnel", file["fresnel"]);
    EXPECT_NE(fresnel.find("ior " + shown(file["fresnel"]["ior"]) + ","), std::string::npos) << fresnel;
    ASSERT_TRUE(file.contains("normals"));
    const std::string normals = lineOf("normals", file["normals"]);
    EXPECT_NE(normals.find(std::to_string(file["normals"]["octaves"].size()) + " octaves"), std::string::npos) << normals;

    // The manifest itself: not a texture; the hint says what to run.
    const ProcessResult toml = heightpackRun({"info", manifest});
    EXPECT_EQ(toml.code, 2) << toml.err;
    expectOneLineError(toml, manifest);
    EXPECT_NE(toml.err.find("heightpack build " + manifest + " -o"), std::string::npos) << toml.err;
    EXPECT_EQ(toml.err.find("export it as"), std::string::npos) << toml.err;

    // A JSON file that is no material is bad input, said in one line.
    std::ofstream(dir.file("other.json")) << "{\"schema\": \"something else\"}\n";
    const ProcessResult other = heightpackRun({"info", dir.file("other.json")});
    EXPECT_EQ(other.code, 3) << other.err;
    expectOneLineError(other, dir.file("other.json"));
}

// pack --help and the pack table of docs/commands.md list the same input formats, as many as the formats the reader
// names when it refuses a file.
TEST(FirstHour, HelpAndReadmeListTheSameInputFormats) {
    const ProcessResult help = heightpackRun({"pack", "--help"});
    ASSERT_EQ(help.code, 0);
    const std::string fromHelp = between(lineWith(help.out, "height map: "), "height map: ", "; 8/16-bit");
    const std::string fromReadme = between(lineWith(documentation(), "| `INPUT` |"), "| `INPUT` | ", " (see \"Input formats\")");
    ASSERT_FALSE(fromHelp.empty()) << help.out;
    EXPECT_EQ(fromReadme, fromHelp);
    EXPECT_EQ(fromHelp, readableFormats());
    ScratchDir dir;
    std::ofstream(dir.file("notes.txt")) << "not an image at all\n";
    const ProcessResult refused = heightpackRun({"info", dir.file("notes.txt")});
    EXPECT_EQ(refused.code, 3);
    const std::string named = between(refused.err, "heightpack reads (", ")");
    ASSERT_FALSE(named.empty()) << refused.err;
    EXPECT_EQ(split(named, ", ").size(), split(fromHelp, ", ").size()) << named << " against " << fromHelp;
}

// --channel's names, in every command's help and in docs/commands.md, are ChannelSelect's table.
TEST(FirstHour, ChannelNamesAreTheTablesInHelpAndReadme) {
    const std::string names = joinedNames<ChannelSelect>(", ");
    for (const char* command : {"pack", "normal", "check", "tile"}) {
        const ProcessResult help = heightpackRun({command, "--help"});
        const std::string line = lineWith(help.out, "where the height is in a colour image: ");
        EXPECT_NE(line.find("colour image: " + names + ", or a channel's name"), std::string::npos) << command << ": " << line;
    }
    EXPECT_NE(documentation().find("| `--channel " + joinedNames<ChannelSelect>("\\|") + "\\|NAME` | which channel of a colour "
                            "image holds the height: " + names + ", or a channel's name"),
              std::string::npos);
}

// The exit-code table says which extensions each command writes: what the command itself says when it is
// given another.
TEST(FirstHour, ReadmeSaysWhichOutputsEachCommandWrites) {
    const std::string row = lineWith(documentation(), "| 2 | usage error (the message points at `--help`)");
    const std::string list = between(row, "an output whose extension is not one the command writes (", ")");
    ASSERT_FALSE(list.empty()) << row;
    std::map<std::string, std::set<std::string>> documented;  // "pack" or "check --preview" -> extensions
    for (const std::string& part : split(list, "; ")) {
        const size_t colon = part.find(": ");
        ASSERT_NE(colon, std::string::npos) << part;
        std::set<std::string> extensions;
        for (const std::string& e : split(part.substr(colon + 2), ", ")) extensions.insert(between(e, "`", "`"));
        for (const std::string& c : split(part.substr(0, colon), ", ")) documented[between(c, "`", "`")] = extensions;
    }
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(16, 16, smoothWave), OIIO::TypeDesc::UINT8);
    const std::string map = dir.file("map.png"), bmp = dir.file("x.bmp");
    const std::map<std::string, std::vector<std::string>> runs = {
        {"pack", {"pack", map, "-o", bmp}},
        {"normal", {"normal", map, "--tile-size", "8m", "--height", "1m", "-o", bmp}},
        {"fresnel", {"fresnel", "-o", bmp}},
        {"tile", {"tile", map, "-o", bmp}},
        {"synth", {"synth", "--wind", "10", "--tile-size", "10m", "-o", bmp}},
        {"check --preview", {"check", map, "--preview", bmp}},
    };
    for (const auto& [name, args] : runs) {
        const ProcessResult run = heightpackRun(args);
        EXPECT_EQ(run.code, 2) << run.err;
        std::set<std::string> said;
        for (const std::string& e : split(between(run.err, " must end in ", ";"), ", ")) said.insert(e);
        EXPECT_EQ(documented[name], said) << name << ": " << run.err << " against the documentation's " << list;
    }
    EXPECT_EQ(documented.size(), runs.size()) << list;
}

// --resize's default is what the help and docs/commands.md say it is: none, which refuses a map whose sides are
// not powers of two, exactly as --resize none does.
TEST(FirstHour, ResizeDefaultIsWhatTheDocsSay) {
    for (const char* command : {"pack", "normal"}) {
        const ProcessResult help = heightpackRun({command, "--help"});
        EXPECT_NE(lineWith(help.out, "--resize").find("--resize TEXT:{none,pow2}=none"), std::string::npos) << help.out;
    }
    EXPECT_NE(documentation().find("| `--resize none\\|pow2` | `none` refuses a map whose sides are not powers of two (exit 3); "
                            "`pow2` resamples it up to the next powers of two with the mip filter | none |"),
              std::string::npos);
    ScratchDir dir;
    writeImage(dir.file("odd.png"), makeImage(24, 16, smoothWave), OIIO::TypeDesc::UINT8);
    EXPECT_EQ(heightpackRun({"pack", dir.file("odd.png"), "-o", dir.file("a.exr")}).code, 3);
    EXPECT_EQ(heightpackRun({"pack", dir.file("odd.png"), "--resize", "none", "-o", dir.file("b.exr")}).code, 3);
    EXPECT_EQ(heightpackRun({"pack", dir.file("odd.png"), "--resize", "pow2", "-o", dir.file("c.exr")}).code, 0);
}
