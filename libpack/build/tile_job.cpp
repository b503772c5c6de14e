#include "heightpack/build/tile_job.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "heightpack/build/check_job.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/image_write.hpp"

#include "job_steps.hpp"

namespace heightpack {

const char* tileMethodName(TileMethod method) {
    switch (method) {
        case TileMethod::Periodic: return "periodic";
        case TileMethod::Moisan: return "moisan";
        case TileMethod::Crossfade: return "crossfade";
        case TileMethod::Mirror: return "mirror";
    }
    return "?";
}

namespace {

bool holdsFloat(const std::string& ext) { return ext == ".exr" || ext == ".tif" || ext == ".tiff"; }

std::string verdictText(const ChainSeams& seams) {
    return seams.tiles() ? "tiles at every level" : describeSeamFailure(*seams.failure, seams.threshold);
}

// Whether every height is a whole number of steps of a bits-bit type, inside [0,1].
bool exactIn(const Image& map, int bits) {
    const double steps = bits == 8 ? 255.0 : 65535.0;
    return std::all_of(map.pixels.begin(), map.pixels.end(), [&](float v) {
        const double s = double(v) * steps;
        return v >= 0.0f && v <= 1.0f && std::abs(s - std::round(s)) < 1e-3;
    });
}

double span(const Image& map) {
    const auto [low, high] = std::minmax_element(map.pixels.begin(), map.pixels.end());
    return double(*high) - *low;
}

// How a result will be stored: the type asked for, else the input's (a PNG holds no floats: 16 bits there),
// widened to float where an integer type would clip (or round a map that should stay unchanged) and the
// format holds floats; `storable` is false where it cannot be stored faithfully at all.
struct Storage {
    int bits = 32;          // the type before widening
    bool explicitBits = false;  // --depth asked for it: never widened
    bool floatFormat = true;    // the output's format holds floats

