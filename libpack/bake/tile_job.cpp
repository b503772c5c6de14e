#include "heightpack/bake/tile_job.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <utility>

#include "heightpack/bake/check_job.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/parallel.hpp"
#include "heightpack/core/tile/quilt.hpp"
#include "heightpack/core/tile/resynthesis.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/image_write.hpp"

#include "job_steps.hpp"

namespace heightpack {

namespace {

bool holdsFloat(const std::string& ext) { return ext == ".exr" || ext == ".tif" || ext == ".tiff"; }

std::string verdictText(const ChainSeams& seams) {
    return seams.tiles() ? "tiles at every level" : describeSeamFailure(*seams.failure, seams.threshold);
}

// Whether every height is a whole number of steps of a bits-bit type, inside [0,1], as a reader of such
// samples gives it: within 0.01 of a step (a float holds k/65535 to 0.004 steps near 1, and readers
// multiply by 1/65535 rather than divide, so neither an exact test nor one within 1e-3 holds).
bool exactIn(const Image& map, int bits) {
    const double steps = bits == 8 ? 255.0 : 65535.0;
    return std::all_of(map.pixels.begin(), map.pixels.end(), [&](float v) {
        const double s = double(v) * steps;
        return v >= 0.0f && v <= 1.0f && std::abs(s - std::round(s)) < 0.01;
    });
}

double span(SampleRange range) { return double(range.high) - range.low; }

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
    // range: the result's (sampleRange).
    Choice choose(const Image& result, SampleRange range, bool unchanged) const {
        Choice c{bits, false, true};
        if (bits == 32) return c;
        const bool inRange = range.low >= 0.0f && range.high <= 1.0f;
        if (inRange && !(unchanged && !exactIn(result, bits))) return c;
        if (!floatFormat || explicitBits) return Choice{bits, false, false};
        return Choice{32, true, true};
    }
    // The heights as that type stores them (in [0,1] where bits < 32: choose said so; rounded half up
    // by a cast, which libm's round costs several times on 16 M texels).
    static Image rounded(Image result, int bits, int threads) {
        if (bits == 32) return result;
        const double steps = bits == 8 ? 255.0 : 65535.0;
        float* v = result.pixels.data();
        const size_t row = size_t(result.width) * result.channels;
        parallelFor(result.height, threads, [&](int begin, int end) {
            for (size_t i = begin * row; i < end * row; ++i)
                v[i] = static_cast<float>(double(static_cast<int64_t>(double(v[i]) * steps + 0.5)) / steps);
        });
        return result;
    }
    static double quantum(int bits) { return bits == 8 ? 1.0 / 255 : bits == 16 ? 1.0 / 65535 : 0.0; }
};

// The method's result. For Periodic, candidates judged as they will be stored, at every level pack would
// make (seams) and as the eye sees it (look), the first that passes both: the re-synthesis four times, each
// with the next seed, the last two with a band half as wide again and then twice the first (the quilt's best
// match before the second where the first breaks at the finest level), then the quilt; then, for maps
// neither describes (a few pure waves whose periods do not divide the tile), Moisan's periodic component with the edge slopes bent together, then Moisan's component and the map crossfaded over
// the crossfade width and over a fifth of the tile, judged by their seams alone (the shell warns when their
// look does not pass). No candidate may stretch the height span past 1.5x the input's. The last is returned
// when none passes, and the caller writes nothing. `judged` (and `looked`, when the look was judged) is the
// verdict on the returned candidate as stored, and `stored` that candidate as stored, so the caller need
// not round or judge it again. judging(asStored, bits) is told of each candidate, as stored, whose seams
// pass, before its look is judged.
Image applyMethod(const Image& map, const TileOptions& options, const SeamOptions& seamOptions, const Storage& storage,
                  TileReport& report, std::optional<ChainSeams>& judged, std::optional<TileLook>& looked,
                  std::shared_ptr<Image>& stored, const std::function<void(std::shared_ptr<const Image> asStored, int bits)>& judging) {
    report.methodUsed = nameOf(options.method);
    report.crossfadeWidth = options.width;
    switch (options.method) {
        case TileMethod::Quilt: {
            QuiltOptions quilt;
            quilt.threads = options.mip.threads;
            quilt.quantum = seamOptions.quantum;
            QuiltResult q = quiltTile(map, quilt);
            report.bandX = q.bandX;
            report.bandY = q.bandY;
            report.match = 1;
            return std::move(q.map);
        }
        case TileMethod::Moisan: return periodicComponent(map, PeriodicContinuity::Heights);
        case TileMethod::Crossfade: return crossfadeTile(map, options.width);
        case TileMethod::Mirror: return mirrorTile(map);
        case TileMethod::Periodic: break;
    }
    const double maxSpan = 1.5 * (double(report.inputHigh) - report.inputLow);  // the caller measured the map
    bool lookRequired = true;
    LookOptions lookOptions{&map, options.mip.threads, std::nullopt};
    auto acceptable = [&](const Image& candidate) {
        judged.reset();
        looked.reset();
        stored.reset();
        const SampleRange range = sampleRange(candidate, options.mip.threads);
        const Storage::Choice c = storage.choose(candidate, range, false);
        if (!c.storable || span(range) > maxSpan) return false;
        SeamOptions storedSeams = seamOptions;
        storedSeams.quantum = Storage::quantum(c.bits);
        stored = std::make_shared<Image>(Storage::rounded(candidate, c.bits, options.mip.threads));
        const Image& asStored = *stored;
        if (lookRequired) {
            // An attempt whose finest level fails is not worth a mip chain (most that fail, fail there): its
            // verdict is that level's, the same first failure the chain would name.
            ChainSeams finest;
            finest.threshold = options.threshold;
            finest.levels.push_back(measureSeams(asStored, storedSeams));
            finest.failure = firstSeamFailure(finest.levels, options.threshold);
            if (!finest.tiles()) {
                judged = std::move(finest);
                return false;
            }
        }
        judged = measureSeamChain(asStored, options.mip, options.threshold, storedSeams);
        if (!judged->tiles()) return false;
        judging(stored, c.bits);  // compressed while its look is judged; one whose seams fail costs none
        if (!lookRequired) return true;
        if (!lookOptions.sourceEcho) lookOptions.sourceEcho = sourceEchoOf(map, options.mip.threads);
        looked = measureTileLook(asStored, lookOptions);
        return looked->passes(options.look);
    };
    // Which attempt of the chain is running (re-synthesis 4, quilt 3, then the fallbacks), for a progress bar.
    auto step = [&](const char* what, int index, int of, int done) {
        if (!options.progress) return;
        char text[64];
        if (of > 1)
            std::snprintf(text, sizeof text, "tile: %s %d of %d", what, index + 1, of);
        else
            std::snprintf(text, sizeof text, "tile: %s", what);
        options.progress(text, done / 12.0);
    };
    // The re-synthesis' attempts from..to-1 (seeds from --seed on; the last two with a band half as wide
    // again and twice the first's), each with a model of its own: what it holds (the model, the Gaussianised
    // map, its sorted values) is released before the quilt makes its own.
    double firstBand = 0;
    std::optional<Image> found;
    auto resynthesis = [&](int from, int to) {
        step("re-synthesis", from, 4, from);
        Resynthesiser resynthesiser(map, seamOptions.quantum, options.mip.threads);
        for (int attempt = from; attempt < to && !found; ++attempt) {
            const uint64_t seed = options.seed + uint64_t(attempt);
            step("re-synthesis", attempt, 4, attempt);
            const double band = attempt < 2 ? 0.0 : std::min(0.25, firstBand * (attempt == 2 ? 1.5 : 2.0));
            ResynthesisResult r = resynthesiser.attempt(seed, band);
            if (attempt == 0) firstBand = double(std::max(r.bandX, 1)) / map.width;
            report.methodUsed = nameOf(TileMethod::Periodic);
            report.bandX = r.bandX;
            report.bandY = r.bandY;
            report.seed = seed;
            report.match = 0;
            if (acceptable(r.map)) found = std::move(r.map);
        }
    };
    // The quilt's attempts from..to-1 at the source's size (an enlarged map's; a map's own otherwise): the
    // best match, the next best, then the best with strips half as wide again; then, for an enlarged map, the
    // same at its own size (a source can be too small to hold a good match). Judged like the re-synthesis.
    QuiltOptions quilt;
    quilt.threads = options.mip.threads;
    quilt.quantum = seamOptions.quantum;
    int enlargement = 1;
    auto quilting = [&](bool atSourceSize, int from, int to) {
        quilt.atSourceSize = atSourceSize;
        for (int attempt = from; attempt < to && !found; ++attempt) {
            step("quilt", attempt, 3, 4 + attempt);
            quilt.match = attempt == 1 ? 1 : 0;
            quilt.band = attempt == 2 ? 1.5 / 8 : 0.0;
            QuiltResult q = quiltTile(map, quilt);
            enlargement = q.enlargement;
            report.methodUsed = nameOf(TileMethod::Quilt);
            report.seed = 0;
            report.bandX = q.bandX;
            report.bandY = q.bandY;
            report.match = quilt.match + 1;
            if (acceptable(q.map)) found = std::move(q.map);
        }
    };
    // A map whose first re-synthesis breaks at the finest level (the new content itself does not join the
    // map: pebbles, cells, strokes, a painted line) is one a Gaussian field does not describe, where further
    // seeds and bands break as well: the quilt's best match comes next, before them. One that breaks at a
    // coarser level (a large-scale swell of the sample) or fails the look is taken to pass with another seed
    // or band (sea crops, enlarged or not, pass so with the third).
    resynthesis(0, 1);
    const bool quiltSooner = !found && judged && judged->failure && judged->failure->level == 0;
    if (!found && quiltSooner) quilting(true, 0, 1);
    if (!found) resynthesis(1, 4);
    if (!found) quilting(true, quiltSooner ? 1 : 0, 3);
    if (!found && enlargement > 1) quilting(false, 0, 3);
    if (found) return std::move(*found);
    // The fallbacks are judged by their seams alone (as before the look existed); their look is reported.
    lookRequired = false;
    report.bandX = report.bandY = 0;
    report.match = 0;
    step("moisan+bend", 0, 1, 7);
    Image result = periodicComponent(map, PeriodicContinuity::HeightsAndSlopes);
    report.methodUsed = "moisan+bend";
    if (acceptable(result)) return result;
    step("crossfade", 0, 1, 8);
    const Image moisan = periodicComponent(map, PeriodicContinuity::Heights);
    for (double width : {options.width, 0.2}) {
        char text[64];
        std::snprintf(text, sizeof text, " over %g of the tile", width);
        for (const Image* base : {&moisan, &map}) {
            result = crossfadeTile(*base, width);
            report.methodUsed = std::string(base == &moisan ? "moisan+crossfade" : "crossfade") + text;
            report.crossfadeWidth = width;
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
    const SampleRange inputRange = sampleRange(map, options.mip.threads);
    report.inputLow = inputRange.low;
    report.inputHigh = inputRange.high;
    SeamOptions seamOptions;
    seamOptions.threads = options.mip.threads;
    seamOptions.quantum = sampleQuantum(loaded->source);
    report.before = measureSeamChain(map, options.mip, options.threshold, seamOptions);
    report.alreadyTiled = report.before.tiles() && !options.force;
    progress("tile", 0.0);

    const std::string ext = lowerExtension(output);
    const int inputBits = loaded->source.integerBits > 0 ? loaded->source.integerBits : 32;
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
    std::optional<TileLook> looked;
    // A grey PNG's pixels are compressed while the candidate is judged (the deflate is serial, the judging
    // leaves a core idle at times): the one that passes is then written at once. (A candidate whose seams
    // pass but whose look does not costs its compression on the side.)
    std::future<std::pair<PreparedPixels, int>> compressing;
    std::shared_ptr<const Image> compressed;  // the candidate being compressed
    std::shared_ptr<Image> judgedStored;      // the result as stored, where applyMethod judged it so
    auto judging = [&](std::shared_ptr<const Image> asStored, int bits) {
        if (ext != ".png" || bits == 32) return;
        compressed = asStored;
        compressing = std::async(std::launch::async, [&output, stored = std::move(asStored), bits, threads = options.mip.threads] {
            FlatImageOptions o;
            o.bits = bits;
            o.threads = threads;
            return std::pair(preparePixels(output, *stored, o), bits);
        });
    };
    Image result = report.alreadyTiled ? map : applyMethod(map, options, seamOptions, storage, report, judged, looked, judgedStored, judging);
    if (report.alreadyTiled) report.methodUsed = "none";
    progress("tile", 1.0);
    report.width = result.width;
    report.height = result.height;
    const SampleRange range = sampleRange(result, options.mip.threads);

    const Storage::Choice stored = storage.choose(result, range, report.alreadyTiled);
    report.bits = stored.bits;
    report.widened = stored.widened;
    if (!stored.storable) {
        char what[200];
        if (range.low >= 0.0f && range.high <= 1.0f)
            std::snprintf(what, sizeof what, "the heights are not whole %d-bit steps: writing them so would round them",
                          stored.bits);
        else
            std::snprintf(what, sizeof what, "the tiled heights reach [%.4g, %.4g], outside the [0,1] of %d-bit samples",
                          double(range.low), double(range.high), stored.bits);
        return withFix(cannotWrite(output, what,
                                   "write float samples (an .exr or .tif output); heightpack never clips or rescales heights"),
                       Fix::WriteFloat);
    }
    // Judge what will be stored: rounded to the type (Periodic's candidates were judged so already, with
    // the same choice of type: the same rounding and quantum). A grey PNG's pixels compressed while judging
    // are used only where the candidate compressed is that result as stored.
    std::optional<PreparedPixels> prepared;
    if (compressing.valid()) {
        auto [pixels, bits] = compressing.get();
        if (bits == report.bits && judgedStored && compressed.get() == judgedStored.get()) prepared = std::move(pixels);
    }
    result = judged && judgedStored ? std::move(*judgedStored) : Storage::rounded(std::move(result), report.bits, options.mip.threads);
    // The heights reported are those of the file: rounded to its steps where it holds integers.
    const SampleRange written = report.bits == 32 ? range : sampleRange(result, options.mip.threads);
    report.low = written.low;
    report.high = written.high;
    if (judged) {
        report.after = std::move(*judged);
    } else {
        SeamOptions afterOptions = seamOptions;
        afterOptions.quantum = Storage::quantum(report.bits);
        report.after = measureSeamChain(result, options.mip, options.threshold, afterOptions);
    }
    report.lookThresholds = options.look;
    report.look = looked ? *looked : measureTileLook(result, {&map, options.mip.threads, std::nullopt});
    // Periodic's re-synthesised and quilted results were judged by their look (the fallbacks were not).
    const bool lookCounts = looked.has_value();
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
    if (lookCounts && !report.look.passes(options.look)) return report;  // likewise

    FlatImageOptions flat;
    flat.bits = report.bits;
    flat.threads = options.mip.threads;
    if (prepared) flat.prepared = std::move(*prepared);
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
    if (report.seed != 0 || report.match != 0)
        flat.attributes.push_back(attribute(attr::tileBand, std::to_string(report.bandX) + "x" + std::to_string(report.bandY)));
    if (report.seed != 0) flat.attributes.push_back(attribute(attr::seed, std::to_string(report.seed)));
    if (report.match != 0) flat.attributes.push_back(attribute(attr::tileMatch, std::to_string(report.match)));
    progress("write", 0.0);
    if (Status s = writeFlatImage(output, result, flat); !s) return s.error();
    report.written = true;
    return report;
}

}  // namespace heightpack
