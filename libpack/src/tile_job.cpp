#include "heightpack/tile_job.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "heightpack/mip.hpp"
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

std::string scoresText(const LevelSeams& s) {
    char text[160];
    std::snprintf(text, sizeof text, "left/right value %.3g slope %.3g, top/bottom value %.3g slope %.3g",
                  s.leftRight.value, s.leftRight.slope, s.topBottom.value, s.topBottom.slope);
    return text;
}

}  // namespace

Result<TileReport> tileFile(const std::string& input, const std::string& output, const TileOptions& options) {
    if (Status s = checkWritable(output); !s) return s.error();
    auto progress = [&](std::string_view stage, double f) {
        if (options.progress) options.progress(stage, f);
    };
    progress("load", 0.0);
    auto loaded = detail::loadInput(input, options.load, 0);
    if (!loaded) return loaded.error();
    TileReport report;
    report.input = input;
    report.output = output;
    report.source = loaded->source;
    const Image& map = loaded->heights;
    progress("check", 0.0);
    report.before = measureSeams(map);
    progress("tile", 0.0);

    if (levelTiles(report.before, options.threshold) && !options.force) {
        report.alreadyTiled = true;
        report.after = report.before;
        report.width = map.width;
        report.height = map.height;
        if (std::filesystem::path(input).extension() == std::filesystem::path(output).extension()) {
            std::error_code same;  // set when output does not exist yet: then it is not the input either
            if (!std::filesystem::equivalent(input, output, same))
                if (Status s = copyFile(input, output); !s) return s.error();
            return report;
        }
        // Another format asked for: the same heights, re-encoded below.
    }

    Image result = report.alreadyTiled                        ? map
                   : options.method == TileMethod::Periodic   ? periodicComponent(map)
                   : options.method == TileMethod::Moisan     ? periodicComponent(map, PeriodicContinuity::Heights)
                   : options.method == TileMethod::Crossfade  ? crossfadeTile(map, options.width)
                                                              : mirrorTile(map);
    progress("tile", 1.0);
    report.after = measureSeams(result);
    progress("write", 0.0);
    report.width = result.width;
    report.height = result.height;

    const std::string& type = loaded->source.pixelType;
    report.bits = options.bits ? options.bits : type == "uint8" ? 8 : type == "uint16" ? 16 : 32;
    std::string ext = std::filesystem::path(output).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (report.bits == 32 && ext == ".png") report.bits = 16;  // PNG holds no floats
    if (report.bits != 32) {
        // Clipping would flatten crests into plateaus with kinks of their own; an affine map keeps the shape.
        const auto [lo, hi] = std::minmax_element(result.pixels.begin(), result.pixels.end());
        if (*lo < 0.0f || *hi > 1.0f) {
            report.remapped = true;
            report.remapOffset = std::min(0.0, double(*lo));
            report.remapScale = 1.0 / (std::max(1.0, double(*hi)) - report.remapOffset);
            for (float& v : result.pixels)
                v = static_cast<float>((v - report.remapOffset) * report.remapScale);
        }
    }

    FlatImageOptions flat;
    flat.bits = report.bits;
    flat.attributes = {
        {"heightpack:tileMethod", std::string(report.alreadyTiled ? "none" : tileMethodName(options.method))},
        {"heightpack:source", std::filesystem::path(input).filename().string()},
        {"heightpack:sourceHash", loaded->hash},
        {"heightpack:seamsBefore", scoresText(report.before)},
        {"heightpack:seamsAfter", scoresText(report.after)},
        {"heightpack:version", options.version},
    };
    if (report.remapped) {
        flat.attributes.push_back({"heightpack:remapScale", static_cast<float>(report.remapScale)});
        flat.attributes.push_back({"heightpack:remapOffset", static_cast<float>(report.remapOffset)});
    }
    if (options.method == TileMethod::Crossfade && !report.alreadyTiled)
        flat.attributes.push_back({"heightpack:crossfadeWidth", static_cast<float>(options.width)});
    if (Status s = writeFlatImage(output, result, flat); !s) return s.error();
    return report;
}

}  // namespace heightpack
