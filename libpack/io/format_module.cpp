// Finds and loads the OpenImageIO module (libpack/oiio) with dlopen, once per process, on first need.
#include "heightpack/io/format_module.hpp"

#include <dlfcn.h>
#ifdef HEIGHTPACK_OIIO_AT_START
#include <OpenImageIO/imageio.h>
#endif
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <vector>

#include "format_module_loader.hpp"

namespace heightpack {

namespace {

namespace fs = std::filesystem;

constexpr const char* kModuleFile = "libheightpack_oiio.so";

struct Loaded {
    std::once_flag once;
    std::atomic<bool> done{false};
    detail::ImageModule* module = nullptr;
    FormatModuleState state;
};

Loaded& loaded() {
    static Loaded* l = new Loaded;  // never destroyed: the module stays mapped until the process ends
    return *l;
}

std::atomic<int>& pendingThreads() {
    static std::atomic<int> threads{-1};
    return threads;
}

// Where the module may be, in order: the environment's choice alone when given; else next to the
// running program (the build tree), in the install's library folder seen from the program's folder, at
// the install prefix this library was built for, and in the build tree that built it (tests, consumers).
std::vector<fs::path> candidates() {
    if (const char* named = std::getenv(kFormatModuleVariable); named && *named) return {fs::path(named)};
    std::vector<fs::path> paths;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        paths.push_back(exe.parent_path() / kModuleFile);
        paths.push_back(exe.parent_path() / HEIGHTPACK_MODULE_FROM_BIN / kModuleFile);
    }
    paths.emplace_back(HEIGHTPACK_MODULE_INSTALLED);
    paths.emplace_back(HEIGHTPACK_MODULE_BUILT);
    return paths;
}

fs::path firstExisting() {
    const std::vector<fs::path> paths = candidates();
    for (const fs::path& p : paths) {
        std::error_code ec;
        if (fs::is_regular_file(p, ec)) return p.lexically_normal();
    }
    return paths.front();
}

void load(Loaded& l) {
    const fs::path path = firstExisting();
    l.state.path = path.string();
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
        l.state.failure = "not found (" + l.state.path + ")";
        return;
    }
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* why = ::dlerror();
        l.state.failure = why ? why : "dlopen failed";
        return;
    }
    using Entry = detail::ImageModule* (*)();
    auto entry = reinterpret_cast<Entry>(::dlsym(handle, "heightpack_image_module"));
    detail::ImageModule* module = entry ? entry() : nullptr;
    if (!module) {
        l.state.failure = l.state.path + " is not heightpack's format module";
        return;
    }
    if (module->interfaceVersion() != detail::kModuleInterface) {
        l.state.failure = l.state.path + " is from another heightpack version";
        return;
    }
    l.module = module;
    l.state.loaded = true;
    l.state.library = "OpenImageIO " + module->libraryVersion();
    if (const int threads = pendingThreads().load(); threads >= 0) module->setThreads(threads);
}

}  // namespace

FormatModuleState formatModuleState() {
#ifdef HEIGHTPACK_OIIO_AT_START
    (void)&OIIO::openimageio_version;  // keeps OpenImageIO a library the program maps at start (CMakeLists.txt)
#endif
    Loaded& l = loaded();
    if (l.done.load()) return l.state;
    FormatModuleState state;
    state.path = firstExisting().string();
    return state;
}

FormatModuleState loadFormatModule() {
    Loaded& l = loaded();
    std::call_once(l.once, [&] {
        load(l);
        l.done.store(true);
    });
    return l.state;
}

namespace detail {

Result<ImageModule*> formatModule(const std::string& path, const char* failed) {
    const FormatModuleState state = loadFormatModule();
    if (!state.loaded)
        return Error{ErrorKind::Internal, path,
                     std::string(failed) + ": heightpack's OpenImageIO module did not load: " + state.failure,
                     std::string("reinstall heightpack, or name the module's file in ") + kFormatModuleVariable};
    return loaded().module;
}

void setFormatModuleThreads(int threads) {
    pendingThreads().store(threads);
    Loaded& l = loaded();
    if (l.done.load() && l.module) l.module->setThreads(threads);
}

int libraryThreads() { return std::max(0, pendingThreads().load()); }

}  // namespace detail

}  // namespace heightpack
