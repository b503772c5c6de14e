// libcurl, loaded (dlopen) the first time a build talks to a cache server rather than linked: it brings
// some thirty libraries (TLS, Kerberos, LDAP, SSH, HTTP/2) that every other heightpack command would
// otherwise load at start-up for nothing. Only the functions http_cache.cpp calls are looked up.
#pragma once

#define CURL_DISABLE_TYPECHECK  // calls go through the pointers below, not the checked macros
#include <curl/curl.h>

#include <string>

namespace heightpack::detail {

struct CurlLibrary {
    decltype(&curl_easy_init) easyInit = nullptr;
    decltype(&curl_easy_cleanup) easyCleanup = nullptr;
    CURLcode (*easySetopt)(CURL*, CURLoption, ...) = nullptr;
    CURLcode (*easyGetinfo)(CURL*, CURLINFO, ...) = nullptr;
    decltype(&curl_easy_perform) easyPerform = nullptr;
    decltype(&curl_easy_strerror) easyStrerror = nullptr;
    decltype(&curl_slist_append) slistAppend = nullptr;
    decltype(&curl_slist_free_all) slistFreeAll = nullptr;
};

// libcurl, loaded and initialised on the first call (from any thread); nullptr when it cannot be loaded,
// with why saying so.
const CurlLibrary* curlLibrary(std::string& why);

}  // namespace heightpack::detail
