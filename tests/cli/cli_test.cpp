// End-to-end runs of the heightpack binary: exit codes, one-line errors, nothing left behind, --json,
// byte-identical outputs whatever --threads.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "heightpack/io.hpp"
#include "heightpack/mip.hpp"
#include "support/test_support.hpp"

extern char** environ;

using namespace heightpack;
using namespace heightpack::test;

namespace {

struct CliRun {
    int code = -1;
    std::string out, err;
};

std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs heightpack with args, capturing stdout and stderr.
CliRun heightpackRun(const std::vector<std::string>& args) {
    ScratchDir io;
    const std::string outPath = io.file("stdout"), errPath = io.file("stderr");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> all = {HEIGHTPACK_EXE};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    CliRun run;
    if (posix_spawn(&pid, HEIGHTPACK_EXE, &actions, nullptr, argv.data(), environ) != 0) return run;
    posix_spawn_file_actions_destroy(&actions);
    int status = 0;
    waitpid(pid, &status, 0);
    run.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    run.out = slurp(outPath);
    run.err = slurp(errPath);
    return run;
}

// The error contract: exactly one line, prefixed, naming the file.
void expectOneLineError(const CliRun& run, const std::string& path) {
    EXPECT_EQ(run.err.rfind("heightpack: error: ", 0), 0u) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    if (!path.empty()) {
        EXPECT_NE(run.err.find(path), std::string::npos) << run.err;
    }
    EXPECT_TRUE(run.out.empty()) << run.out;
}

float smooth(int x, int y) {
    return static_cast<float>(0.5 + 0.4 * std::sin(x * 0.19) * std::cos(y * 0.13));
}

}  // namespace

TEST(Cli, PacksAndInfoReportsWhatWasWritten) {
    ScratchDir dir;
    const Image map = makeImage(64, 32, smooth);
    writeImage(dir.file("map.png"), map, OIIO::TypeDesc::UINT16);
    const CliRun pack = heightpackRun({"pack", dir.file("map.png"), "--filter", "triangle", "-o", dir.file("map.exr")});
    ASSERT_EQ(pack.code, 0) << pack.err;
    EXPECT_NE(pack.out.find("wrote " + dir.file("map.exr")), std::string::npos) << pack.out;

    const CliRun info = heightpackRun({"info", dir.file("map.exr"), "--json"});
    ASSERT_EQ(info.code, 0) << info.err;
    const auto j = nlohmann::json::parse(info.out);
    EXPECT_EQ(j["layout"], "neighbour4");
    EXPECT_EQ(j["wrap"], "periodic");
    EXPECT_EQ(j["filter"], "triangle");
    EXPECT_EQ(j["tiled"], true);
    EXPECT_EQ(j["channels"], (std::vector<std::string>{"R", "G", "B", "A"}));

    // The statistics info prints are those of the chain computed here from the decoded input.
    auto loaded = loadHeightMap(dir.file("map.png"));
    ASSERT_TRUE(loaded.ok());
    const auto chain = generateMipChain(loaded->heights, Filter::Triangle);
    ASSERT_EQ(j["levelCount"], chain.size());
    for (size_t l = 0; l < chain.size(); ++l) {
        const auto& level = j["levels"][l];
        const auto& px = chain[l].pixels;
        EXPECT_EQ(level["width"], chain[l].width);
        EXPECT_EQ(level["height"], chain[l].height);
        EXPECT_FLOAT_EQ(level["channels"][0]["min"].get<float>(), *std::min_element(px.begin(), px.end()));
        EXPECT_FLOAT_EQ(level["channels"][0]["max"].get<float>(), *std::max_element(px.begin(), px.end()));
    }

    const CliRun text = heightpackRun({"info", dir.file("map.exr")});
    ASSERT_EQ(text.code, 0);
    EXPECT_NE(text.out.find("layout        neighbour4"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("7 levels"), std::string::npos) << text.out;
}

TEST(Cli, JsonReportIsOneObjectOnStdout) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(32, 32, smooth), OIIO::TypeDesc::UINT8);
    const CliRun run = heightpackRun({"pack", dir.file("map.png"), "--json", "-o", dir.file("map.exr")});
    ASSERT_EQ(run.code, 0) << run.err;
    const auto j = nlohmann::json::parse(run.out);
    EXPECT_EQ(j["output"], dir.file("map.exr"));
    EXPECT_EQ(j["levels"].size(), 6u);
    EXPECT_EQ(j["levels"][5]["width"], 1);
    EXPECT_TRUE(j["timings"]["total"].is_number());
    EXPECT_EQ(j["source"]["pixelType"], "uint8");
}

TEST(Cli, SameInputSameBytesWhateverTheThreadCount) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), randomImage(512, 256, 3), OIIO::TypeDesc::UINT16);
    for (const char* compression : {"zip", "piz", "none"}) {
        for (const char* threads : {"1", "2", "3"}) {
            const std::string out = dir.file(std::string("t") + threads + ".exr");
            const CliRun run = heightpackRun({"pack", dir.file("map.png"), "--threads", threads, "--compression",
                                           compression, "--emit-plain", out + ".plain.exr", "-q", "-o", out});
            ASSERT_EQ(run.code, 0) << run.err;
            EXPECT_TRUE(run.out.empty());
        }
        EXPECT_EQ(readBytes(dir.file("t1.exr")), readBytes(dir.file("t2.exr"))) << compression;
        EXPECT_EQ(readBytes(dir.file("t1.exr")), readBytes(dir.file("t3.exr"))) << compression;
        EXPECT_EQ(readBytes(dir.file("t1.exr.plain.exr")), readBytes(dir.file("t2.exr.plain.exr"))) << compression;
    }
}

