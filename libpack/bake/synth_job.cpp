#include "heightpack/bake/synth_job.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <tuple>

#include "heightpack/core/cascades.hpp"
#include "heightpack/core/parallel.hpp"
#include "heightpack/core/sea_report.hpp"
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
        attribute(attr::layout, "synthesised"),
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
    if (r.foldFraction || r.maxDisplacement) a.push_back(attribute(attr::choppiness, static_cast<float>(options.choppiness)));
    if (r.foldFraction) a.push_back(attribute(attr::foldFraction, static_cast<float>(*r.foldFraction)));
    if (r.maxDisplacement) a.push_back(attribute(attr::maxDisplacement, static_cast<float>(*r.maxDisplacement)));
    if (r.displacementBound) a.push_back(attribute(attr::displacementBound, static_cast<float>(*r.displacementBound)));
    if (options.foam) {
        a.push_back(attribute(attr::foamThreshold, static_cast<float>(options.foamOptions.threshold)));
        a.push_back(attribute(attr::foamDecay, static_cast<float>(options.foamOptions.decay)));
        a.push_back(attribute(attr::foamBuildUp, static_cast<float>(options.foamOptions.buildUp)));
    }
    return a;
}

using ProgressFn = std::function<void(std::string_view, double)>;

// One tile: every frame computed, then foam over the loop, then the numbers, then the files.
Result<SynthTileReport> synthTile(const std::string& output, const SpectrumOptions& s, const SynthOptions& options,
                                  int cascade, int count, const ProgressFn& progress, StagedOutputs* staged) {
    const bool metres = lowerExtension(output) == ".exr";
    const bool wantJacobian = options.foam || options.report;
    const bool wantDisplacement = options.displacement || wantJacobian;
    const int frames = options.frames;
    const double period = s.loopPeriod;
    auto timeOf = [&](int f) { return frames > 1 ? f * period / frames : 0.0; };
    auto share = [&](double f) { return (cascade + f) / count; };

    const Ocean ocean(s, options.threads);
    std::vector<SeaFields> fields;
    for (int f = 0; f < frames; ++f) {
        progress("synth", share(double(f) / frames));
        fields.push_back(ocean.fields(timeOf(f), {true, wantDisplacement, wantJacobian}, options.choppiness, options.threads));
    }

    SynthTileReport report;
    report.tileSize = s.tileSize;
    if (count > 1) report.bandLow = s.bandLow, report.bandHigh = s.bandHigh;
    report.significantWaveHeight = significantWaveHeight(fields[0].heights);
    const SeaStateSummary summary = summariseSeaState(s, ocean.resolvedVariance());
    report.expectedSignificantWaveHeight = summary.significantWaveHeight;
    report.peakPeriod = summary.peakPeriod;
    report.peakWavelength = summary.peakWavelength;
    report.steepness = summary.steepness;
    report.minHeight = report.maxHeight = fields[0].heights.pixels[0];
    double folds = 0.0, moved = 0.0;
    for (const SeaFields& frame : fields) {
        const auto [lo, hi] = std::minmax_element(frame.heights.pixels.begin(), frame.heights.pixels.end());
        report.minHeight = std::min(report.minHeight, double(*lo));
        report.maxHeight = std::max(report.maxHeight, double(*hi));
        if (wantJacobian) folds += foldFraction(frame.jacobian) / frames;
        if (wantDisplacement) moved = std::max(moved, largestDisplacement(frame.displacement, options.choppiness));
    }
    if (wantJacobian) report.foldFraction = folds;
    if (wantDisplacement) {
        report.maxDisplacement = moved;
        report.displacementBound = std::abs(options.choppiness) * ocean.displacementBound();
    }

    std::vector<std::vector<float>> foam;
    if (options.foam) {
        std::vector<Image> jacobians;
        for (SeaFields& frame : fields) jacobians.push_back(std::move(frame.jacobian));
        foam = loopingFoamDensity(jacobians, frames > 1 ? period : 0.0, options.foamOptions);
    }

    // Integer files: one mapping onto [0,1] for the whole sequence, so frames compare.
    const double offset = metres ? 0.0 : report.minHeight;
    const double scale = metres ? 1.0 : std::max(report.maxHeight - report.minHeight, 1e-9);
    const std::vector<ExrAttribute> sea = seaAttributes(options, s, report, cascade, count);
    const bool withD = options.displacement || options.foam;
    for (int f = 0; f < frames; ++f) {
        progress("write", share(double(f) / frames));
        const Image& h = fields[f].heights;
        const int channels = 1 + (withD ? 2 : 0) + (options.foam ? 1 : 0);
        Image image(h.width, h.height, channels);
        const Image coverage = options.foam ? foamCoverage(foam[f], h.width, h.height, options.threads) : Image();
        parallelFor(h.height, options.threads, [&](int y0, int y1) {
            for (size_t i = size_t(y0) * h.width; i < size_t(y1) * h.width; ++i) {
                float* texel = &image.pixels[i * channels];
                texel[0] = static_cast<float>((h.pixels[i] - offset) / scale);
                if (withD) texel[1] = fields[f].displacement.pixels[2 * i], texel[2] = fields[f].displacement.pixels[2 * i + 1];
                if (options.foam) texel[3] = coverage.pixels[i];
            }
        });
        FlatImageOptions flat;
        if (withD) flat.channelNames = {"Y", "Dx", "Dy"};
        if (options.foam) flat.channelNames.push_back("Foam");
        flat.bits = metres ? 32 : 16;
        flat.threads = options.threads;
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
    // Displacement and foam are channels beside the heights: only an EXR holds them.
    // Foam first: it brings the displacement with it, so a foam request names foam.
    for (const auto& [asked, what, channels] : {std::tuple{options.foam, "foam", "Y, Dx, Dy, Foam"},
                                                std::tuple{options.displacement, "displacement", "Y, Dx, Dy"}})
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
