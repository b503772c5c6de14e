// What `build` says about its shared cache, as text and JSON: the counts per backend, the entries it did
// not trust or could not store, and why it stopped using a cache. Only where the cache is (a folder, or
// a server's URL without credentials) is ever printed.
#pragma once

#include <nlohmann/json.hpp>

#include <vector>

#include "heightpack/bake/build/build_report.hpp"
#include "heightpack/bake/build/cache_session.hpp"

namespace heightpack::cli {

// {"hits", "misses", "stored", "rejected", "errors"}.
nlohmann::json cacheCountsJson(const CacheCounts& counts);

// The build's "cache": backend, location, mode, the counts, why it was unavailable (null when it was
// not), and for a folder what trimming left (evicted, bytes).
nlohmann::json cacheReportJson(const CacheOptions& cache, const CacheCounts& counts, const CacheTrim& trim,
                               const std::vector<CacheOutage>& outages);

// "cache LOCATION (BACKEND, MODE): N hit(s), N miss(es), N stored, N rejected, N error(s)[; folder trim]" on stdout.
void printCacheSummary(const CacheOptions& cache, const CacheCounts& counts, const CacheTrim& trim);

// One warning on stderr per entry not trusted and per output not stored in a folder: the build went on
// (the output was baked), but a person should know the cache is not doing its job.
void warnAboutEntries(const BuildReport& report, const SharedCache& cache);

// One warning on stderr per outage: the cache (named) stopped being used, and why.
void warnAboutOutages(const CacheOptions& cache, const std::vector<CacheOutage>& outages);

}  // namespace heightpack::cli
