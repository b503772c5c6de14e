#include "build_failures.hpp"

#include <cstdio>
#include <filesystem>
#include <new>

#include "manifest_hints.hpp"

namespace heightpack::detail {

std::string describeFailure(const CheckReport& r) {
    if (r.failure) return describeSeamFailure(*r.failure, r.threshold);
    if (r.packing && !r.packing->consistent) return "its packing is inconsistent";
    return "it fails the check";
}

void guarded(Step& s, const std::function<void()>& body) {
    try {
        body();
    } catch (const std::bad_alloc&) {
        s.error = withFix(Error{ErrorKind::Internal, s.report.input, "out of memory", "run fewer jobs or threads at once"},
                          Fix::FewerJobs);
    } catch (const std::exception& e) {
        s.error = Error{ErrorKind::Internal, s.report.input, std::string("internal error: ") + e.what(), "please report this"};
    }
}

Error inAsset(Error e, const Step& s, const std::string& manifestPath) {
    e = inManifestTerms(std::move(e));
    e.hint += (e.hint.empty() ? "" : "; ") + std::string("asset '") + s.report.name + "' of " + manifestPath + ":" +
              std::to_string(s.report.line);
    return e;
}

Error tileFailure(const Step& s, const std::string& manifestPath) {
    std::string what = s.report.kind + " '" + s.report.name + "'";
    if (s.report.frame >= 0) what += " frame " + std::to_string(s.report.frame);
    what += " (" + s.report.input + ") does not tile: " + s.report.check->failure;
    // The fix that works: tile judges with the same measure and threshold, on the chain this filter makes,
    // and a float EXR holds whatever heights the fix needs. The shell words the tile command.
    const std::filesystem::path source(s.report.input);
    const std::string tiled = (source.parent_path() / (source.stem().string() + "_tiled.exr")).string();
    char threshold[32] = "";
    if (s.check.threshold != kDefaultSeamThreshold) std::snprintf(threshold, sizeof threshold, "%g", s.check.threshold);
    const std::string filter = s.check.mip.filter != Filter::Kaiser ? filterName(s.check.mip.filter) : "";
    return withFix(badInput(manifestPath + ":" + std::to_string(s.report.line), what,
                            "make it tile with heightpack tile (same filter and threshold) and use that as the "
                            "source, or set tileable = false if it is not meant to tile"),
                   Fix::MakeTileable, {s.report.input, tiled, filter, threshold});
}

}  // namespace heightpack::detail
