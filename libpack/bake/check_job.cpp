#include "heightpack/bake/check_job.hpp"

#include <algorithm>
#include <optional>

#include "heightpack/io/files.hpp"
#include "heightpack/io/image_write.hpp"
#include "heightpack/io/info.hpp"
#include "heightpack/io/pixel_type.hpp"
#include "heightpack/io/read.hpp"

#include "job_steps.hpp"

namespace heightpack {

namespace {

Image channelZero(const Image& image) {
    if (image.channels == 1) return image;
    Image out(image.width, image.height, 1);
    for (size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] = image.pixels[i * image.channels];
    return out;
}

void keepWorst(SeamScore& worst, const SeamScore& s) {
    if (!s.measured) return;
    if (!worst.measured) {
        worst = s;
        return;
    }
    worst.value = std::max(worst.value, s.value);
    worst.slope = std::max(worst.slope, s.slope);
}

// Puts the seams of a chain whose level 0 is level0 into report: levels, worst, failure and the verdict;
// and level0's look.
void scoreChain(ChainSeams seams, const Image& level0, const SeamOptions& seamOptions, const CheckOptions& options,
                CheckReport& report) {
    if (options.progress) options.progress("check", 0.0);
    report.tiles = seams.tiles();
    report.failure = seams.failure;
    report.levels = std::move(seams.levels);
    for (const LevelSeams& s : report.levels) {
        keepWorst(report.worst.leftRight, s.leftRight);
        keepWorst(report.worst.topBottom, s.topBottom);
    }
    report.worst.width = level0.width;
    report.worst.height = level0.height;
    if (report.packing && !report.packing->consistent) report.tiles = false;
    report.look = measureTileLook(level0, {nullptr, seamOptions.threads, std::nullopt});
    report.lookThresholds = options.look;
    report.lookFails = options.lookFails;
}

}  // namespace

double sampleQuantum(const SourceInfo& source) {
    return source.integerBits > 0 ? 1.0 / double((1 << source.integerBits) - 1) : 0.0;
}

ChainSeams measureSeamChain(const Image& heights, const MipOptions& mip, double threshold, const SeamOptions& seams,
                            std::string* note) {
    const bool powers = isPowerOfTwo(heights.width) && isPowerOfTwo(heights.height);
    if (!powers && note) *note = "sides are not powers of two: level 0 only";
    return measureChainSeams(heights, powers ? generateMipLevelsBelow(heights, mip) : std::vector<Image>{}, threshold, seams);
}

CheckReport checkHeights(const Image& heights, const SourceInfo& source, const CheckOptions& options) {
    CheckReport report;
    report.input = source.path;
    report.kind = "image";
    report.source = source;
    report.threshold = options.threshold;
    if (options.progress) options.progress("mip", 0.0);
    SeamOptions seamOptions;
    seamOptions.threads = options.mip.threads;
    seamOptions.quantum = sampleQuantum(source);
    scoreChain(measureSeamChain(heights, options.mip, options.threshold, seamOptions, &report.note), heights, seamOptions, options, report);
    if (!report.note.empty()) report.noteFix = Fix::ResizeToPowerOfTwo;  // pack would have to resize
    return report;
}

Result<CheckReport> checkFile(const std::string& path, const CheckOptions& options) {
    if (!options.previewPath.empty())
        if (Status s = checkWritable(options.previewPath); !s) return s.error();
    CheckReport report;
    report.input = path;
    report.threshold = options.threshold;

    // A texture with mip levels is checked as stored; anything else gets the chain pack would make.
    auto progress = [&](std::string_view stage, double f) {
        if (options.progress) options.progress(stage, f);
    };
    progress("load", 0.0);
    std::vector<Image> chain;
    SeamOptions seamOptions;
    seamOptions.threads = options.mip.threads;
    // A flat image is decoded once, by loadInput: its headers alone say it has one level. A texture with
    // levels (or a KTX2 or DDS, whose reader decodes as it reads) is read whole.
    const auto container = containerForPath(path);
    const bool gpuContainer = container && *container != Container::Exr;
    size_t levels = 0;
    if (!gpuContainer) {
        auto layout = readTextureLevels(path, options.load.silenceDecoderMessages);
        if (!layout) return layout.error();
        levels = layout->levelSizes.size();
    }
    std::optional<TextureFile> texture;
    if (gpuContainer || levels > 1) {
        auto file = readTextureFile(path, options.load.silenceDecoderMessages);
        if (!file) return file.error();  // unreadable or damaged at any level: no verdict on part of it
        texture = std::move(*file);
    }
    if (texture && texture->levels.size() > 1) {
        const TextureDescription& described = texture->description;
        report.kind = described.kind == TextureKind::Image ? "texture" : layoutWord(described);
        if (described.layout == Layout::Neighbour4 && texture->levels[0].channels == 4)
            report.packing = checkPacking(texture->levels, described.wrap);
        for (const Image& level : texture->levels) {
            chain.push_back(channelZero(level));
            // A NaN is bad input, not a seam: the verdict would be meaningless.
            if (Status s = checkFinite(chain.back(), path, 0, "level " + std::to_string(chain.size() - 1)); !s)
                return s.error();
        }
        scoreChain(measureChainSeams(chain, options.threshold, seamOptions), chain[0], seamOptions, options, report);
    } else {
        auto loaded = detail::loadInput(path, options.load, options.mip.threads);
        if (!loaded) return loaded.error();
        report = checkHeights(loaded->heights, loaded->source, options);
        report.input = path;
        chain = {std::move(loaded->heights)};  // level 0, for the preview
    }

    if (!options.previewPath.empty()) {
        FlatImageOptions flat;
        flat.bits = 8;
        flat.attributes = {attribute(attr::layout, attr::seamPreview), attribute(attr::source, path),
                           attribute(attr::threshold, static_cast<float>(options.threshold))};
        if (Status s = writeFlatImage(options.previewPath, seamPreview(chain[0], report.worst, options.threshold), flat);
            !s)
            return s.error();
    }
    return report;
}

}  // namespace heightpack
