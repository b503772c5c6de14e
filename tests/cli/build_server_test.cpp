// `heightpack build --cache http://...` end to end (issue 37, part 2) against an nginx WebDAV server the
// test starts: a second output folder bakes nothing and gets a cache-less build's bytes; damaged entries
// on the server are rejected, rebaked and replaced; read-only stores nothing; a server that refuses to
// store is still read; two builders at once agree;
// a server that is not there, answers 503, never answers or dies mid-build costs one warning and the
// build succeeds; no credential ever shows. Entries are read from the server's folder by their headers
// (one JSON line) and compared with the build's own outputs, not found by the library's addressing.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <thread>
#include <vector>

#include "cli/cache_material.hpp"
#include "support/dav_server.hpp"
#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
namespace fs = std::filesystem;

namespace {

constexpr std::uint64_t kHeaderBytes = 4096;  // an entry's header, before the output's bytes (README)

struct Entry {
    fs::path path;
    std::string name;    // relative to the cache's folder on the server
    std::string output;  // what its header says it holds
};

// The entries under folder, by the output their header names.
std::map<std::string, Entry> entriesUnder(const fs::path& folder) {
    std::map<std::string, Entry> found;
    if (!fs::exists(folder)) return found;
    for (const auto& e : fs::recursive_directory_iterator(folder)) {
        if (!e.is_regular_file()) continue;
        std::ifstream in(e.path(), std::ios::binary);
        std::string line;
        std::getline(in, line);
        const auto header = nlohmann::json::parse(line, nullptr, false);
        if (!header.is_discarded() && header.contains("output"))
            found[header["output"]] = {e.path(), fs::relative(e.path(), folder).string(), header["output"]};
    }
    return found;
}

std::string base64(const std::string& text) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < text.size(); i += 3) {
        unsigned v = static_cast<unsigned char>(text[i]) << 16;
        if (i + 1 < text.size()) v |= static_cast<unsigned char>(text[i + 1]) << 8;
        if (i + 2 < text.size()) v |= static_cast<unsigned char>(text[i + 2]);
        out += digits[(v >> 18) & 63];
        out += digits[(v >> 12) & 63];
        out += i + 1 < text.size() ? digits[(v >> 6) & 63] : '=';
        out += i + 2 < text.size() ? digits[v & 63] : '=';
    }
    return out;
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

class HttpCacheTest : public ::testing::Test {
protected:
    void SetUp() override { writeCacheMaterial(dir.path(), manifest); }

    // heightpack build MANIFEST -o FOLDER [--cache CACHE] EXTRA... --json, in environment (this
    // process's when empty): the process, its JSON report in doc.
    ProcessResult run(const std::string& folder, const std::string& cache, std::vector<std::string> extra = {},
                      std::vector<std::string> environment = {}, bool json = true) {
        std::vector<std::string> args = {HEIGHTPACK_EXE, "build", manifest, "-o", dir.file(folder)};
        if (json) args.push_back("--json");
        if (!cache.empty()) args.insert(args.end(), {"--cache", cache});
        args.insert(args.end(), extra.begin(), extra.end());
        const ProcessResult r = runProcess(args, environment);
        EXPECT_EQ(r.code, 0) << r.err;
        if (json) {
            doc = nlohmann::json::parse(r.out, nullptr, false);
            EXPECT_FALSE(doc.is_discarded()) << r.out;
        }
        return r;
    }
    static nlohmann::json counts(int hits, int misses, int stored, int rejected, int errors = 0) {
        return {{"hits", hits}, {"misses", misses}, {"stored", stored}, {"rejected", rejected}, {"errors", errors}};
    }
    // What the cache counted, without where it is.
    nlohmann::json cacheCounts() const {
        nlohmann::json c;
        for (const char* k : {"hits", "misses", "stored", "rejected", "errors"}) c[k] = doc["cache"][k];
        return c;
    }

    ScratchDir dir;
    std::string manifest = dir.file("sea.toml");
    nlohmann::json doc;
};

class HttpCacheServerTest : public HttpCacheTest {
protected:
    void SetUp() override {
        HttpCacheTest::SetUp();
        ASSERT_TRUE(server.started()) << server.why();
    }
    DavServer server;
    std::string url = server.url("hp");
    fs::path stored = fs::path(server.root()) / "hp";
};

}  // namespace

