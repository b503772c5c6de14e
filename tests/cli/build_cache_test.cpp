// `heightpack build --cache` end to end (issue 26, item 2): output folders standing for two machines share
// one cache folder; what one baked the other copies, byte for byte, and a later build without the cache
// finds up to date; damaged entries are caught and rebaked; two builders at once agree; the least
// recently used entries go beyond --cache-size. Entries are found by reading their headers (one JSON
// line), not by the library's own addressing.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <thread>

#include "cli/cache_material.hpp"
#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
namespace fs = std::filesystem;

namespace {

// The cache's entries: output -> entry file, read from each entry's header line.
std::map<std::string, fs::path> entries(const fs::path& cache) {
    std::map<std::string, fs::path> found;
    for (const auto& e : fs::recursive_directory_iterator(cache)) {
        if (!e.is_regular_file() || e.path().extension() != ".bin") continue;
        std::ifstream in(e.path(), std::ios::binary);
        std::string line;
        std::getline(in, line);
        const auto header = nlohmann::json::parse(line, nullptr, false);
        if (!header.is_discarded() && header.contains("output")) found[header["output"]] = e.path();
    }
    return found;
}

// Files in the cache that are not entries (a writer's temporary left behind).
std::vector<std::string> strays(const fs::path& cache) {
    std::vector<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(cache))
        if (e.is_regular_file() && (e.path().extension() != ".bin" || e.path().filename().string().starts_with(".")))
            names.push_back(e.path().string());
    return names;
}

class BuildCacheTest : public ::testing::Test {
protected:
    void SetUp() override { writeCacheMaterial(dir.path(), manifest); }

    // heightpack build MANIFEST -o FOLDER [--cache CACHE] EXTRA... --json: the whole JSON report.
    nlohmann::json build(const std::string& folder, bool cached, std::vector<std::string> extra = {},
                         std::string* err = nullptr) {
        std::vector<std::string> args = {"build", manifest, "-o", dir.file(folder), "--json"};
        if (cached) args.insert(args.end(), {"--cache", cache});
        args.insert(args.end(), extra.begin(), extra.end());
        const ProcessResult r = heightpackRun(args);
        EXPECT_EQ(r.code, 0) << r.err;
        if (err) *err = r.err;
        const auto doc = nlohmann::json::parse(r.out, nullptr, false);
        EXPECT_FALSE(doc.is_discarded()) << r.out;
        return doc;
    }
    static nlohmann::json counts(int hits, int misses, int stored, int rejected) {
        return {{"hits", hits}, {"misses", misses}, {"stored", stored}, {"rejected", rejected}, {"errors", 0}};
    }
    // Output -> status, from a report's one material.
    static std::map<std::string, std::string> statuses(const nlohmann::json& doc) {
        std::map<std::string, std::string> s;
        for (const auto& a : doc["materials"][0]["assets"]) s[a["output"]] = a["status"];
        return s;
    }

    ScratchDir dir;
    std::string manifest = dir.file("sea.toml");
    std::string cache = dir.file("shared/cache");  // made by the first build, folders above it too
};

}  // namespace

