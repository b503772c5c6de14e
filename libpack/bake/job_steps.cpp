#include "job_steps.hpp"

#include <filesystem>

#include "heightpack/io/read.hpp"

namespace heightpack::detail {

Result<LoadedInput> loadInput(const std::string& input, LoadOptions options, int threads) {
    options.threads = threads;
    auto loaded = loadHeightMap(input, options);
    if (!loaded) return loaded.error();
    LoadedInput out;
    out.hash = hashPixels(loaded->heights);
    out.heights = std::move(loaded->heights);
    out.source = std::move(loaded->source);
    return out;
}

Result<bool> ensurePowerOfTwo(Image& heights, const std::string& input, bool resize, const MipOptions& mip,
                              bool levelZeroAlone) {
    if (isPowerOfTwo(heights.width) && isPowerOfTwo(heights.height)) return false;
    const int w = nextPowerOfTwo(heights.width), h = nextPowerOfTwo(heights.height);
    if (!resize) {
        const std::string size = std::to_string(w) + "x" + std::to_string(h);
        std::string hint = "resample it to " + size;
        if (levelZeroAlone) hint += ", or write level 0 alone as an 8-bit PNG";
        return withFix(badInput(input,
                                "is " + std::to_string(heights.width) + "x" + std::to_string(heights.height) +
                                    ", but mip chains need power-of-two sides",
                                hint),
                       levelZeroAlone ? Fix::ResizeOrLevelZeroOnly : Fix::ResizeToPowerOfTwo, {size});
    }
    heights = resample(heights, w, h, mip);
    return true;
}

std::vector<ExrAttribute> commonAttributes(std::string_view layout, Wrap wrap, Filter filter, const SourceInfo& source,
                                           const std::string& hash, const std::string& version) {
    const std::string wrapText = attributeText(wrap);
    return {
        attribute(attr::layout, std::string(layout)),
        attribute(attr::wrap, wrap),
        // The standard attribute OpenImageIO's texture system reads for its wrap modes.
        {"wrapmodes", wrapText + "," + wrapText},
        attribute(attr::filter, filter),
        attribute(attr::texelCentre, 0.5f),
        // The file name only: the same input packed from another folder gives the same bytes.
        attribute(attr::source, std::filesystem::path(source.path).filename().string()),
        attribute(attr::sourceHash, hash),
        attribute(attr::version, version),
    };
}

}  // namespace heightpack::detail
