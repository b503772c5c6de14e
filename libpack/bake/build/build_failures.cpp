#include "build_failures.hpp"

#include <cstdio>
#include <filesystem>
#include <new>

#include "heightpack/io/files.hpp"

#include "manifest_hints.hpp"

namespace heightpack::detail {

namespace fs = std::filesystem;

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
    // reading the heights from the channel the manifest names, and a float EXR (one channel) holds whatever
    // heights the fix needs. A frame's tiled map is that frame of a tiled sequence, NAME_tiled.EXR, which
    // is what the manifest's source then names (relative to the manifest, as it reads its sources). The
    // shell words the tile command.
    const fs::path input(s.report.input);
    const bool frame = s.report.frame >= 0;
    const fs::path stem = frame ? input.stem().stem() : input.stem();  // a frame's NAME.0003 is frame 3 of NAME
    const fs::path tiledSource = input.parent_path() / (stem.string() + "_tiled.exr");
    const std::string tiled = frame ? frameFileName(tiledSource.string(), s.report.frame, 2) : tiledSource.string();
    const fs::path folder = fs::path(manifestPath).parent_path();
    fs::path sourceValue = folder.empty() ? tiledSource : tiledSource.lexically_relative(folder);
    if (sourceValue.empty()) sourceValue = fs::absolute(tiledSource);
    char threshold[32] = "";
    if (s.check.threshold != kDefaultSeamThreshold) std::snprintf(threshold, sizeof threshold, "%g", s.check.threshold);
    const std::string filter = s.check.mip.filter != Filter::Kaiser ? filterName(s.check.mip.filter) : "";
    const ChannelSelect channel = s.check.load.channel;
    const std::string channelText = channel == ChannelSelect::Named  ? s.check.load.channelName
                                    : channel == ChannelSelect::Auto ? std::string()
                                                                     : std::string(nameOf(channel));
    return withFix(badInput(manifestPath + ":" + std::to_string(s.report.line), what,
                            "make it tile with heightpack tile (same channel, filter and threshold) and use that as "
                            "the source, or set tileable = false if it is not meant to tile"),
                   Fix::MakeTileable,
                   {s.report.input, tiled, filter, threshold, channelText, sourceValue.generic_string(),
                    frame ? "sequence" : ""});
}

}  // namespace heightpack::detail
