#include "curl_library.hpp"

#include <dlfcn.h>

#include <mutex>

namespace heightpack::detail {

namespace {

template <class F>
bool find(void* handle, const char* name, F& function) {
    function = reinterpret_cast<F>(::dlsym(handle, name));
    return function != nullptr;
}

}  // namespace

const CurlLibrary* curlLibrary(std::string& why) {
    static CurlLibrary library;
    static std::string failure;
    static bool loaded = false;
    static std::once_flag once;
    std::call_once(once, [] {
        void* handle = nullptr;
        for (const char* name : {"libcurl.so.4", "libcurl.so"})
            if ((handle = ::dlopen(name, RTLD_NOW | RTLD_LOCAL)) != nullptr) break;
        if (!handle) {
            failure = "cannot be asked: libcurl.so.4 cannot be loaded (install libcurl4)";
            return;
        }
        decltype(&curl_global_init) globalInit = nullptr;
        CurlLibrary& l = library;
        if (!find(handle, "curl_global_init", globalInit) || !find(handle, "curl_easy_init", l.easyInit) ||
            !find(handle, "curl_easy_cleanup", l.easyCleanup) || !find(handle, "curl_easy_setopt", l.easySetopt) ||
            !find(handle, "curl_easy_getinfo", l.easyGetinfo) || !find(handle, "curl_easy_perform", l.easyPerform) ||
            !find(handle, "curl_easy_strerror", l.easyStrerror) || !find(handle, "curl_slist_append", l.slistAppend) ||
            !find(handle, "curl_slist_free_all", l.slistFreeAll)) {
            failure = "cannot be asked: the libcurl found lacks a function heightpack calls";
            return;
        }
        if (globalInit(CURL_GLOBAL_DEFAULT) != CURLE_OK) {
            failure = "cannot be asked: libcurl could not be initialised";
            return;
        }
        loaded = true;  // the handle stays open: the library is used until the process ends
    });
    if (!loaded) why = failure;
    return loaded ? &library : nullptr;
}

}  // namespace heightpack::detail
