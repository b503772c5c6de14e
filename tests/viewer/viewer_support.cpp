#include "viewer_support.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <utility>

extern char** environ;

namespace heightpack::test {

namespace {

// One virtual X server for every windowed viewer run of this test program (ctest runs one suite per
// process), started at the first and stopped at exit: xvfb-run around each run started a server, a
// shell and xauth every time, about 0.2 s of CPU and half a second of waiting each. Empty when Xvfb
// cannot start; view() then falls back to xvfb-run, whose own failure the test reports.
class SharedXServer {
public:
    static const std::string& display() {
        static SharedXServer server;
        return server.display_;
    }
    SharedXServer(const SharedXServer&) = delete;
    SharedXServer& operator=(const SharedXServer&) = delete;
    ~SharedXServer() {
        if (pid_ <= 0) return;
        kill(pid_, SIGTERM);
        waitpid(pid_, nullptr, 0);
    }

private:
    SharedXServer() {
        int fds[2];
        if (pipe(fds) != 0) return;
        const std::string fd = std::to_string(fds[1]);
        pid_ = fork();
        if (pid_ == 0) {
            prctl(PR_SET_PDEATHSIG, SIGKILL);  // gone with this process, even when a sanitizer aborts it
            close(fds[0]);
            if (const int null = open("/dev/null", O_WRONLY); null >= 0) dup2(null, 1), dup2(null, 2);
            // -displayfd: the server picks a free display and writes its number when it accepts clients.
            execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1280x1024x24", "-nolisten", "tcp",
                   static_cast<char*>(nullptr));
            _exit(127);
        }
        close(fds[1]);
        std::string number;
        char c;
        while (pid_ > 0 && read(fds[0], &c, 1) == 1 && c != '\n') number += c;
        close(fds[0]);
        if (!number.empty()) display_ = ":" + number;
    }

    pid_t pid_ = -1;
    std::string display_;
};

}  // namespace

std::vector<std::string> viewerEnvironment(const std::vector<std::string>& without, const std::vector<std::string>& with) {
    // Mesa's GL driver keeps small allocations until it is unloaded at exit, where LeakSanitizer cannot
    // even name them; leak checking stays on for everything else, address and UB checks stay on here.
    std::vector<std::string> env;
    bool sawAsan = false;
    for (char** e = environ; *e; ++e) {
        std::string entry = *e;
        if (std::any_of(without.begin(), without.end(),
                        [&](const std::string& name) { return entry.rfind(name + "=", 0) == 0; }))
            continue;
        if (entry.rfind("ASAN_OPTIONS=", 0) == 0) {
            entry += ":detect_leaks=0";
            sawAsan = true;
        }
        env.push_back(entry);
    }
    if (!sawAsan) env.push_back("ASAN_OPTIONS=detect_leaks=0");
    // Mesa's llvmpipe spends most of a viewer run compiling its shaders with LLVM (14.8 s of CPU of a
    // 320x180 screenshot on an empty shader cache, 1.2 s with it warm); without LLVM's optimisation
    // passes it compiles them in half the time and draws the same bytes (IEEE arithmetic either way).
    // A caller's own GALLIVM_PERF wins.
    if (std::none_of(env.begin(), env.end(), [](const std::string& e) { return e.rfind("GALLIVM_PERF=", 0) == 0; }))
        env.push_back("GALLIVM_PERF=nopt");
    env.insert(env.end(), with.begin(), with.end());
    return env;
}

ViewRun view(const std::vector<std::string>& args, const std::vector<std::string>& extraEnvironment) {
    if (const std::string& display = SharedXServer::display(); !display.empty()) {
        std::vector<std::string> argv = {HEIGHTPACK_VIEW_EXE};
        argv.insert(argv.end(), args.begin(), args.end());
        std::vector<std::string> with = {"DISPLAY=" + display};
        with.insert(with.end(), extraEnvironment.begin(), extraEnvironment.end());
        return runProcess(argv, viewerEnvironment({"DISPLAY", "WAYLAND_DISPLAY", "XAUTHORITY"}, with));
    }
    std::vector<std::string> argv = {"xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", HEIGHTPACK_VIEW_EXE};
    argv.insert(argv.end(), args.begin(), args.end());
    return runProcess(argv, viewerEnvironment({}, extraEnvironment));
}

ViewRun viewWithoutDisplay(const std::vector<std::string>& args, const std::vector<std::string>& extraEnvironment) {
    std::vector<std::string> argv = {HEIGHTPACK_VIEW_EXE};
    argv.insert(argv.end(), args.begin(), args.end());
    return runProcess(argv, viewerEnvironment({"DISPLAY", "WAYLAND_DISPLAY"}, extraEnvironment));
}

Picture readPicture(const std::string& path) {
    Picture p;
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    if (!in) return p;
    p.width = in->spec().width;
    p.height = in->spec().height;
    p.rgb.resize(size_t(p.width) * p.height * 3);
    EXPECT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, p.rgb.data()));
    return p;
}

Picture screenshot(const ScratchDir& dir, const std::string& name, std::vector<std::string> args) {
    args.insert(args.end(), {"--screenshot", dir.file(name)});
    const ViewRun run = view(args);
    EXPECT_EQ(run.code, 0) << run.err;
    return readPicture(dir.file(name));
}

Difference compare(const Picture& a, const Picture& b, int tolerance) {
    Difference d;
    EXPECT_EQ(a.rgb.size(), b.rgb.size());
    size_t over = 0;
    for (size_t i = 0; i < std::min(a.rgb.size(), b.rgb.size()); ++i) {
        const int diff = std::abs(int(a.rgb[i]) - int(b.rgb[i]));
        d.max = std::max(d.max, diff);
        over += diff > tolerance;
    }
    d.fractionOver = double(over) / std::max<size_t>(1, a.rgb.size());
    return d;
}

GridHeights readGridHeights(const std::string& path) {
    GridHeights g;
    auto in = OIIO::ImageInput::open(path);
    EXPECT_TRUE(in) << path;
    if (!in) return g;
    const OIIO::ImageSpec& spec = in->spec();
    g.segments = spec.width;
    g.rings = spec.height;
    for (auto [name, values] : {std::pair{"Y", &g.heights}, std::pair{"Dx", &g.shiftX}, std::pair{"Dy", &g.shiftY}}) {
        const int channel = spec.channelindex(name);
        EXPECT_GE(channel, 0) << path << " has no channel " << name;
        if (channel < 0) return g;
        values->resize(size_t(g.segments) * g.rings);
        EXPECT_TRUE(in->read_image(0, 0, channel, channel + 1, OIIO::TypeDesc::FLOAT, values->data()));
    }
    auto number = [&](const char* name) { return spec.get_float_attribute(std::string("heightpack:") + name, NAN); };
    g.cameraX = number("cameraX"), g.cameraY = number("cameraY"), g.cameraZ = number("cameraZ");
    g.pixelAngle = number("pixelAngle"), g.innerRadius = number("gridInnerRadius"), g.ringScale = number("gridRingScale");
    g.waterLevel = number("waterLevel"), g.time = number("time");
    return g;
}

}  // namespace heightpack::test
