// SIGKILL at random moments of every kind of write (issue 21): sequences (synth frames with displacement
// and foam, pack of a sequence with --emit-plain), GPU containers and builds. A kill cannot be caught, so
// what it leaves must already be whole: every file in the folder is then byte for byte its old or its new
// complete self, and the next run leaves no temporary file of any shape behind.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <thread>

#include "heightpack/bake/build/build_report.hpp"
#include "heightpack/bake/build/build_state.hpp"

#include <nlohmann/json.hpp>

#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

namespace fs = std::filesystem;
using namespace heightpack;
using namespace heightpack::test;

namespace {

using Snapshot = std::map<std::string, std::vector<unsigned char>>;  // relative path -> bytes

bool isTemporary(const std::string& name) { return name.find(".hptmp-") != std::string::npos; }

// Every file under folder but temporaries, with its bytes.
Snapshot snapshot(const fs::path& folder) {
    Snapshot files;
    for (const auto& e : fs::recursive_directory_iterator(folder))
        if (e.is_regular_file() && !isTemporary(e.path().filename().string()))
            files[fs::relative(e.path(), folder).string()] = readBytes(e.path().string());
    return files;
}

std::vector<std::string> temporaries(const fs::path& folder) {
    std::vector<std::string> found;
    for (const auto& e : fs::recursive_directory_iterator(folder))
        if (isTemporary(e.path().filename().string())) found.push_back(e.path().string());
    return found;
}

void restore(const fs::path& folder, const Snapshot& files) {
    fs::remove_all(folder);
    for (const auto& [name, bytes] : files) {
        fs::create_directories((folder / name).parent_path());
        writeBytes((folder / name).string(), bytes);
    }
}

// Starts heightpack with args, kills it with SIGKILL after delay, and reaps it. Returns whether it was
// still running when the signal came.
bool runAndKill(const std::vector<std::string>& args, std::chrono::microseconds delay) {
    const pid_t child = ::fork();
    if (child == 0) {
        const int devnull = ::open("/dev/null", O_WRONLY);
        ::dup2(devnull, 1);
        ::dup2(devnull, 2);
        std::vector<char*> argv{const_cast<char*>(HEIGHTPACK_EXE)};
        for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(HEIGHTPACK_EXE, argv.data());
        ::_exit(127);
    }
    std::this_thread::sleep_for(delay);
    int status = 0;
    const bool running = ::waitpid(child, &status, WNOHANG) == 0;
    ::kill(child, SIGKILL);
    ::waitpid(child, &status, 0);
    return running;
}

struct Scenario {
    const char* name;
    std::function<void(const ScratchDir&)> prepare;  // inputs, written once
    std::vector<std::string> before, after;          // two runs with different outputs, relative to out/
};

class KillTest : public ::testing::TestWithParam<int> {};

// The command lines, with OUT standing for the output folder and IN for the input folder.
std::vector<std::string> expand(std::vector<std::string> args, const ScratchDir& dir) {
    for (std::string& a : args) {
        for (const auto& [key, folder] : {std::pair{"OUT", "out"}, std::pair{"IN", "in"}})
            if (a.rfind(std::string(key) + "/", 0) == 0) a = dir.file(folder) + a.substr(std::strlen(key));
    }
    return args;
}

std::vector<Scenario> scenarios() {
    const std::vector<std::string> sea = {"synth", "--spectrum", "jonswap", "--wind", "9m/s", "--tile-size", "64m",
                                          "--size", "128", "--frames", "6", "--loop", "6s", "--shift", "--foam",
                                          "--threads", "1", "-o", "OUT/sea.exr"};
    auto withSeed = [](std::vector<std::string> args, const char* seed) {
        args.insert(args.end(), {"--seed", seed});
        return args;
    };
    const auto writeSequence = [](const ScratchDir& dir) {
        fs::create_directories(dir.file("in"));
        for (int f = 0; f < 5; ++f) {
            char name[32];
            std::snprintf(name, sizeof name, "in/map.%04d.png", f);
            writeImage(dir.file(name), randomImage(256, 256, 40 + f), OIIO::TypeDesc::UINT16);
        }
    };
    const auto writeManifest = [](const ScratchDir& dir) {
        fs::create_directories(dir.file("in"));
        // Two manifests that differ in their maps' filter, so every texture changes.
        for (const char* filter : {"box", "kaiser"}) {
            std::string text = "format = 1\nname = \"sea\"\n";
            for (int i = 0; i < 3; ++i) {
                const std::string map = dir.file("in/m" + std::to_string(i) + ".png");
                writeImage(map, randomImage(256, 256, 70 + i), OIIO::TypeDesc::UINT16);
                text += "[[displacement]]\nname = \"m" + std::to_string(i) + "\"\nsource = \"" + map +
                        "\"\ntile_size = 32\nfilter = \"" + filter + "\"\n";
            }
            std::ofstream(dir.file(std::string("in/sea_") + filter + ".toml")) << text;
        }
    };
    return {
        {"SynthSequence", [](const ScratchDir&) {}, withSeed(sea, "1"), withSeed(sea, "2")},
        {"PackSequenceWithPlain", writeSequence,
         {"pack", "IN/map.####.png", "--filter", "box", "--emit-plain", "OUT/plain.####.exr", "-o", "OUT/p.####.exr"},
         {"pack", "IN/map.####.png", "--filter", "kaiser", "--emit-plain", "OUT/plain.####.exr", "-o", "OUT/p.####.exr"}},
        {"Containers", writeSequence,
         {"pack", "IN/map.####.png", "--pixel-type", "float", "-o", "OUT/t.####.ktx2"},
         {"pack", "IN/map.####.png", "--pixel-type", "half", "-o", "OUT/t.####.ktx2"}},
        {"Build", writeManifest, {"build", "IN/sea_box.toml", "-o", "OUT/sea", "--jobs", "1"},
         {"build", "IN/sea_kaiser.toml", "-o", "OUT/sea", "--jobs", "1"}},
    };
}

TEST_P(KillTest, EveryFileIsOldOrNewAndTheNextRunLeavesNoTemporary) {
    const Scenario s = scenarios()[GetParam()];
    ScratchDir dir;
    s.prepare(dir);
    const fs::path out = dir.file("out");
    fs::create_directories(out);
    const auto before = expand(s.before, dir), after = expand(s.after, dir);
    const ProcessResult first = heightpackRun(before);
    ASSERT_EQ(first.code, 0) << first.err;
    const Snapshot old = snapshot(out);
    const auto start = std::chrono::steady_clock::now();
    const ProcessResult second = heightpackRun(after);
    ASSERT_EQ(second.code, 0) << second.err;
    const auto took = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start);
    const Snapshot fresh = snapshot(out);
    ASSERT_NE(old, fresh) << "the two runs must write different bytes for the test to tell them apart";

