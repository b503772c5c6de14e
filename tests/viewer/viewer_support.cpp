#include "viewer_support.hpp"

#include <algorithm>

extern char** environ;

namespace heightpack::test {

std::vector<std::string> viewerEnvironment(const std::vector<std::string>& without) {
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
    return env;
}

ViewRun view(const std::vector<std::string>& args) {
    std::vector<std::string> argv = {"xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", HEIGHTPACK_VIEW_EXE};
    argv.insert(argv.end(), args.begin(), args.end());
    return runProcess(argv, viewerEnvironment());
}

}  // namespace heightpack::test