// A second machine bakes nothing: every output is a hit, and the bytes are a cache-less build's.
TEST_F(HttpCacheServerTest, SecondFolderBakesNothingAndMatchesABuildWithoutTheCache) {
    run("plain", "");
    run("one", url);
    EXPECT_EQ(cacheCounts(), counts(0, kOutputs, kOutputs, 0)) << doc.dump(1);
    EXPECT_EQ(doc["cache"]["backend"], "http");
    EXPECT_EQ(doc["cache"]["location"], url);
    EXPECT_TRUE(doc["cache"]["unavailable"].is_null());

    // On the server: one entry per output at hp/ab/abcdef...bin (ccache's subdirs layout), its header
    // then the output's very bytes.
    const auto entries = entriesUnder(stored);
    ASSERT_EQ(entries.size(), size_t(kOutputs));
    for (const auto& [output, e] : entries) {
        const std::string file = e.path.filename().string();
        EXPECT_EQ(e.name, file.substr(0, 2) + "/" + file) << e.name;
        EXPECT_EQ(file.size(), 32u + 4u) << file;
        EXPECT_EQ(bytesOf(e.path).substr(kHeaderBytes), bytesOf(dir.file("plain/" + output))) << output;
    }

    const std::string logBefore = server.accessLog();
    run("two", url);
    EXPECT_EQ(cacheCounts(), counts(kOutputs, 0, 0, 0)) << doc.dump(1);
    EXPECT_EQ(doc["materials"][0]["rebuilt"], 0);
    EXPECT_EQ(doc["materials"][0]["restored"], kOutputs);
    EXPECT_EQ(filesUnder(dir.file("two")), filesUnder(dir.file("plain")));
    const std::string requests = server.accessLog().substr(logBefore.size());
    EXPECT_EQ(count(requests, "GET "), size_t(kOutputs)) << requests;
    EXPECT_EQ(count(requests, "PUT "), 0u) << requests;

    // The text report names the backend and counts per kind.
    const ProcessResult text = run("three", url, {}, {}, false);
    EXPECT_NE(text.out.find("cache " + url + " (http, read-write): " + std::to_string(kOutputs) +
                            " hit(s), 0 miss(es), 0 stored, 0 rejected, 0 error(s)"),
              std::string::npos)
        << text.out;
    EXPECT_TRUE(text.err.empty()) << text.err;
}