    std::mt19937 random(1234 + GetParam());
    int killedWhileRunning = 0;
    constexpr int kKills = 8;
    // Kills until kKills have landed while the command ran (a kill after it finished proves nothing; under
    // load a run's length varies, so after a late delay the next are drawn from before it), each followed
    // by a whole run.
    long latest = took.count() * 9 / 10;
    for (int k = 0; k < 3 * kKills && killedWhileRunning < kKills; ++k) {
        restore(out, old);
        const std::chrono::microseconds delay(std::uniform_int_distribution<long>(0, latest)(random));
        const bool landed = runAndKill(after, delay);
        killedWhileRunning += landed;
        if (!landed) latest = std::max(1L, delay.count() * 9 / 10);
        const Snapshot killed = snapshot(out);
        for (const auto& [name, bytes] : killed) {
            const auto o = old.find(name), n = fresh.find(name);
            const bool whole = (o != old.end() && o->second == bytes) || (n != fresh.end() && n->second == bytes);
            if (!whole && fs::path(name).filename() == kBuildStateFile) {
                // The build records each output as it lands (so a killed build resumes): its state file may
                // be between old and new, but whole, and it must never vouch for bytes that are not there.
                // Whole: a state document, which may list no output (a build forgets every output it is
                // about to replace before replacing any, and a kill can land right after).
                const std::string text(bytes.begin(), bytes.end());
                const nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
                EXPECT_TRUE(doc.is_object() && doc.contains("outputs") && doc["outputs"].is_object() &&
                            buildStateText(parseBuildState(text)) == text)
                    << s.name << ": " << name << " after a kill at " << delay.count() << " us is damaged";
                const BuildState state = parseBuildState(text);
                for (const auto& [output, entry] : state) {
                    const auto there = killed.find((fs::path(name).parent_path() / output).string());
                    const std::string hash = there == killed.end() ? "" : hashText(std::string(there->second.begin(), there->second.end()));
                    EXPECT_EQ(hash, entry.hash) << s.name << ": " << name << " vouches for " << output << " after a kill at "
                                                << delay.count() << " us";
                }
                continue;
            }
            EXPECT_TRUE(whole) << s.name << ": " << name << " after a kill at " << delay.count() << " us is neither its old nor its new self";
        }
        const ProcessResult again = heightpackRun(after);
        ASSERT_EQ(again.code, 0) << again.err;
        EXPECT_EQ(temporaries(out), std::vector<std::string>{}) << s.name << ": left after the run that followed a kill at " << delay.count() << " us";
        EXPECT_EQ(snapshot(out), fresh) << s.name;
    }
    EXPECT_GE(killedWhileRunning, kKills / 2) << "most kills must land while the command runs";
}

INSTANTIATE_TEST_SUITE_P(Writes, KillTest, ::testing::Range(0, 4),
                         [](const ::testing::TestParamInfo<int>& info) { return std::string(scenarios()[info.param].name); });

// A killed run of an earlier heightpack left temporaries of temporaries (a staged frame's name wrapped
// again by its writer's own temporary file): the next run recognises and removes those too.
TEST(StaleTemporaries, EveryShapeAnEarlierRunLeftIsRemoved) {
    ScratchDir dir;
    const fs::path out = dir.file("out");
    fs::create_directories(out);
    // A process id that no longer runs: a child that has exited.
    const pid_t dead = ::fork();
    if (dead == 0) ::_exit(0);
    ::waitpid(dead, nullptr, 0);
    const std::string pid = std::to_string(dead);
    const std::vector<std::string> litter = {".sea.0000.hptmp-" + pid + "-0.exr",
                                             "..sea.0001.hptmp-" + pid + "-0.hptmp-" + pid + "-1.exr",
                                             "...sea.0002.hptmp-" + pid + "-3.hptmp-" + pid + "-4.hptmp-" + pid + "-5.exr"};
    for (const std::string& name : litter) writeBytes((out / name).string(), {1, 2, 3});
    const ProcessResult r = heightpackRun({"synth", "--wind", "9m/s", "--tile-size", "64m", "--size", "64", "--frames", "3",
                                           "--loop", "4s", "-o", (out / "sea.exr").string()});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(temporaries(out), std::vector<std::string>{});
}

}  // namespace
