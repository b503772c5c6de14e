#include "heightpack/bake/pack_job.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "heightpack/bake/pack_shift.hpp"
#include "heightpack/bake/pack_foam.hpp"
#include "heightpack/core/pack.hpp"
#include "heightpack/core/parallel.hpp"
#include "heightpack/io/shift_read.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/foam_read.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/read.hpp"
#include "heightpack/io/texture_write.hpp"

#include "job_steps.hpp"
#include "stored_chain.hpp"

namespace heightpack {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// packHeights' first half, which packHeightMap shares: resize, scale, mip. Leaves maps.packed empty.
Result<PackedMaps> plainChain(Image heights, const SourceInfo& source, const PackOptions& options) {
    if (options.progress) options.progress("mip", 0.0);
    PackedMaps maps;
    auto resized = detail::ensurePowerOfTwo(heights, source.path, options.resizeToPowerOfTwo, options.mip);
    if (!resized) return resized.error();
    maps.resized = *resized;
    if (options.scale != 1.0f || options.offset != 0.0f)
        for (float& v : heights.pixels) v = options.offset + options.scale * v;
    maps.plain = generateMipChain(std::move(heights), options.mip);  // level 0 is the heights, not a copy
    if (options.progress) options.progress("mip", 1.0);
    return maps;
}

// The writer packs bands itself: the shift's chains are made plain, as the heights' are.
PackOptions withoutPacking(PackOptions options) {
    options.layout = Layout::Plain;
    return options;
}

}  // namespace

Result<PackedMaps> packHeights(Image heights, const SourceInfo& source, const PackOptions& options) {
    auto maps = plainChain(std::move(heights), source, options);
    if (maps && options.layout == Layout::Neighbour4) maps->packed = packMipChain(maps->plain, options.mip.wrap);
    return maps;
}

std::vector<ExrAttribute> heightAttributes(Layout layout, const PackOptions& options, const SourceInfo& source,
                                           const std::string& sourceHash) {
    auto attributes = detail::commonAttributes(attributeText(layout), options.mip.wrap, options.mip.filter, source,
                                               sourceHash, options.version);
    attributes.push_back(attribute(attr::heightScale, options.scale));
    attributes.push_back(attribute(attr::heightOffset, options.offset));
    // What the source records of the world carries over: its tile, its metres (a stored unit is 1 / scale
    // of the source's, unless the options give the range), its place in a loop.
    const MapUnits& units = source.units;
    if (units.tileWidth) attributes.push_back(attribute(attr::tileWidth, float(*units.tileWidth)));
    if (units.tileHeight) attributes.push_back(attribute(attr::tileHeight, float(*units.tileHeight)));
    const double range = options.heightRange > 0.0 ? options.heightRange
                         : units.heightRange     ? *units.heightRange / options.scale
                                                 : 0.0;
    if (range > 0.0 && std::isfinite(range)) attributes.push_back(attribute(attr::heightRange, float(range)));
    if (units.loopPeriod) {
        attributes.push_back(attribute(attr::loopPeriod, float(*units.loopPeriod)));
        attributes.push_back(attribute(attr::time, float(units.time.value_or(0.0))));
    }
    return attributes;
}