// A truncated and an altered entry on the server: each reported, rebaked, and replaced by a sound one.
TEST_F(HttpCacheServerTest, DamagedEntriesAreRejectedRebakedAndReplaced) {
    run("one", url);
    const auto entries = entriesUnder(stored);
    ASSERT_EQ(entries.size(), size_t(kOutputs));
    const fs::path truncated = entries.at("long.exr").path, altered = entries.at("short.exr").path;
    const std::string soundLong = bytesOf(truncated), soundShort = bytesOf(altered);
    fs::resize_file(truncated, fs::file_size(truncated) - 100);
    {
        std::fstream f(altered, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(static_cast<std::streamoff>(fs::file_size(altered) - 7));
        f.put(static_cast<char>(soundShort[soundShort.size() - 7] ^ 0x5a));
    }
    const ProcessResult second = run("two", url);
    EXPECT_EQ(cacheCounts(), counts(kOutputs - 2, 2, 2, 2)) << doc.dump(1);
    for (const char* why : {"truncated", "altered"}) EXPECT_NE(second.err.find(why), std::string::npos) << second.err;
    EXPECT_NE(second.err.find(url + "/" + entries.at("long.exr").name), std::string::npos) << second.err;
    EXPECT_EQ(filesUnder(dir.file("two")), filesUnder(dir.file("one")));
    EXPECT_EQ(bytesOf(truncated), soundLong);
    EXPECT_EQ(bytesOf(altered), soundShort);
    run("three", url);
    EXPECT_EQ(cacheCounts(), counts(kOutputs, 0, 0, 0)) << doc.dump(1);
}

// Read-only never writes: nothing stored on an empty server, no PUT sent, hits still restored.
TEST_F(HttpCacheServerTest, ReadOnlyStoresNothing) {
    run("one", url, {"--cache-mode", "read-only"});
    EXPECT_EQ(cacheCounts(), counts(0, kOutputs, 0, 0)) << doc.dump(1);
    EXPECT_EQ(doc["cache"]["mode"], "read-only");
    EXPECT_TRUE(entriesUnder(stored).empty());
    run("two", url);  // CI writes
    const std::string logBefore = server.accessLog();
    run("three", "", {}, {"HEIGHTPACK_CACHE=" + url, "HEIGHTPACK_CACHE_MODE=read-only"});  // an artist reads
    EXPECT_EQ(cacheCounts(), counts(kOutputs, 0, 0, 0)) << doc.dump(1);
    const std::string requests = server.accessLog().substr(logBefore.size());
    EXPECT_EQ(count(requests, "PUT "), 0u) << requests;
    EXPECT_EQ(count(server.accessLog(), "PUT "), size_t(kOutputs));
}

// A server that serves entries but refuses to store them (405): one warning, hits still restored.
TEST_F(HttpCacheServerTest, ServerThatRefusesToStoreIsStillRead) {
    run("one", url);
    writeImage(dir.file("maps/b.png"), waves(32, 1, 1, 0.2), OIIO::TypeDesc::UINT16);  // short.exr: a miss
    const std::string readOnly = server.url("readonly/hp");
    const ProcessResult r = run("two", readOnly);
    EXPECT_EQ(cacheCounts(), counts(kOutputs - 1, 1, 0, 0, 1)) << doc.dump(1);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("heightpack: warning: cache " + readOnly + " refuses to store entries", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("405"), std::string::npos) << r.err;
    EXPECT_EQ(entriesUnder(stored).size(), size_t(kOutputs));
}

// Two builders at once, several outputs each at once, on one server: the same bytes, and every entry
// whole (a third builder restores all of them).
TEST_F(HttpCacheServerTest, TwoBuildersAtOnceAgree) {
    ProcessResult a, b;
    auto build = [&](const std::string& folder, ProcessResult& r) {
        r = runProcess({HEIGHTPACK_EXE, "build", manifest, "-o", dir.file(folder), "--cache", url, "--jobs", "3", "-q"});
    };
    std::thread first(build, "one", std::ref(a)), second(build, "two", std::ref(b));
    first.join();
    second.join();
    ASSERT_EQ(a.code, 0) << a.err;
    ASSERT_EQ(b.code, 0) << b.err;
    EXPECT_EQ(filesUnder(dir.file("two")), filesUnder(dir.file("one")));
    run("three", url);
    EXPECT_EQ(cacheCounts(), counts(kOutputs, 0, 0, 0)) << doc.dump(1);
    EXPECT_EQ(filesUnder(dir.file("three")), filesUnder(dir.file("one")));
}

// A user and password in the URL go to the server as basic authentication, a token from the
// environment as a bearer token; neither is ever printed, in text, JSON, warnings or a plan.
TEST_F(HttpCacheServerTest, CredentialsReachTheServerAndNeverShow) {
    const std::string password = "s3cret-Pw", token = "tok-5ee1d";
    const std::string withPassword = "http://artist:" + password + "@127.0.0.1:" + std::to_string(server.port()) + "/hp";
    std::vector<ProcessResult> runs;
    runs.push_back(run("one", withPassword));
    EXPECT_EQ(doc["cache"]["location"], url);
    runs.push_back(run("two", withPassword, {}, {}, false));
    EXPECT_NE(server.accessLog().find("\"Basic " + base64("artist:" + password) + "\""), std::string::npos)
        << server.accessLog();
    runs.push_back(run("three", url, {}, {"HEIGHTPACK_CACHE_TOKEN=" + token}));
    EXPECT_NE(server.accessLog().find("\"Bearer " + token + "\""), std::string::npos) << server.accessLog();
    runs.push_back(runProcess({HEIGHTPACK_EXE, "build", manifest, "-o", dir.file("plan"), "--cache", withPassword,
                               "--plan", "json"}));
    // A server that is down, named in a warning.
    const std::string down = "http://artist:" + password + "@127.0.0.1:" + std::to_string(unusedPort()) + "/hp";
    runs.push_back(run("four", down, {}, {"HEIGHTPACK_CACHE_TOKEN=" + token}));
    EXPECT_FALSE(runs.back().err.empty());
    for (const ProcessResult& r : runs)
        for (const std::string& secret : {password, token, base64("artist:" + password)}) {
            EXPECT_EQ(r.out.find(secret), std::string::npos) << r.out;
            EXPECT_EQ(r.err.find(secret), std::string::npos) << r.err;
        }
    for (const auto& e : fs::recursive_directory_iterator(dir.path())) {
        if (e.is_regular_file() && e.path().extension() != ".exr" && e.path().extension() != ".png") {
            EXPECT_EQ(bytesOf(e.path()).find(password), std::string::npos) << e.path();
        }
    }
}

// Each way a server fails: the build succeeds with the cache-less build's bytes, one warning naming
// the server (never its password) and why, and every output counted as an error.
class HttpCacheOutageTest : public HttpCacheTest {
protected:
    void expectOneWarning(const ProcessResult& r, const std::string& where, const std::string& why) {
        EXPECT_EQ(r.code, 0) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_EQ(r.err.rfind("heightpack: warning: cache " + where + " ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(why), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("pw-"), std::string::npos) << r.err;
        EXPECT_FALSE(doc["cache"]["unavailable"].is_null()) << doc.dump(1);
    }
    std::string withPassword(int port, const std::string& path = "hp") const {
        return "http://u:pw-x@127.0.0.1:" + std::to_string(port) + "/" + path;
    }
    static std::string plain(int port, const std::string& path = "hp") {
        return "http://127.0.0.1:" + std::to_string(port) + "/" + path;
    }
};

TEST_F(HttpCacheOutageTest, NothingListening) {
    run("plain", "");
    const int port = unusedPort();
    const ProcessResult r = run("one", withPassword(port), {"--jobs", "2"});
    expectOneWarning(r, plain(port), "refuses connections");
    EXPECT_EQ(cacheCounts(), counts(0, 0, 0, 0, kOutputs)) << doc.dump(1);
    EXPECT_EQ(filesUnder(dir.file("one")), filesUnder(dir.file("plain")));
}

TEST_F(HttpCacheOutageTest, ServerAnswers503) {
    DavServer server;
    ASSERT_TRUE(server.started()) << server.why();
    run("plain", "");
    const ProcessResult r = run("one", withPassword(server.port(), "broken/hp"), {"--jobs", "2"});
    expectOneWarning(r, plain(server.port(), "broken/hp"), "HTTP 503");
    EXPECT_EQ(cacheCounts(), counts(0, 0, 0, 0, kOutputs)) << doc.dump(1);
    EXPECT_EQ(filesUnder(dir.file("one")), filesUnder(dir.file("plain")));
    // Only the requests in flight when it first failed were sent: the build stopped asking.
    EXPECT_LE(count(server.accessLog(), " 503 "), 2u) << server.accessLog();
}

// A server that accepts connections and never answers (a socket this test holds): the low-speed
// timeout ends the requests in flight, and no other request is made.
TEST_F(HttpCacheOutageTest, ServerThatNeverAnswers) {
    run("plain", "");
    const int listener = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof address;
    ASSERT_EQ(::bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    ASSERT_EQ(::listen(listener, 16), 0);
    ::getsockname(listener, reinterpret_cast<sockaddr*>(&address), &length);
    const int port = ntohs(address.sin_port);
    std::atomic<bool> done{false};
    std::vector<int> accepted;
    std::thread holder([&] {
        while (!done) {
            pollfd p{listener, POLLIN, 0};
            if (::poll(&p, 1, 50) > 0) accepted.push_back(::accept(listener, nullptr, nullptr));
        }
    });
    const auto start = std::chrono::steady_clock::now();
    const ProcessResult r = run("one", withPassword(port), {"--jobs", "2"});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    done = true;
    holder.join();
    for (int fd : accepted) ::close(fd);
    ::close(listener);
    RecordProperty("seconds", std::to_string(seconds));
    expectOneWarning(r, plain(port), "stalled");
    EXPECT_EQ(cacheCounts(), counts(0, 0, 0, 0, kOutputs)) << doc.dump(1);
    EXPECT_LE(accepted.size(), 2u) << "one request per job in flight, none after the first stall";
    EXPECT_EQ(filesUnder(dir.file("one")), filesUnder(dir.file("plain")));
}

// The server dies (SIGKILL) once the build has stored its first entry: the rest is baked without it.
TEST_F(HttpCacheOutageTest, ServerKilledMidBuild) {
    std::string sea = kSea;
    sea.replace(sea.find("frames = 2"), 10, "frames = 24");  // 28 outputs, to leave most after the kill
    std::ofstream(manifest) << sea;
    run("plain", "");
    DavServer server;
    ASSERT_TRUE(server.started()) << server.why();
    const fs::path stored = fs::path(server.root()) / "hp";
    ProcessResult r;
    std::atomic<bool> finished{false};
    std::thread build([&] {
        r = run("one", withPassword(server.port()), {"--jobs", "1"});
        finished = true;
    });
    while (entriesUnder(stored).empty() && !finished) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    server.kill();
    build.join();
    expectOneWarning(r, plain(server.port()), "");
    EXPECT_GE(doc["cache"]["stored"].get<int>(), 1) << doc.dump(1);
    EXPECT_GE(doc["cache"]["errors"].get<int>(), 1) << doc.dump(1);
    EXPECT_EQ(filesUnder(dir.file("one")), filesUnder(dir.file("plain")));
}
