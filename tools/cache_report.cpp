#include "cache_report.hpp"

#include <cstdio>

#include "progress.hpp"

namespace heightpack::cli {

nlohmann::json cacheCountsJson(const CacheCounts& c) {
    return {{"hits", c.hits}, {"misses", c.misses}, {"stored", c.stored}, {"rejected", c.rejected}, {"errors", c.errors}};
}

nlohmann::json cacheReportJson(const CacheOptions& cache, const CacheCounts& counts, const CacheTrim& trim,
                               const std::vector<CacheOutage>& outages) {
    nlohmann::json j = cacheCountsJson(counts);
    j["backend"] = nameOf(cache.location->backend);
    j["location"] = cache.location->where;
    j["mode"] = nameOf(cache.mode);
    nlohmann::json why = nlohmann::json::array();
    for (const CacheOutage& o : outages) why.push_back(o.why);
    j["unavailable"] = outages.empty() ? nlohmann::json(nullptr) : why;
    if (cache.location->backend == CacheBackend::Folder) {
        j["evicted"] = trim.removed;
        j["bytes"] = trim.bytesLeft;
    }
    return j;
}

void printCacheSummary(const CacheOptions& cache, const CacheCounts& c, const CacheTrim& trim) {
    std::printf("cache %s (%s, %s): %d hit(s), %d miss(es), %d stored, %d rejected, %d error(s)",
                cache.location->where.c_str(), nameOf(cache.location->backend), nameOf(cache.mode), c.hits, c.misses,
                c.stored, c.rejected, c.errors);
    if (cache.location->backend == CacheBackend::Folder && cache.mode == CacheMode::ReadWrite)
        std::printf("; %d evicted, %.1f MiB kept", trim.removed, static_cast<double>(trim.bytesLeft) / (1 << 20));
    std::printf("\n");
}

void warnAboutEntries(const BuildReport& r, const SharedCache& cache) {
    for (const AssetReport& a : r.assets) {
        const std::string entry = cache.entryAddress(a.key, a.output);
        if (!a.cache.rejected.empty()) {
            clearProgressLine();
            std::fprintf(stderr, "heightpack: warning: %s: cache entry for %s not used: %s; baked%s\n", entry.c_str(),
                         a.output.c_str(), a.cache.rejected.c_str(), a.cache.stored ? " and stored again" : "");
        }
        if (!a.cache.storeFailed.empty()) {
            clearProgressLine();
            std::fprintf(stderr, "heightpack: warning: %s not stored in the cache: %s\n", a.output.c_str(),
                         a.cache.storeFailed.c_str());
        }
    }
}

void warnAboutOutages(const CacheOptions& cache, const std::vector<CacheOutage>& outages) {
    for (const CacheOutage& o : outages) {
        clearProgressLine();
        std::fprintf(stderr, "heightpack: warning: cache %s %s; %s\n", cache.location->where.c_str(), o.why.c_str(),
                     o.storesOnly ? "nothing more was stored in it" : "the build went on without it");
    }
}

}  // namespace heightpack::cli