// Two machines: the second bakes nothing, gets the first's bytes, and is then up to date without the cache.
TEST_F(BuildCacheTest, SecondFolderRestoresEverythingAndIsThenUpToDateWithoutTheCache) {
    const auto first = build("one", true);
    EXPECT_EQ(first["materials"][0]["cache"], counts(0, kOutputs, kOutputs, 0)) << first.dump(1);
    EXPECT_EQ(entries(cache).size(), size_t(kOutputs));

    const auto second = build("two", true);
    EXPECT_EQ(second["cache"]["hits"], kOutputs) << second.dump(1);
    EXPECT_EQ(second["materials"][0]["cache"], counts(kOutputs, 0, 0, 0));
    EXPECT_EQ(second["materials"][0]["rebuilt"], 0);
    EXPECT_EQ(second["materials"][0]["restored"], kOutputs);
    for (const auto& [output, status] : statuses(second)) EXPECT_EQ(status, "restored from cache") << output;
    // Every byte alike, the state file included: it records a restored output as the baked one.
    EXPECT_EQ(filesUnder(dir.file("two")), filesUnder(dir.file("one")));
    EXPECT_TRUE(strays(cache).empty());

    const ProcessResult text = heightpackRun({"build", manifest, "-o", dir.file("text"), "--cache", cache});
    ASSERT_EQ(text.code, 0) << text.err;
    EXPECT_NE(text.out.find("restored from cache"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find(std::to_string(kOutputs) + " hit(s), 0 miss(es)"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("(folder, read-write)"), std::string::npos) << text.out;

    const auto third = build("two", false);
    EXPECT_EQ(third["materials"][0]["upToDate"], kOutputs) << third.dump(1);
    EXPECT_TRUE(third["cache"].is_null());
}

// The key is the content: one map's new bytes make one miss, the rest still come from the cache.
TEST_F(BuildCacheTest, ChangingOneMapBakesThatOutputOnly) {
    build("one", true);
    writeImage(dir.file("maps/b.png"), waves(32, 1, 1, 0.2), OIIO::TypeDesc::UINT16);
    const auto second = build("two", true);
    EXPECT_EQ(second["materials"][0]["cache"], counts(kOutputs - 1, 1, 1, 0)) << second.dump(1);
    for (const auto& [output, status] : statuses(second))
        EXPECT_EQ(status, output == "short.exr" ? "rebuilt" : "restored from cache") << output;
    // The old short.exr stays, under its old key, beside the new one.
    const auto files = std::distance(fs::recursive_directory_iterator(cache), fs::recursive_directory_iterator());
    const auto folders = std::count_if(fs::recursive_directory_iterator(cache), fs::recursive_directory_iterator(),
                                       [](const fs::directory_entry& e) { return e.is_directory(); });
    EXPECT_EQ(files - folders, kOutputs + 1);
}

// $HEIGHTPACK_CACHE names the cache when --cache does not; the flag wins over it.
TEST_F(BuildCacheTest, EnvironmentNamesTheCacheAndTheFlagWins) {
    build("one", true);
    const std::string elsewhere = dir.file("other-cache");
    const std::vector<std::string> args = {HEIGHTPACK_EXE, "build", manifest, "-o", dir.file("two"), "--json"};
    const ProcessResult fromVariable = runProcess(args, {"HEIGHTPACK_CACHE=" + cache});
    ASSERT_EQ(fromVariable.code, 0) << fromVariable.err;
    EXPECT_EQ(nlohmann::json::parse(fromVariable.out)["cache"]["hits"], kOutputs);

    std::vector<std::string> withFlag = args;
    withFlag[4] = dir.file("three");
    withFlag.insert(withFlag.end(), {"--cache", elsewhere});
    const ProcessResult fromFlag = runProcess(withFlag, {"HEIGHTPACK_CACHE=" + cache});
    ASSERT_EQ(fromFlag.code, 0) << fromFlag.err;
    EXPECT_EQ(nlohmann::json::parse(fromFlag.out)["cache"]["misses"], kOutputs);
    EXPECT_EQ(entries(elsewhere).size(), size_t(kOutputs));

    // A check-only build writes nothing: the variable is not used, the flag is refused.
    const ProcessResult check = runProcess({HEIGHTPACK_EXE, "build", manifest, "--check-only"}, {"HEIGHTPACK_CACHE=" + cache});
    EXPECT_EQ(check.code, 0) << check.err;
    const ProcessResult refused = heightpackRun({"build", manifest, "--check-only", "--cache", cache});
    EXPECT_EQ(refused.code, 2);
    expectOneLineError(refused, "");
}

// Two builders at once on one cache, several outputs each at once: same bytes, no temporary left.
TEST_F(BuildCacheTest, TwoBuildsAtOnceAgreeAndLeaveNoTemporary) {
    ProcessResult a, b;
    auto run = [&](const std::string& folder, ProcessResult& r) {
        r = heightpackRun({"build", manifest, "-o", dir.file(folder), "--cache", cache, "--jobs", "3", "-q"});
    };
    std::thread first(run, "one", std::ref(a)), second(run, "two", std::ref(b));
    first.join();
    second.join();
    ASSERT_EQ(a.code, 0) << a.err;
    ASSERT_EQ(b.code, 0) << b.err;
    EXPECT_EQ(filesUnder(dir.file("two")), filesUnder(dir.file("one")));
    EXPECT_TRUE(strays(cache).empty()) << strays(cache).front();
    // Whoever stored last, every entry is whole: a third machine restores all of it.
    const auto third = build("three", true);
    EXPECT_EQ(third["materials"][0]["cache"], counts(kOutputs, 0, 0, 0)) << third.dump(1);
    EXPECT_EQ(filesUnder(dir.file("three")), filesUnder(dir.file("one")));
}

// Truncated, altered and foreign entries are reported, never copied, and rewritten by the rebake.
TEST_F(BuildCacheTest, DamagedEntriesAreRejectedRebakedAndRewritten) {
    build("one", true);
    auto found = entries(cache);
    const std::string sound = bytesOf(found.at("long.exr"));
    fs::resize_file(found.at("long.exr"), fs::file_size(found.at("long.exr")) - 100);  // truncated
    {
        std::fstream altered(found.at("short.exr"), std::ios::in | std::ios::out | std::ios::binary);
        altered.seekp(static_cast<std::streamoff>(fs::file_size(found.at("short.exr")) - 7));
        altered.put('\x5a');  // one byte of the output's, its length unchanged
    }
    fs::copy_file(found.at("fresnel.exr"), found.at("ripple_n.exr"), fs::copy_options::overwrite_existing);  // foreign

    std::string warnings;
    const auto second = build("two", true, {}, &warnings);
    EXPECT_EQ(second["materials"][0]["cache"], counts(kOutputs - 3, 3, 3, 3)) << second.dump(1);
    for (const auto& [output, status] : statuses(second))
        EXPECT_EQ(status, output == "long.exr" || output == "short.exr" || output == "ripple_n.exr" ? "rebuilt"
                                                                                                  : "restored from cache")
            << output;
    for (const char* why : {"truncated", "altered", "another output"}) EXPECT_NE(warnings.find(why), std::string::npos) << warnings;
    EXPECT_EQ(filesUnder(dir.file("two")), filesUnder(dir.file("one")));
    EXPECT_EQ(bytesOf(entries(cache).at("long.exr")), sound);  // rewritten whole

    const auto third = build("three", true);
    EXPECT_EQ(third["materials"][0]["cache"], counts(kOutputs, 0, 0, 0)) << third.dump(1);
}

// Beyond --cache-size the least recently used entries go: a hit makes an entry the most recent.
TEST_F(BuildCacheTest, TrimmingKeepsTheMostRecentlyUsedWithinTheSize) {
    build("one", true);
    const auto stored = entries(cache);
    ASSERT_EQ(stored.size(), size_t(kOutputs));
    const auto hourAgo = fs::file_time_type::clock::now() - std::chrono::hours(1);
    for (const auto& [output, path] : stored) fs::last_write_time(path, hourAgo);

    // Another material that shares one output with the first (same map, options and name): a hit.
    const std::string lagoon = dir.file("lagoon.toml");
    std::ofstream(lagoon) << "format = 1\nname = \"lagoon\"\n\n[[displacement]]\nname = \"long\"\n"
                             "source = \"maps/a.png\"\ntile_size = 64.0\n";
    const std::uintmax_t limit = fs::file_size(stored.at("long.exr")) + 100;
    const ProcessResult r = heightpackRun({"build", lagoon, "-o", dir.file("lagoon"), "--cache", cache, "--cache-size",
                                           std::to_string(limit), "--json"});
    ASSERT_EQ(r.code, 0) << r.err;
    const auto doc = nlohmann::json::parse(r.out);
    EXPECT_EQ(doc["cache"]["hits"], 1) << r.out;
    EXPECT_EQ(doc["cache"]["evicted"], kOutputs - 1);
    EXPECT_LE(doc["cache"]["bytes"].get<std::uintmax_t>(), limit);
    const auto left = entries(cache);
    ASSERT_EQ(left.size(), 1u);
    EXPECT_EQ(left.begin()->first, "long.exr");

    // Sizes with units; a size that is none is a usage error. A forced build bakes and stores everything.
    const auto kept = build("one", true, {"--cache-size", "1K", "--force"});
    EXPECT_EQ(kept["cache"]["stored"], kOutputs);
    EXPECT_EQ(kept["cache"]["hits"], 0);
    EXPECT_EQ(kept["cache"]["bytes"], 0);  // every entry is over a kibibyte
    const ProcessResult bad = heightpackRun({"build", manifest, "-o", dir.file("one"), "--cache", cache, "--cache-size", "2X"});
    EXPECT_EQ(bad.code, 2) << bad.err;
}

// A cache that is a file, not a folder: one line naming it, exit 4, nothing written.
TEST_F(BuildCacheTest, CacheThatIsAFileIsRefusedBeforeAnyWork) {
    const std::string file = dir.file("cache.txt");
    std::ofstream(file) << "not a folder\n";
    const ProcessResult r = heightpackRun({"build", manifest, "-o", dir.file("one"), "--cache", file});
    EXPECT_EQ(r.code, 4) << r.err;
    expectOneLineError(r, file);
    EXPECT_FALSE(fs::exists(dir.file("one")));
}

// Read-only: hits are restored, misses baked and not stored, and nothing in the folder changes (not even
// an entry's time, which a read-write hit renews). A read-only folder that is not there is a warning.
TEST_F(BuildCacheTest, ReadOnlyRestoresAndWritesNothing) {
    build("one", true);
    writeImage(dir.file("maps/b.png"), waves(32, 1, 1, 0.2), OIIO::TypeDesc::UINT16);  // short.exr: a miss
    const auto hourAgo = fs::file_time_type::clock::now() - std::chrono::hours(1);
    for (const auto& [output, path] : entries(cache)) fs::last_write_time(path, hourAgo);
    auto snapshot = [&] {
        std::map<std::string, std::pair<std::string, fs::file_time_type>> files;
        for (const auto& e : fs::recursive_directory_iterator(cache))
            files[e.path().string()] = {e.is_regular_file() ? bytesOf(e.path()) : "", e.last_write_time()};
        return files;
    };
    const auto before = snapshot();
    const auto second = build("two", true, {"--cache-mode", "read-only"});
    EXPECT_EQ(second["cache"]["mode"], "read-only") << second.dump(1);
    EXPECT_EQ(second["materials"][0]["cache"], counts(kOutputs - 1, 1, 0, 0)) << second.dump(1);
    EXPECT_EQ(snapshot(), before);

    // The same from the environment; a mode that is none is a usage error.
    const std::vector<std::string> args = {HEIGHTPACK_EXE, "build", manifest, "-o", dir.file("three"), "--json"};
    const ProcessResult fromVariable =
        runProcess(args, {"HEIGHTPACK_CACHE=" + cache, "HEIGHTPACK_CACHE_MODE=read-only"});
    ASSERT_EQ(fromVariable.code, 0) << fromVariable.err;
    EXPECT_EQ(nlohmann::json::parse(fromVariable.out)["cache"]["stored"], 0) << fromVariable.out;
    EXPECT_EQ(snapshot(), before);
    const ProcessResult bad = runProcess(args, {"HEIGHTPACK_CACHE=" + cache, "HEIGHTPACK_CACHE_MODE=sometimes"});
    EXPECT_EQ(bad.code, 2) << bad.err;
    expectOneLineError(bad, "");

    const std::string missing = dir.file("no-such-cache");
    const ProcessResult none =
        heightpackRun({"build", manifest, "-o", dir.file("four"), "--cache", missing, "--cache-mode", "read-only"});
    ASSERT_EQ(none.code, 0) << none.err;
    EXPECT_EQ(std::count(none.err.begin(), none.err.end(), '\n'), 1) << none.err;
    EXPECT_NE(none.err.find(missing), std::string::npos) << none.err;
    EXPECT_FALSE(fs::exists(missing));
}

// Text that is neither a folder nor an http(s) URL is a usage error that does not repeat the text.
TEST_F(BuildCacheTest, OtherSchemesAreRefusedWithoutEchoingThem) {
    for (const std::string bad : {"ftp://user:hunter2@host/cache", "http://user:hunter2@/nohost"}) {
        const ProcessResult r = heightpackRun({"build", manifest, "-o", dir.file("one"), "--cache", bad});
        EXPECT_EQ(r.code, 2) << bad << ": " << r.err;
        expectOneLineError(r, "");
        EXPECT_EQ(r.err.find("hunter2"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir.file("one")));
    }
    // --cache-size is a folder's: with a server it is a usage error.
    const ProcessResult sized = heightpackRun(
        {"build", manifest, "-o", dir.file("one"), "--cache", "http://127.0.0.1:9/hp", "--cache-size", "1G"});
    EXPECT_EQ(sized.code, 2) << sized.err;
    expectOneLineError(sized, "");
}
