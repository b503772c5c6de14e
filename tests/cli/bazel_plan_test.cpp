// `heightpack build --plan bazel` run by Bazel itself (Debian's bazel-bootstrap) under its linux-sandbox,
// every action given only the files it declares: the bytes are `heightpack build`'s, a second build runs
// nothing, a changed map reruns only its actions, and a second workspace (another folder, another output
// base) gets every action from an HTTP cache, nginx's WebDAV module, as a remote cache hit. Bazel takes
// seconds to start and nginx is a server: ctest label `bazel`, outside the test loop's four minutes.
#include <OpenImageIO/imageio.h>
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <nlohmann/json.hpp>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <thread>

#include "support/heightpack_process.hpp"
#include "support/test_support.hpp"

using namespace heightpack;
using namespace heightpack::test;
namespace fs = std::filesystem;

namespace {

// A map, a normal map from another, and a sea of three frames sharing its foam loop: eight actions.
const char* kManifest = R"(format = 1
name = "water"

[[displacement]]
name = "swell"
source = "maps/a.png"
tile_size = 64.0

[[displacement]]
name = "sea"
tile_size = 256.0
choppiness = 1.0
synth = { wind = 12.0, size = 32, seed = 5, loop = 6.0, frames = 3, shift = true, foam = true }

[normals]
name = "ripple_n"
source = "maps/r.png"
tile_size = 8.0
height = 0.05
)";

Image periodicMap(int size, double amplitude, int seed) {
    return makeImage(size, size, [=](int x, int y) {
        const double u = double(x) / size, v = double(y) / size;
        double h = 0.5;
        for (int k = 1; k <= 4; ++k)
            h += amplitude / k * std::sin(2 * std::numbers::pi * (k * u + ((k + seed) % 3) * v) + 0.7 * k + seed);
        return static_cast<float>(h);
    });
}

void writeText(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Every file under root (links followed: bazel-bin is one), relative path -> a hash of its bytes; the
// foam loop Bazel keeps as an action's output (heightpack build removes it) left out.
std::map<std::string, size_t> fingerprint(const fs::path& root) {
    std::map<std::string, size_t> files;
    std::error_code ec;
    for (const auto& e : fs::recursive_directory_iterator(root, fs::directory_options::follow_directory_symlink, ec)) {
        const std::string name = fs::relative(e.path(), root).string();
        if (e.is_regular_file() && name.rfind(".heightpack-synth", 0) != 0)
            files[name] = std::hash<std::string>{}(readText(e.path()));
    }
    return files;
}

// A port on 127.0.0.1 that nothing listens on (the kernel's choice; free again once closed).
int freePort() {
    const int s = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof a;
    const bool bound = ::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
                       ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &length) == 0;
    ::close(s);
    return bound ? ntohs(a.sin_port) : -1;
}