TEST(Cli, BadInputsExitThreeWithOneLineAndNoOutput) {
    ScratchDir dir;
    writeBytes(dir.file("empty.png"), {});
    const std::string text = "hello\n";
    writeBytes(dir.file("text.png"), std::vector<unsigned char>(text.begin(), text.end()));
    writeImage(dir.file("full.png"), randomImage(256, 256, 1), OIIO::TypeDesc::UINT8);
    auto bytes = readBytes(dir.file("full.png"));
    bytes.resize(bytes.size() / 2);
    writeBytes(dir.file("truncated.png"), bytes);
    std::vector<float> rgb(16 * 16 * 3, 0.5f);
    writeImage(dir.file("colour.png"), 16, 16, 3, rgb, OIIO::TypeDesc::UINT8);
    Image nan = makeImage(16, 16, smooth);
    nan.at(2, 3) = std::numeric_limits<float>::quiet_NaN();
    writeImage(dir.file("nan.exr"), nan, OIIO::TypeDesc::FLOAT);
    writeImage(dir.file("odd.png"), makeImage(1000, 600, smooth), OIIO::TypeDesc::UINT8);
    writeBytes(dir.file("huge.png"), pngWithClaimedSize(100000, 100000));

    const std::pair<const char*, const char*> cases[] = {
        {"missing.png", "no such file"},  {"empty.png", "empty"},      {"text.png", "cannot be read"},
        {"truncated.png", "truncated"},   {"colour.png", "--channel"}, {"nan.exr", "NaN"},
        {"odd.png", "--resize pow2"},     {"huge.png", "100000x100000"},
    };
    for (const auto& [name, words] : cases) {
        const CliRun run = heightpackRun({"pack", dir.file(name), "-o", dir.file("out.exr")});
        EXPECT_EQ(run.code, 3) << name << ": " << run.err;
        expectOneLineError(run, dir.file(name));
        EXPECT_NE(run.err.find(words), std::string::npos) << name << ": " << run.err;
        EXPECT_FALSE(std::filesystem::exists(dir.file("out.exr"))) << name;
    }
    // Nothing but the inputs: no output, no temporary file.
    EXPECT_EQ(dir.listing().size(), 8u);
}

TEST(Cli, UnwritableOutputsExitFourAndAreLeftAlone) {
    ScratchDir dir;
    writeImage(dir.file("map.png"), makeImage(32, 32, smooth), OIIO::TypeDesc::UINT8);

    const CliRun noFolder = heightpackRun({"pack", dir.file("map.png"), "-o", dir.file("missing/out.exr")});
    EXPECT_EQ(noFolder.code, 4);
    expectOneLineError(noFolder, dir.file("missing/out.exr"));

    writeBytes(dir.file("locked.exr"), {'o', 'l', 'd'});
    ::chmod(dir.file("locked.exr").c_str(), 0444);
    const CliRun locked = heightpackRun({"pack", dir.file("map.png"), "-o", dir.file("locked.exr")});
    EXPECT_EQ(locked.code, 4);
    expectOneLineError(locked, dir.file("locked.exr"));
    EXPECT_EQ(readBytes(dir.file("locked.exr")), (std::vector<unsigned char>{'o', 'l', 'd'}));
    EXPECT_EQ(dir.listing(), (std::vector<std::string>{"locked.exr", "map.png"}));
}

TEST(Cli, UsageErrorsExitTwoAndPointAtHelp) {
    ScratchDir dir;
    const std::vector<std::vector<std::string>> cases = {
        {},
        {"frobnicate"},
        {"pack", "map.png"},                                     // no -o
        {"pack", "map.png", "-o", "x.exr", "--filter", "gauss"},
        {"pack", "map.png", "-o", "x.exr", "--threads", "-1"},
        {"pack", "map.png", "-o", "x.exr", "--wrap", "mirror"},
        {"info"},
    };
    for (const auto& args : cases) {
        const CliRun run = heightpackRun(args);
        EXPECT_EQ(run.code, 2) << (args.empty() ? "(no args)" : args[0]) << ": " << run.err;
        expectOneLineError(run, "");
        EXPECT_NE(run.err.find("--help"), std::string::npos) << run.err;
    }
}

TEST(Cli, HelpShowsAnExample) {
    for (const char* command : {"pack", "info"}) {
        const CliRun run = heightpackRun({command, "--help"});
        EXPECT_EQ(run.code, 0);
        EXPECT_NE(run.out.find("Example"), std::string::npos) << run.out;
        EXPECT_NE(run.out.find(std::string("heightpack ") + command), std::string::npos) << run.out;
    }
    const CliRun top = heightpackRun({"--help"});
    EXPECT_EQ(top.code, 0);
    EXPECT_NE(top.out.find("Exit codes"), std::string::npos);
}

TEST(Cli, ExampleMapsPack) {
    // The bundled examples are what the README's demo packs: each must go through as shipped.
    ScratchDir dir;
    for (const char* name : {"swell.png", "choppy.png", "ripple.png", "painted_not_tileable.png"}) {
        const std::string input = std::string(HEIGHTPACK_SOURCE_DIR) + "/examples/maps/" + name;
        const CliRun run = heightpackRun({"pack", input, "-q", "-o", dir.file(std::string(name) + ".exr")});
        EXPECT_EQ(run.code, 0) << name << ": " << run.err;
    }
}
