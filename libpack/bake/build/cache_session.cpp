#include "heightpack/bake/build/cache_session.hpp"

#include <filesystem>
#include <utility>

#include "cache_entry.hpp"
#include "http_cache.hpp"

namespace heightpack {

namespace fs = std::filesystem;

namespace {

detail::HttpServer serverOf(const CacheOptions& options) {
    const CacheLocation& where = *options.location;
    return {where.where, where.user, where.password, options.token, options.connectMilliseconds, options.stallSeconds};
}

}  // namespace

SharedCache::SharedCache(CacheOptions options) : options_(std::move(options)) {}

Result<std::shared_ptr<SharedCache>> SharedCache::open(const CacheOptions& options) {
    if (!options.location)
        return Error{ErrorKind::Internal, "", "a shared cache was opened without a location", "please report this"};
    auto cache = std::make_shared<SharedCache>(options);
    const CacheLocation& where = *options.location;
    switch (where.backend) {
        case CacheBackend::Folder: {
            if (options.mode == CacheMode::ReadWrite) {
                if (Status s = openCache(where.where); !s) return s.error();
                break;
            }
            std::error_code ec;
            if (!fs::is_directory(where.where, ec)) cache->fail({"is not a folder (a cache only read is not made)", false});
            break;
        }
        case CacheBackend::Http:
            if (std::string why = detail::initialiseHttp(); !why.empty()) cache->fail({why, false});
            break;
    }
    return cache;
}

std::string SharedCache::entryAddress(const std::string& key, const std::string& output) const {
    if (location().backend == CacheBackend::Folder) return cacheEntryPath(location().where, key, output);
    return location().where + "/" + detail::entryName(key, output);
}

Result<CacheLookup> SharedCache::restore(const std::string& key, const std::string& output, const std::string& destination) {
    if (down()) return CacheLookup{false, {}, {}, true};
    if (location().backend == CacheBackend::Folder)
        return restoreFromCache(location().where, key, output, destination, options_.mode == CacheMode::ReadWrite);
    detail::ServerFailure failure;
    auto found = detail::restoreFromServer(serverOf(options_), key, output, destination, failure);
    // A server that refuses to be read is as useless as one that is down: both stop every request.
    if (failure.trouble != detail::ServerTrouble::None) fail({failure.why, false});
    return found;
}

CacheStore SharedCache::store(const std::string& key, const std::string& output, const std::string& source,
                              const std::string& hash) {
    CacheStore result;
    if (options_.mode == CacheMode::ReadOnly) return result;
    if (down() || storesRefused()) {
        result.unavailable = true;
        return result;
    }
    if (location().backend == CacheBackend::Folder) {
        Status stored = storeInCache(location().where, key, output, source, hash);
        result.stored = stored.ok();
        if (!stored) result.failed = stored.error().path + ": " + stored.error().what;
        return result;
    }
    detail::ServerFailure failure;
    Status stored = detail::storeOnServer(serverOf(options_), key, output, source, hash, failure);
    result.stored = stored.ok();
    // A server that is down stops everything; one that only refuses to store is still read.
    if (failure.trouble == detail::ServerTrouble::Down) fail({failure.why, false});
    if (failure.trouble == detail::ServerTrouble::Refused) fail({"refuses to store entries: " + failure.why, true});
    if (failure.trouble != detail::ServerTrouble::None)
        result.unavailable = true;
    else if (!stored)
        result.failed = stored.error().path + ": " + stored.error().what;
    return result;
}

CacheTrim SharedCache::trim() {
    if (location().backend != CacheBackend::Folder || options_.mode != CacheMode::ReadWrite || down()) return {};
    return trimCache(location().where, options_.sizeLimit);
}

std::vector<CacheOutage> SharedCache::outages() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return outages_;
}

void SharedCache::fail(CacheOutage outage) {
    std::lock_guard<std::mutex> lock(mutex_);
    // The first of each kind is the one to tell: jobs in flight when a server goes fail with it too.
    for (const CacheOutage& known : outages_)
        if (!known.storesOnly || outage.storesOnly) return;
    outages_.push_back(std::move(outage));
}

bool SharedCache::down() const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const CacheOutage& o : outages_)
        if (!o.storesOnly) return true;
    return false;
}

bool SharedCache::storesRefused() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return !outages_.empty();
}

}  // namespace heightpack