// nginx as a WebDAV server (PUT and GET: what Bazel's HTTP cache speaks) on 127.0.0.1, its config, store,
// logs and pid under folder; stopped by its pid.
class DavServer {
public:
    explicit DavServer(const fs::path& folder) : folder_(folder), port_(freePort()) {
        fs::create_directories(folder / "store");
        fs::create_directories(folder / "tmp");
        // Under root, nginx's workers run as nobody: they reach and write the store.
        const fs::perms reach = fs::perms::group_exec | fs::perms::others_exec;
        fs::permissions(folder.parent_path(), reach, fs::perm_options::add);
        fs::permissions(folder, reach, fs::perm_options::add);
        fs::permissions(folder / "store", fs::perms::all);
        fs::permissions(folder / "tmp", fs::perms::all);
        const std::string f = folder.string();
        writeText(f + "/nginx.conf", "daemon on;\nworker_processes 1;\npid " + f + "/nginx.pid;\nerror_log " + f +
                                         "/error.log;\nevents { worker_connections 64; }\nhttp {\n  access_log off;\n"
                                         "  client_max_body_size 0;\n  client_body_temp_path " + f + "/tmp;\n"
                                         "  proxy_temp_path " + f + "/tmp;\n  fastcgi_temp_path " + f + "/tmp;\n"
                                         "  uwsgi_temp_path " + f + "/tmp;\n  scgi_temp_path " + f + "/tmp;\n"
                                         "  server {\n    listen 127.0.0.1:" + std::to_string(port_) + ";\n    root " + f +
                                         "/store;\n    location / { dav_methods PUT DELETE MKCOL; create_full_put_path on; }\n"
                                         "  }\n}\n");
        started_ = runProcess({"nginx", "-p", f, "-e", f + "/error.log", "-c", f + "/nginx.conf"});
        for (int i = 0; i < 100 && pid() <= 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ~DavServer() {
        const pid_t p = pid();
        if (p <= 0) return;
        ::kill(p, SIGTERM);
        for (int i = 0; i < 100 && ::kill(p, 0) == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    pid_t pid() const {
        int p = 0;
        std::ifstream(folder_ / "nginx.pid") >> p;
        return p;
    }
    std::string url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/hp"; }
    const ProcessResult& started() const { return started_; }

private:
    fs::path folder_;
    int port_;
    ProcessResult started_;
};

// The spawns one Bazel build ran, from its execution log (one JSON object after another).
struct Spawn {
    std::string message, runner;
    bool remoteHit = false;
};

std::vector<Spawn> spawns(const std::string& log) {
    std::vector<Spawn> all;
    std::ifstream in(log);
    while (in >> std::ws && in.peek() != EOF) {
        nlohmann::json j;
        in >> j;
        all.push_back({j.value("progressMessage", ""), j.value("runner", ""), j.value("remoteCacheHit", false)});
    }
    return all;
}

// The outputs a build's spawns made, by their messages' output names ("bake water: swell.exr //:...").
std::set<std::string> madeOutputs(const std::vector<Spawn>& ran) {
    std::set<std::string> made;
    for (const Spawn& s : ran) {
        const size_t colon = s.message.find(": "), space = s.message.find(' ', colon + 2);
        made.insert(colon == std::string::npos ? s.message : s.message.substr(colon + 2, space - colon - 2));
    }
    return made;
}

class BazelPlanTest : public ::testing::Test {
protected:
    void TearDown() override {
        // Bazel leaves read-only files and folders (its install base, its outputs): writable again, so the
        // scratch folder goes.
        runProcess({"chmod", "-R", "u+w", dir.path().string()});
    }

    // A Bazel build of the workspace in folder, with its own output base; extra: more build options.
    // Returns the spawns it ran; every one must have run in the linux-sandbox or come from the cache.
    std::vector<Spawn> bazel(const std::string& folder, const std::string& outputBase, std::vector<std::string> extra) {
        const std::string log = dir.file("exec." + std::to_string(++builds) + ".json");
        std::vector<std::string> argv = {"bash", "-c", "cd \"$0\" && exec \"$@\"", folder, "bazel", "--nohome_rc", "--noworkspace_rc",
                                         "--batch", "--output_user_root=" + dir.file("bazel-root"),
                                         "--output_base=" + dir.file(outputBase), "--host_jvm_args=-Xmx1g",
                                         "build", "//...", "--jobs=2", "--spawn_strategy=linux-sandbox",
                                         "--repository_cache=" + dir.file("bazel-repositories"),
                                         "--execution_log_json_file=" + log};
        argv.insert(argv.end(), extra.begin(), extra.end());
        const ProcessResult r = runProcess(argv);
        EXPECT_EQ(r.code, 0) << r.err.substr(r.err.size() > 4000 ? r.err.size() - 4000 : 0);
        return spawns(log);
    }

    ScratchDir dir;
    int builds = 0;
};

TEST_F(BazelPlanTest, BazelBuildsTheSameBytesRerunsOnlyWhatChangedAndSharesThroughAnHttpCache) {
    const ProcessResult version = runProcess({"bazel", "--version"});
    ASSERT_EQ(version.code, 0) << "bazel is not installed (scripts/install-deps.sh installs bazel-bootstrap)";
    DavServer server(dir.path() / "nginx");
    ASSERT_GT(server.pid(), 0) << server.started().err << readText(dir.path() / "nginx/error.log");

    const std::string ws = dir.file("ws");
    fs::create_directories(ws + "/maps");
    writeImage(ws + "/maps/a.png", periodicMap(64, 0.08, 1), OIIO::TypeDesc::UINT16);
    writeImage(ws + "/maps/r.png", periodicMap(32, 0.1, 3), OIIO::TypeDesc::UINT8);
    writeText(ws + "/water.toml", kManifest);
    // The workspace as the README sets it up, in the folder that holds the manifest.
    const ProcessResult setup = runProcess({"bash", "-c",
                                            "cd \"$1\" && \"$0\" build --plan bazel-workspace > WORKSPACE && "
                                            "\"$0\" build water.toml -o out/water --plan bazel > BUILD.bazel",
                                            HEIGHTPACK_EXE, ws});
    ASSERT_EQ(setup.code, 0) << setup.err;
    const std::string remote = "--remote_cache=" + server.url();

    // 1. Every action sandboxed: the foam loop, three frames, the map, the normal map and material.json.
    const std::vector<Spawn> first = bazel(ws, "base1", {remote});
    EXPECT_EQ(first.size(), 7u);
    for (const Spawn& s : first) EXPECT_EQ(s.runner, "linux-sandbox") << s.message;
    EXPECT_EQ(madeOutputs(first), (std::set<std::string>{".heightpack-synth/sea.foam", "sea.0000.exr", "sea.0001.exr",
                                                          "sea.0002.exr", "swell.exr", "ripple_n.exr", "material.json"}));
    ASSERT_EQ(heightpackRun({"build", ws + "/water.toml", "-o", dir.file("reference"), "-q"}).code, 0);
    const auto reference = fingerprint(dir.file("reference"));
    EXPECT_EQ(reference.size(), 7u);  // six textures, material.json and the state
    EXPECT_EQ(fingerprint(ws + "/bazel-bin/out/water"), reference);

    // 2. Nothing changed: no action runs.
    EXPECT_TRUE(bazel(ws, "base1", {remote}).empty());

    // 3. The normal map's source changed: its action and the last one, nothing else.
    writeImage(ws + "/maps/r.png", periodicMap(32, 0.07, 4), OIIO::TypeDesc::UINT8);
    const std::vector<Spawn> changed = bazel(ws, "base1", {remote});
    EXPECT_EQ(madeOutputs(changed), (std::set<std::string>{"ripple_n.exr", "material.json"}));
    ASSERT_EQ(heightpackRun({"build", ws + "/water.toml", "-o", dir.file("reference"), "-q"}).code, 0);
    const auto changedReference = fingerprint(dir.file("reference"));
    EXPECT_NE(changedReference, reference);
    EXPECT_EQ(fingerprint(ws + "/bazel-bin/out/water"), changedReference);

    // 4. Another workspace (another machine's checkout) with another output base: every action a hit.
    const std::string other = dir.file("other");
    fs::create_directories(other);
    for (const char* file : {"WORKSPACE", "BUILD.bazel", "water.toml", "maps"})
        fs::copy(ws + "/" + file, other + "/" + file, fs::copy_options::recursive);
    const std::vector<Spawn> second = bazel(other, "base2", {remote});
    EXPECT_EQ(second.size(), 7u);
    for (const Spawn& s : second) {
        EXPECT_TRUE(s.remoteHit) << s.message;
        EXPECT_EQ(s.runner, "remote cache hit") << s.message;
    }
    EXPECT_EQ(fingerprint(other + "/bazel-bin/out/water"), changedReference);
}

}  // namespace
