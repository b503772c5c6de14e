// Where a build's shared cache is and how the build may use it: a folder (local or on a network share) or
// an HTTP server that stores files by PUT and serves them by GET (nginx with WebDAV, bazel-remote, any
// object store behind a plain HTTP front), read and written or only read. The location is text only at
// the edge (parseCacheLocation); past it the backend is a typed value.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "heightpack/core/names.hpp"
#include "heightpack/core/result.hpp"

namespace heightpack {

inline constexpr std::uint64_t kDefaultCacheSize = std::uint64_t(10) << 30;  // 10 GiB

enum class CacheBackend { Folder, Http };
template <>
struct NameTable<CacheBackend> {
    static constexpr EnumName<CacheBackend> entries[] = {
        {CacheBackend::Folder, "folder", "a folder, local or on a network share"},
        {CacheBackend::Http, "http", "an HTTP server: GET to fetch, PUT to store (nginx with WebDAV, bazel-remote)"},
    };
};

enum class CacheMode { ReadWrite, ReadOnly };
template <>
struct NameTable<CacheMode> {
    static constexpr EnumName<CacheMode> entries[] = {
        {CacheMode::ReadWrite, "read-write", "restore what the cache holds, store what is baked"},
        {CacheMode::ReadOnly, "read-only", "restore what the cache holds, never write to it"},
    };
};

// One cache. `where` is safe to print, log and record: a URL's user and password are taken out of it.
struct CacheLocation {
    CacheBackend backend = CacheBackend::Folder;
    std::string where;     // the folder as given, or the server's base URL without credentials or trailing '/'
    std::string user;      // a URL's user:password@ (HTTP basic authentication); never printed
    std::string password;
};

// The cache that text names: an http:// or https:// URL is a server (its user:password@, if any, taken
// out of `where` into user and password), any other text a folder. Fails (InconsistentOptions) on an
// empty text, another scheme ("ftp://...") or a URL that cannot be parsed; the error never repeats the
// text (it may hold a password).
Result<CacheLocation> parseCacheLocation(const std::string& text);

struct CacheOptions {
    std::optional<CacheLocation> location;  // none: no cache
    CacheMode mode = CacheMode::ReadWrite;
    std::string token;  // a server's bearer token (Authorization: Bearer); never printed
    // A folder's: the most its entries may hold after a build (least recently used go). A server keeps
    // its own size.
    std::uint64_t sizeLimit = kDefaultCacheSize;
    int connectMilliseconds = 2000;  // a server that takes longer to accept a connection is down
    int stallSeconds = 3;            // a server that sends or takes nothing for this long is down
};

}  // namespace heightpack
