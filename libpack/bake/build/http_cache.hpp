// The shared cache on an HTTP server: entries (cache_entry.hpp) fetched by GET and stored by PUT with a
// Content-Length, at URL/NAME, as ccache, sccache and Bazel's remote caches use one. A server that cannot
// be reached, refuses or stalls is told apart from one that answers "not here", so the caller can stop
// asking it; nothing said here holds the server's credentials.
#pragma once

#include <string>

#include "heightpack/bake/build/shared_cache.hpp"
#include "heightpack/core/result.hpp"

namespace heightpack::detail {

struct HttpServer {
    std::string url;  // base URL, no credentials, no trailing '/'
    std::string user, password;  // basic authentication, when given
    std::string token;           // bearer token, when given (sent instead of user and password)
    int connectMilliseconds = 2000;
    int stallSeconds = 3;
};

// What went wrong with the server itself (not with an entry).
enum class ServerTrouble {
    None,
    Refused,  // it answered, but not as a cache would (401, 403, 405, ...): asking again will not help
    Down,     // no connection, a connection cut, nothing for stallSeconds, or a 5xx answer
};
struct ServerFailure {
    ServerTrouble trouble = ServerTrouble::None;
    std::string why;  // "refuses connections (...)", "stalled: ...", "answered HTTP 503", ...
};

// Loads libcurl and makes it ready for requests from any thread (the first call does the work, later
// ones nothing); why it cannot, or empty.
std::string initialiseHttp();

// GETs the entry of (key, output) and, when it is sound, writes its bytes to destination atomically,
// as restoreFromCache does with a folder's. 404 is a miss; any other failure of the server sets failure
// (then the lookup is a miss that is unavailable). Fails only when destination cannot be written.
Result<CacheLookup> restoreFromServer(const HttpServer& server, const std::string& key, const std::string& output,
                                      const std::string& destination, ServerFailure& failure);

// PUTs the file at source, whose XXH3-128 is hash, as the entry of (key, output), with its Content-Length.
// Done when the server took it (2xx). When the server fails, failure says how and the Error why; a
// source that cannot be read (or an output name too long for a header) is an Error alone.
Status storeOnServer(const HttpServer& server, const std::string& key, const std::string& output,
                     const std::string& source, const std::string& hash, ServerFailure& failure);

}  // namespace heightpack::detail
