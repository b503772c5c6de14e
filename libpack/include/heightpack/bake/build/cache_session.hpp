// A build's use of its shared cache, whichever backend holds it: restores and stores go through one
// object that every job of every material shares, so that a cache found unusable once (a server down,
// refusing or stalling) is not asked again: the build goes on without it, and says why once. A cache only
// saves time; it never fails a build, except a folder to write that is not one (judged before any work).
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/bake/build/cache_options.hpp"
#include "heightpack/bake/build/shared_cache.hpp"
#include "heightpack/core/result.hpp"

namespace heightpack {

// Why a build stopped using its cache, or part of it.
struct CacheOutage {
    std::string why;          // in words without the server's credentials: "refuses connections (...)"
    bool storesOnly = false;  // the server refused to store; restoring from it went on
};

// What storing one output did.
struct CacheStore {
    bool stored = false;
    bool unavailable = false;  // not stored: the cache was down or refused (the outage says why)
    std::string failed;        // not stored for a reason of its own (a folder that could not be written): why
};

class SharedCache {
public:
    // The cache options.location names. A folder to read and write is made if missing and must be
    // writable: else CannotWrite, before any work. A folder only to read that is not one is an outage
    // (the build goes on without it). A server is not asked anything yet.
    static Result<std::shared_ptr<SharedCache>> open(const CacheOptions& options);

    const CacheOptions& options() const { return options_; }
    const CacheLocation& location() const { return *options_.location; }

    // Where the entry of (key, output) is or would be: its file, or its URL (without credentials).
    std::string entryAddress(const std::string& key, const std::string& output) const;

    // Copies the cache's sound entry of (key, output) to destination, as restoreFromCache does. A cache
    // that is down (now or earlier in this build) gives a miss marked unavailable. Fails only when
    // destination cannot be written.
    Result<CacheLookup> restore(const std::string& key, const std::string& output, const std::string& destination);

    // Stores the file at source, whose XXH3-128 is hash, as the entry of (key, output): nothing in
    // read-only mode or once the cache is down.
    CacheStore store(const std::string& key, const std::string& output, const std::string& source,
                     const std::string& hash);

    // A folder read and written: its least recently used entries beyond the size limit removed. Else
    // nothing (a server keeps its own size; a read-only cache is not written).
    CacheTrim trim();

    // What made the build stop using the cache, in the order it happened: at most one outage of reading
    // and writing and one of writing alone.
    std::vector<CacheOutage> outages() const;

    explicit SharedCache(CacheOptions options);

private:
    void fail(CacheOutage outage);
    bool down() const;
    bool storesRefused() const;

    CacheOptions options_;
    mutable std::mutex mutex_;
    std::vector<CacheOutage> outages_;
};

}  // namespace heightpack