    struct Choice {
        int bits = 32;
        bool widened = false;
        bool storable = true;
    };
    Choice choose(const Image& result, bool unchanged) const {
        Choice c{bits, false, true};
        if (bits == 32) return c;
        const auto [low, high] = std::minmax_element(result.pixels.begin(), result.pixels.end());
        const bool inRange = *low >= 0.0f && *high <= 1.0f;
        if (inRange && !(unchanged && !exactIn(result, bits))) return c;
        if (!floatFormat || explicitBits) return Choice{bits, false, false};
        return Choice{32, true, true};
    }
    // The heights as that type stores them.
    static Image rounded(Image result, int bits) {
        if (bits == 32) return result;
        const double steps = bits == 8 ? 255.0 : 65535.0;
        for (float& v : result.pixels) v = static_cast<float>(std::round(double(v) * steps) / steps);
        return result;
    }
    static double quantum(int bits) { return bits == 8 ? 1.0 / 255 : bits == 16 ? 1.0 / 65535 : 0.0; }
};

// The method's result; for Periodic, the first candidate that tiles at every level and keeps the height
// span within 1.5x the input's: Moisan with the edge slopes bent together; Moisan crossfaded near the
// edges (its heights already meet there, so the blend only hides kinks: a change of slope at a scale
// the bend did not reach, a line along the edge); the map itself crossfaded (when Moisan's smooth field
// would stretch the span: a sheet of unrelated tiles); then the same two with a band of a fifth of the
// tile (wider would reach the middle half of the map, which no candidate may change). The last candidate
// is returned when none passes, and the caller writes nothing. `judged` is set to the verdict on the
// returned candidate as stored when one was reached, so the caller need not judge it again.
Image applyMethod(const Image& map, const TileOptions& options, const SeamOptions& seamOptions, const Storage& storage,
                  std::string& name, double& band, std::optional<ChainSeams>& judged) {
    name = tileMethodName(options.method);
    band = options.width;
    switch (options.method) {
        case TileMethod::Moisan: return periodicComponent(map, PeriodicContinuity::Heights);
        case TileMethod::Crossfade: return crossfadeTile(map, options.width);
        case TileMethod::Mirror: return mirrorTile(map);
        case TileMethod::Periodic: break;
    }
    const double maxSpan = 1.5 * span(map);
    // Judged as it will be stored: a candidate the output cannot hold (a PNG, heights past [0,1]) is passed
    // over for one it can.
    auto acceptable = [&](const Image& candidate) {
        judged.reset();
        const Storage::Choice c = storage.choose(candidate, false);
        if (!c.storable || span(candidate) > maxSpan) return false;
        SeamOptions stored = seamOptions;
        stored.quantum = Storage::quantum(c.bits);
        judged = measureChainSeams(seamChain(Storage::rounded(candidate, c.bits), options.mip), options.threshold, stored);
        return judged->tiles();
    };
    Image result = periodicComponent(map);
    if (acceptable(result)) return result;
    const Image moisan = periodicComponent(map, PeriodicContinuity::Heights);
    for (double width : {options.width, 0.2}) {
        char text[64];
        std::snprintf(text, sizeof text, " over %g of the tile", width);
        for (const Image* base : {&moisan, &map}) {
            result = crossfadeTile(*base, width);
            name = std::string(base == &moisan ? "moisan+crossfade" : "crossfade") + text;
            band = width;
            if (acceptable(result)) return result;
        }
    }
    return result;
}

}  // namespace

Result<TileReport> tileFile(const std::string& input, const std::string& output, const TileOptions& options) {
    if (Status s = checkWritable(output); !s) return s.error();
    auto progress = [&](std::string_view stage, double f) {
        if (options.progress) options.progress(stage, f);
    };
    progress("load", 0.0);
    auto loaded = detail::loadInput(input, options.load, options.mip.threads);
    if (!loaded) return loaded.error();
    TileReport report;
    report.input = input;
    report.output = output;
    report.source = loaded->source;
    const Image& map = loaded->heights;
    progress("check", 0.0);
    const auto [inLow, inHigh] = std::minmax_element(map.pixels.begin(), map.pixels.end());
    report.inputLow = *inLow;
    report.inputHigh = *inHigh;
    SeamOptions seamOptions;
    seamOptions.threads = options.mip.threads;
    seamOptions.quantum = sampleQuantum(loaded->source);
    report.before = measureChainSeams(seamChain(map, options.mip), options.threshold, seamOptions);
    report.alreadyTiled = report.before.tiles() && !options.force;
    progress("tile", 0.0);

    const std::string ext = lowerExtension(output);
    const std::string& type = loaded->source.pixelType;
    const int inputBits = type == "uint8" ? 8 : type == "uint16" ? 16 : 32;
    if (report.alreadyTiled && loaded->source.channels == 1 && lowerExtension(input) == ext) {
        // The file itself: bit-exact, metadata and all.
        report.after = report.before;
        report.methodUsed = "none";
        report.bits = inputBits;
        report.low = report.inputLow;
        report.high = report.inputHigh;
        report.width = map.width;
        report.height = map.height;
        std::error_code same;  // set when output does not exist yet: then it is not the input either
        if (!std::filesystem::equivalent(input, output, same))
            if (Status s = copyFile(input, output); !s) return s.error();
        report.written = true;
        return report;
    }

    Storage storage;
    storage.bits = options.bits ? options.bits : inputBits;
    storage.explicitBits = options.bits != 0;
    storage.floatFormat = holdsFloat(ext);
    if (storage.bits == 32 && !storage.floatFormat) storage.bits = 16;
    std::optional<ChainSeams> judged;
    Image result = report.alreadyTiled ? map
                                       : applyMethod(map, options, seamOptions, storage, report.methodUsed,
                                                     report.crossfadeWidth, judged);
    if (report.alreadyTiled) report.methodUsed = "none";
    progress("tile", 1.0);
    report.width = result.width;
    report.height = result.height;
    const auto [low, high] = std::minmax_element(result.pixels.begin(), result.pixels.end());
    report.low = *low;
    report.high = *high;

    const Storage::Choice stored = storage.choose(result, report.alreadyTiled);
    report.bits = stored.bits;
    report.widened = stored.widened;
    if (!stored.storable) {
        char what[200];
        if (*low >= 0.0f && *high <= 1.0f)
            std::snprintf(what, sizeof what, "the heights are not whole %d-bit steps: writing them so would round them",
                          stored.bits);
        else
            std::snprintf(what, sizeof what, "the tiled heights reach [%.4g, %.4g], outside the [0,1] of %d-bit samples",
                          double(*low), double(*high), stored.bits);
        return withFix(cannotWrite(output, what,
                                   "write float samples (an .exr or .tif output); heightpack never clips or rescales heights"),
                       Fix::WriteFloat);
    }
    // Judge what will be stored: rounded to the type (Periodic's candidates were judged so already, with
    // the same type: the same rounding and quantum).
    result = Storage::rounded(std::move(result), report.bits);
    if (judged) {
        report.after = std::move(*judged);
    } else {
        SeamOptions afterOptions = seamOptions;
        afterOptions.quantum = Storage::quantum(report.bits);
        report.after = measureChainSeams(seamChain(result, options.mip), options.threshold, afterOptions);
    }
    // Mirror tiling breaks slopes at its mirror lines by design (the help says so): it is written when its
    // heights meet, and the report still shows the kinks.
    const bool onlyDesignedKinks =
        options.method == TileMethod::Mirror &&
        std::none_of(report.after.levels.begin(), report.after.levels.end(), [&](const LevelSeams& l) {
            return (l.leftRight.measured && l.leftRight.value > options.threshold) ||
                   (l.topBottom.measured && l.topBottom.value > options.threshold);
        });
    if (!report.after.tiles() && !report.alreadyTiled && !onlyDesignedKinks)
        return report;  // nothing written: the caller says why

    FlatImageOptions flat;
    flat.bits = report.bits;
    flat.threads = options.mip.threads;
    flat.attributes = {
        attribute(attr::tileMethod, report.methodUsed),
        attribute(attr::source, std::filesystem::path(input).filename().string()),
        attribute(attr::sourceHash, loaded->hash),
        attribute(attr::seamsBefore, verdictText(report.before)),
        attribute(attr::seamsAfter, verdictText(report.after)),
        attribute(attr::version, options.version),
    };
    if (report.methodUsed.find("crossfade") != std::string::npos)
        flat.attributes.push_back(attribute(attr::crossfadeWidth, static_cast<float>(report.crossfadeWidth)));
    progress("write", 0.0);
    if (Status s = writeFlatImage(output, result, flat); !s) return s.error();
    report.written = true;
    return report;
}

}  // namespace heightpack