Result<PackReport> packHeightMap(const std::string& input, const std::string& output, const PackOptions& options) {
    auto progress = [&](std::string_view stage, double fraction) {
        if (options.progress) options.progress(stage, fraction);
    };
    if (!isHeightLayout(options.layout))
        return Error{ErrorKind::Internal, output, std::string("pack writes heights, not the '") + nameOf(options.layout) +
                                                      "' layout of normal maps", "please report this"};
    const bool packed = options.layout == Layout::Neighbour4;
    // Fail on an unwritable output before spending any time on the input.
    if (Status s = checkWritable(output); !s) return s.error();
    if (!packed && !options.plainOutput.empty())
        return withFix(inconsistentOptions(options.plainOutput, "would be a second plain chain beside the plain output",
                                           "write the plain chain once"),
                       Fix::OnePlainChain);
    // Each output's container, decided here once from its name: the planner and the writer take it as it is.
    auto packedOutput = textureOutput(output);
    if (!packedOutput) return packedOutput.error();
    std::optional<TextureOutput> twinOutput;  // the plain chain beside the packed one
    if (packed && !options.plainOutput.empty()) {
        auto twin = textureOutput(options.plainOutput);
        if (!twin) return twin.error();
        twinOutput = *twin;
    }
    if (twinOutput) {
        if (std::filesystem::path(options.plainOutput).lexically_normal() ==
            std::filesystem::path(output).lexically_normal())
            return withFix(cannotWrite(options.plainOutput, "is also the packed output", "give the plain output another name"),
                           Fix::RenamePlainOutput);
        if (Status s = checkWritable(options.plainOutput); !s) return s.error();
    }

    PackReport report;
    report.input = input;
    report.output = output;
    report.plainOutput = packed ? options.plainOutput : output;
    report.layout = options.layout;
    report.container = packedOutput->container;

    auto start = std::chrono::steady_clock::now();
    progress("load", 0.0);
    auto loaded = detail::loadInput(input, options.load, options.mip.threads);
    if (!loaded) return loaded.error();
    report.source = loaded->source;
    report.sourceHash = loaded->hash;
    Image heights = std::move(loaded->heights);
    progress("load", 1.0);
    report.loadSeconds = secondsSince(start);
    // Dx, Dy and foam: layers of the same EXR (channels NAME.R ...) or of the same KTX2 or DDS array.
    std::optional<Image> d, f;
    if (options.shift) {
        auto loadedD = loadShift(input, options.load);
        if (!loadedD) return loadedD.error();
        d = std::move(*loadedD);
    }
    if (options.foam) {
        auto loadedF = loadFoam(input, options.load);
        if (!loadedF) return loadedF.error();
        f = std::move(*loadedF);
    }
    // The hash covers every channel the file is made from: the heights, then Dx, Dy, then the foam.
    std::vector<const Image*> hashed = {&heights};
    if (d) hashed.push_back(&*d);
    if (f) hashed.push_back(&*f);
    if (hashed.size() > 1) report.sourceHash = hashPixels(hashed);
    std::optional<ShiftMaps> shift;
    if (d) {
        auto maps = packShift(std::move(*d), report.source, withoutPacking(options));
        if (!maps) return maps.error();
        shift = std::move(*maps);
    }
    std::optional<std::vector<Image>> foam;
    if (f) {
        auto chain = foamChain(std::move(*f), report.source, options);
        if (!chain) return chain.error();
        foam = std::move(*chain);
    }
    const std::vector<CompanionChain> companions = companionsOf(shift ? &*shift : nullptr, foam ? &*foam : nullptr);

    start = std::chrono::steady_clock::now();
    // The plain chain only: the writer packs it a band at a time, so the packed chain is never held whole.
    auto maps = plainChain(std::move(heights), report.source, options);
    if (!maps) return maps.error();
    const std::vector<Image>& chain = maps->plain;
    report.resized = maps->resized;
    for (const Image& level : chain) report.levelSizes.emplace_back(level.width, level.height);
    report.mipSeconds = secondsSince(start);

    start = std::chrono::steady_clock::now();
    TextureWriteOptions writeOptions;
    writeOptions.storage = options.storage;
    writeOptions.threads = options.mip.threads;
    writeOptions.writer = "heightpack " + options.version;
    // A painted 8- or 16-bit map lies on a 16-bit grid (8-bit k/255 = 257k/65535): uint16 keeps it.
    if (!report.resized && report.source.integerBits > 0) {
        writeOptions.gridOrigin = options.offset;
        writeOptions.gridSpan = options.scale;
    }
    // The plain chain goes to plainOutput beside the packed one (the twin), or alone to output.
    writeOptions.progress = [&](double f) { progress("write", twinOutput ? f * 0.8 : f); };

    const Wrap wrap = options.mip.wrap;
    const auto fillPacked = [&](int level, int y0, int rows, float* dst) {
        packNeighbour4Rows(chain[level], wrap, y0, rows, dst);
    };
    const auto fillPlain = [&](int level, int y0, int rows, float* dst) {
        const Image& l = chain[level];
        std::copy(l.row(y0), l.row(y0) + static_cast<size_t>(rows) * l.width, dst);
    };
    // One channel of a row, for writers that take the channels apart (EXR tiles): copies of the levels' rows.
    const auto runPacked = [&](int level, int y, int x0, int count, int channel, float* dst) {
        packNeighbour4Run(chain[level], wrap, y, x0, count, channel, dst);
    };
    const auto runPlain = [&](int level, int y, int x0, int count, int, float* dst) {
        std::copy_n(chain[level].row(y) + x0, count, dst);
    };
    // What an output holds: the heights packed (or plain), and Dx, Dy and foam as its container holds
    // them (an EXR's further channels, a KTX2's or DDS's further layers).
    const auto contentFor = [&](const TextureOutput& out, bool packedChain) {
        ChainToWrite c;
        c.width = chain[0].width;
        c.height = chain[0].height;
        c.attributes = heightAttributes(packedChain ? options.layout : Layout::Plain, options, report.source, report.sourceHash);
        if (!companions.empty()) {
            detail::fillWithCompanions(c, out.container, chain, companions, wrap, packedChain);
        } else {
            c.channelNames = packedChain ? std::vector<std::string>{"R", "G", "B", "A"} : std::vector<std::string>{"Y"};
            c.fillRows = packedChain ? decltype(c.fillRows)(fillPacked) : decltype(c.fillRows)(fillPlain);
            c.fillRun = packedChain ? decltype(c.fillRun)(runPacked) : decltype(c.fillRun)(runPlain);
        }
        return c;
    };
    ChainToWrite content = contentFor(*packedOutput, packed);

    // The pixel type, given or chosen, and its lookup error: judged over every chain written (the heights,
    // Dx, Dy, foam), the same for both outputs, since a packed texel holds copies of the plain chains' values.
    std::vector<TextureOutput> outputs = {*packedOutput};
    if (twinOutput) outputs.push_back(*twinOutput);
    std::vector<const std::vector<Image>*> chains = {&chain};
    for (const CompanionChain& c : companions) chains.push_back(c.levels);
    auto stored = detail::chooseStorage(outputs, content, chains, writeOptions);
    if (!stored) return stored.error();
    writeOptions.storage.pixelType = stored->pixelType;
    report.pixelType = stored->pixelType;
    report.lookupError = stored->lookupError;
    const std::vector<ExrAttribute> errors = detail::lookupErrorAttributes(*stored);
    const auto record = [&](ChainToWrite& c, bool packedChain) {
        c.attributes.insert(c.attributes.end(), errors.begin(), errors.end());
        const std::string laidOut = attributeText(packedChain ? Layout::Neighbour4 : Layout::Plain);
        if (shift) c.attributes.push_back(attribute(attr::shift, laidOut));
        if (foam) c.attributes.push_back(attribute(attr::foam, laidOut));
    };
    record(content, packed);
    if (Status s = writeTexture(*packedOutput, content, writeOptions, stored->plan); !s) return s.error();
    if (twinOutput) {
        content = contentFor(*twinOutput, false);
        record(content, false);
        writeOptions.progress = [&](double f) { progress("write", 0.8 + 0.2 * f); };
        if (Status s = writeTexture(*twinOutput, content, writeOptions, stored->plan); !s) return s.error();
    }
    progress("write", 1.0);
    report.writeSeconds = secondsSince(start);
    return report;
}

}  // namespace heightpack
