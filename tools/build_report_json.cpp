#include "build_report_json.hpp"

#include <filesystem>

#include "cache_report.hpp"
#include "look_report.hpp"
#include "report_json.hpp"

namespace heightpack::cli {

namespace {

namespace fs = std::filesystem;

nlohmann::json assetJson(const AssetReport& a, double threshold) {
    nlohmann::json j = {{"name", a.name},
                        {"kind", a.kind},
                        {"line", a.line},
                        {"input", a.input.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.input)},
                        {"inputHash", a.inputHash.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.inputHash)},
                        {"output", a.output},
                        {"key", a.key},
                        {"status", assetStatusName(a.status)},
                        {"seconds", a.seconds}};
    if (a.frame >= 0) j["frame"] = a.frame;
    if (a.cache.looked) {
        auto reason = [](const std::string& why) { return why.empty() ? nlohmann::json(nullptr) : nlohmann::json(why); };
        j["cache"] = {{"hit", a.cache.hit}, {"stored", a.cache.stored}, {"rejected", reason(a.cache.rejected)},
                      {"storeFailed", reason(a.cache.storeFailed)}, {"unavailable", a.cache.unavailable || a.cache.storeUnavailable}};
    }
    if (a.check) {
        const AssetCheck& c = *a.check;
        j["check"] = {{"ran", c.ran}, {"passedEarlier", c.earlier}, {"tiles", c.tiles}};
        if (c.ran) {
            j["check"]["worst"] = {{"leftRight", seamScoreJson(c.worst.leftRight, threshold)},
                                   {"topBottom", seamScoreJson(c.worst.topBottom, threshold)}};
            j["check"]["look"] = lookJson(c.look, c.lookThresholds);
        }
        if (!c.failure.empty()) j["check"]["failure"] = c.failure;
    } else {
        j["check"] = nullptr;
    }
    return j;
}

}  // namespace

nlohmann::json buildReportJson(const BuildReport& r, double threshold, bool checkOnly) {
    nlohmann::json assets = nlohmann::json::array();
    for (const AssetReport& a : r.assets) assets.push_back(assetJson(a, threshold));
    nlohmann::json failures = nlohmann::json::array();
    for (const Error& e : r.checkFailures) failures.push_back({{"where", e.path}, {"what", e.what}});
    return {{"name", r.material},
            {"manifest", r.manifest},
            {"outputDir", checkOnly ? nlohmann::json(nullptr) : nlohmann::json(r.outputDir)},
            {"material", checkOnly ? nlohmann::json(nullptr)
                                    : nlohmann::json((fs::path(r.outputDir) / kMaterialFile).string())},
            {"materialWritten", r.materialWritten},
            {"rebuilt", r.rebuilt()},
            {"upToDate", r.upToDate()},
            {"restored", r.restored()},
            {"cache", cacheCountsJson(r.cache())},
            {"staleTemporariesRemoved", r.staleTemporariesRemoved},
            {"checkFailures", failures},
            {"assets", assets}};
}

}  // namespace heightpack::cli
