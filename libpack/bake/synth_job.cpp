#include "heightpack/bake/synth_job.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <tuple>

#include "heightpack/core/sea/cascades.hpp"
#include "heightpack/core/parallel.hpp"
#include "heightpack/core/sea/sea_report.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/image_write.hpp"

namespace heightpack {

namespace {

std::string formatted(const char* format, double a, double b, double c = 0.0) {
    char text[96];
    std::snprintf(text, sizeof text, format, a, b, c);
    return text;
}

// The header attributes that describe the sea (the same in every file of a tile).
std::vector<ExrAttribute> seaAttributes(const SynthOptions& options, const SpectrumOptions& s, const SynthTileReport& r,
                                        int cascade, int count) {
    std::vector<ExrAttribute> a = {
        attribute(attr::layout, attr::synthesised),
        attribute(attr::spectrum, s.model),
        attribute(attr::wind, formatted("%.4g m/s from %.4g deg", s.windSpeed, s.windDirection)),
        attribute(attr::spreading, s.spreading),
        attribute(attr::tileWidth, static_cast<float>(s.tileSize)),
        attribute(attr::seed, std::to_string(s.seed)),
        attribute(attr::significantWaveHeight, static_cast<float>(r.significantWaveHeight)),
        attribute(attr::spectrumWaveHeight, static_cast<float>(r.expectedSignificantWaveHeight)),
        attribute(attr::peakPeriod, static_cast<float>(r.peakPeriod)),
        attribute(attr::peakWavelength, static_cast<float>(r.peakWavelength)),
        attribute(attr::steepness, static_cast<float>(r.steepness)),
        attribute(attr::version, options.version),
    };
    if (s.model == SpectrumModel::Jonswap) a.push_back(attribute(attr::fetch, static_cast<float>(s.fetch)));
    if (s.depth > 0.0) a.push_back(attribute(attr::depth, static_cast<float>(s.depth)));
    if (s.swell.significantHeight > 0.0)
        a.push_back(attribute(attr::swell, formatted("%.4g m, %.4g s, %.4g deg", s.swell.significantHeight,
                                                     s.swell.peakPeriod, s.swell.direction)));
    if (count > 1) {
        a.push_back(attribute(attr::cascade, std::to_string(cascade) + "/" + std::to_string(count)));
        a.push_back(attribute(attr::bandLow, static_cast<float>(r.bandLow)));
        a.push_back(attribute(attr::bandHigh, static_cast<float>(r.bandHigh)));
    }
    if (r.foldFraction || r.maxShift) a.push_back(attribute(attr::choppiness, static_cast<float>(options.choppiness)));
    if (r.foldFraction) a.push_back(attribute(attr::foldFraction, static_cast<float>(*r.foldFraction)));
    if (r.maxShift) a.push_back(attribute(attr::maxShift, static_cast<float>(*r.maxShift)));
    if (r.shiftBound) a.push_back(attribute(attr::shiftBound, static_cast<float>(*r.shiftBound)));
    if (options.foam) {
        a.push_back(attribute(attr::foamThreshold, static_cast<float>(options.foamOptions.threshold)));
        a.push_back(attribute(attr::foamDecay, static_cast<float>(options.foamOptions.decay)));
        a.push_back(attribute(attr::foamBuildUp, static_cast<float>(options.foamOptions.buildUp)));
    }
    return a;
}

using ProgressFn = std::function<void(std::string_view, double)>;

// What a frame's image holds, in this order: the heights, then Dx and Dy, then the Jacobian (where the
// foam goes once worked out from it); each only when asked for or needed by the report.
struct FrameLayout {
    bool shift = false, jacobian = false;
    int channels() const { return 1 + (shift ? 2 : 0) + (jacobian ? 1 : 0); }
    int jacobianChannel() const { return shift ? 3 : 1; }
};

// The first `count` channels of image: what is written when the report needed more than the file holds.
Image firstChannels(const Image& image, int count, int threads) {
    Image out(image.width, image.height, count);
    parallelFor(image.height, threads, [&](int y0, int y1) {
        for (size_t i = size_t(y0) * image.width; i < size_t(y1) * image.width; ++i)
            std::copy_n(&image.pixels[i * image.channels], count, &out.pixels[i * count]);
    });
    return out;
}

// One tile: every frame computed, then foam over the loop, then the numbers, then the files. Each frame's
// fields are transformed straight into its interleaved image, the one the file is written from, and the
// amplitudes are let go before writing: with shift and foam, 20 bytes a texel at the peak (the image
// and the half spectrum; the transforms work in the heights' channel until the heights are written last).
Result<SynthTileReport> synthTile(const std::string& output, const SpectrumOptions& s, const SynthOptions& options,
                                  int cascade, int count, const ProgressFn& progress, StagedOutputs* staged) {
    const bool metres = lowerExtension(output) == ".exr";
    const FrameLayout layout{options.shift || options.foam || options.report, options.foam || options.report};
    const int frames = options.frames, channels = layout.channels(), jc = layout.jacobianChannel();
    const double period = s.loopPeriod;
    auto timeOf = [&](int f) { return frames > 1 ? f * period / frames : 0.0; };
    auto share = [&](double f) { return (cascade + f) / count; };

    std::vector<Image> images;
    double resolvedVariance = 0.0, shiftBound = 0.0;
    {
        // A single frame is t = 0 only: the ocean keeps half the amplitudes.
        const Ocean ocean(s, OceanOptions{options.threads, frames > 1});
        for (int f = 0; f < frames; ++f) {
            progress("synth", share(double(f) / frames));
            Image& image = images.emplace_back(s.size, s.size, channels);
            float* first = image.pixels.data();
            SeaFieldTargets to;
            to.heights = {first, channels};
            if (layout.shift) to.shiftX = {first + 1, channels}, to.shiftY = {first + 2, channels};
            if (layout.jacobian) to.jacobian = {first + jc, channels};
            ocean.fieldsInto(timeOf(f), to, options.choppiness, options.threads);
        }
        resolvedVariance = ocean.resolvedVariance();
        shiftBound = ocean.shiftBound();
    }

    SynthTileReport report;
    report.tileSize = s.tileSize;
    if (count > 1) report.bandLow = s.bandLow, report.bandHigh = s.bandHigh;

    const SeaStateSummary summary = summariseSeaState(s, resolvedVariance);
    report.expectedSignificantWaveHeight = summary.significantWaveHeight;
    report.peakPeriod = summary.peakPeriod;
    report.peakWavelength = summary.peakWavelength;
    report.steepness = summary.steepness;
    report.minHeight = report.maxHeight = images[0].pixels[0];
    double folds = 0.0, moved = 0.0;
    const FrameChannels at{0, layout.shift ? 1 : -1, layout.jacobian ? jc : -1};
    for (int f = 0; f < frames; ++f) {
        const FrameNumbers numbers = frameNumbers(images[f], at, options.choppiness, options.threads);
        if (f == 0) report.significantWaveHeight = numbers.significantWaveHeight;
        report.minHeight = std::min(report.minHeight, double(numbers.minHeight));
        report.maxHeight = std::max(report.maxHeight, double(numbers.maxHeight));
        folds += numbers.foldFraction / frames;
        moved = std::max(moved, numbers.largestShift);
    }
    if (layout.jacobian) report.foldFraction = folds;
    if (layout.shift) {
        report.maxShift = moved;
        report.shiftBound = std::abs(options.choppiness) * shiftBound;
    }

    // The Jacobian's channel becomes the foam's coverage: texel by texel for a frozen sea, through the
    // loop's densities for a sequence.
    if (options.foam) {
        auto eachTexel = [&](Image& image, const auto& change) {
            parallelFor(image.height, options.threads, [&](int y0, int y1) {
                for (size_t i = size_t(y0) * image.width; i < size_t(y1) * image.width; ++i) change(i, image.pixels[i * channels + jc]);
            });
        };
        if (frames == 1 || period <= 0.0) {
            for (Image& image : images)
                eachTexel(image, [&](size_t, float& t) { t = foamCoverageOf(frozenFoamDensity(t, options.foamOptions)); });
        } else {
            std::vector<Image> jacobians;
            for (const Image& image : images) {
                Image& j = jacobians.emplace_back(image.width, image.height, 1);
                for (size_t i = 0; i < j.pixels.size(); ++i) j.pixels[i] = image.pixels[i * channels + jc];
            }
            const std::vector<std::vector<float>> foam = loopingFoamDensity(jacobians, period, options.foamOptions);
            for (int f = 0; f < frames; ++f) eachTexel(images[f], [&](size_t i, float& t) { t = foamCoverageOf(foam[f][i]); });
        }
    }

    // Integer files: one mapping onto [0,1] for the whole sequence, so frames compare.
    const double offset = metres ? 0.0 : report.minHeight;
    const double scale = metres ? 1.0 : std::max(report.maxHeight - report.minHeight, 1e-9);
    const std::vector<ExrAttribute> sea = seaAttributes(options, s, report, cascade, count);
    const bool withD = options.shift || options.foam;
    const int written = 1 + (withD ? 2 : 0) + (options.foam ? 1 : 0);
    for (int f = 0; f < frames; ++f) {
        progress("write", share(double(f) / frames));
        if (!metres)
            for (size_t i = 0; i < images[f].texelCount(); ++i) {
                float& h = images[f].pixels[i * channels];
                h = static_cast<float>((h - offset) / scale);
            }
        Image compact;
        if (written != channels) compact = firstChannels(images[f], written, options.threads);
        const Image& image = written == channels ? images[f] : compact;
        FlatImageOptions flat;
        if (withD) flat.channelNames = {"Y", layerName::dx, layerName::dy};
        if (options.foam) flat.channelNames.push_back(layerName::foam);
        flat.bits = metres ? 32 : 16;
        flat.threads = options.threads;
        flat.compression = options.compression;
        flat.attributes = sea;
        flat.attributes.push_back(attribute(attr::heightScale, static_cast<float>(scale)));
        flat.attributes.push_back(attribute(attr::heightOffset, static_cast<float>(offset)));
        if (frames > 1) {
            flat.attributes.push_back(attribute(attr::frame, std::to_string(f) + "/" + std::to_string(frames)));
            flat.attributes.push_back(attribute(attr::loopPeriod, static_cast<float>(period)));
            flat.attributes.push_back(attribute(attr::time, static_cast<float>(timeOf(f))));
        }
        const std::string path = frameFileName(output, f, frames);
        if (Status w = writeFlatImage(staged ? staged->stage(path) : path, image, flat); !w) return w.error();
        report.outputs.push_back(path);
    }
    return report;
}

}  // namespace

std::string cascadeFileName(const std::string& output, int cascade, int count) {
    if (count <= 1) return output;
    const std::filesystem::path p(output);
    return (p.parent_path() / (p.stem().string() + "_c" + std::to_string(cascade) + p.extension().string())).string();
}

Result<SynthReport> synthesise(const std::string& output, const SynthOptions& options) {
    // The shift and foam are channels beside the heights: only an EXR holds them.
    // Foam first: it brings the shift with it, so a foam request names foam.
    for (const auto& [asked, what, channels] : {std::tuple{options.foam, "foam", "Y, Dx, Dy, Foam"},
                                                std::tuple{options.shift, "shift", "Y, Dx, Dy"}})
        if (asked && lowerExtension(output) != ".exr")
            return withFix(inconsistentOptions(output, std::string("the ") + what + " is written as channels " + channels +
                                                           " of an EXR, and this is not one",
                                               "name the output .exr"),
                           Fix::CompanionsNeedExr, {what});
    const int count = std::max(1, options.cascades);
    for (int c = 0; c < count; ++c)
        for (int f = 0; f < options.frames; ++f)
            if (Status s = checkWritable(frameFileName(cascadeFileName(output, c, count), f, options.frames)); !s)
                return s.error();
    const ProgressFn progress = [&](std::string_view stage, double f) {
        if (options.progress) options.progress(stage, f);
    };
    std::vector<SpectrumOptions> tiles;
    if (count == 1) {
        tiles.push_back(options.spectrum);
    } else {
        const SpectrumOptions& s = options.spectrum;
        for (const CascadeBand& band : cascadeBands(s.tileSize, s.size, count, s.seed)) tiles.push_back(cascadeOptions(s, band));
    }
    // Several files (frames, cascades) land together once all are written: a failure leaves none of them.
    StagedOutputs staged;
    const bool stage = count > 1 || options.frames > 1;
    SynthReport report;
    double variance = 0.0, expected = 0.0;
    for (int c = 0; c < count; ++c) {
        auto tile = synthTile(cascadeFileName(output, c, count), tiles[c], options, c, count, progress, stage ? &staged : nullptr);
        if (!tile) return tile.error();
        report.outputs.insert(report.outputs.end(), tile->outputs.begin(), tile->outputs.end());
        variance += tile->significantWaveHeight * tile->significantWaveHeight / 16.0;
        expected += tile->expectedSignificantWaveHeight * tile->expectedSignificantWaveHeight / 16.0;
        // The sum's extremes are at most the sum of the tiles' extremes: a bound, with cascades.
        report.minHeight += tile->minHeight;
        report.maxHeight += tile->maxHeight;
        report.tiles.push_back(std::move(*tile));
    }
    if (Status committed = staged.commit(); !committed) return committed.error();
    report.significantWaveHeight = 4.0 * std::sqrt(variance);
    report.expectedSignificantWaveHeight = 4.0 * std::sqrt(expected);
    progress("write", 1.0);
    return report;
}

}  // namespace heightpack
