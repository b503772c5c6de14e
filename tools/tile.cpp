// heightpack tile: make a height map tile.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "heightpack/bake/tile_job.hpp"
#include "heightpack/core/parallel.hpp"
#include "heightpack/io/threads.hpp"
#include "heightpack/version.hpp"

#include "command.hpp"
#include "enum_option.hpp"
#include "look_report.hpp"

namespace heightpack::cli {

namespace {

class TileCommand final : public Command {
public:
    CLI::App* attach(CLI::App& app) override {
        CLI::App* cmd = app.add_subcommand("tile", "make a height map tile: new content across each wrap line, a smooth change elsewhere");
        cmd->add_option("input", input_, "the height map")->required();
        cmd->add_option("-o,--output", output_, "the tiling map to write (.png, .tif, .exr)")->required();
        addEnumOption(*cmd, "--method", options_.method,
                      "periodic: re-synthesise a band around each wrap line as new content that continues both "
                        "sides (Gaussian conditional simulation with the map's own statistics), the large scales made "
                        "periodic by Moisan's smooth field, and for maps a Gaussian field does not describe the quilt; "
                        "quilt: a strip copied from where it matches best across each wrap line, cut in along the "
                        "least visible paths and healed in the gradient domain (pebbles, cells, strokes, sharp "
                        "rock); moisan: Moisan's periodic component only (slopes may kink "
                        "at the edges); crossfade: offset and blend (leaves an echo: features shown twice per tile); "
                      "mirror: mirror tiling, twice the size");
        widthOption_ = cmd->add_option("--width", options_.width, "crossfade band as a fraction of the tile, in (0, 0.5]")
            ->capture_default_str()
            ->check(CLI::Validator(
                [](std::string& text) {
                    char* end = nullptr;
                    const double v = std::strtod(text.c_str(), &end);
                    return (end != text.c_str() && *end == '\0' && v > 0 && v <= 0.5)
                               ? std::string()
                               : "'" + text + "' is not a fraction in (0, 0.5]";
                },
                "FRACTION"));
        cmd->add_flag("--force", options_.force, "apply the method even when the map already tiles");
        cmd->add_option("--seed", options_.seed, "periodic: the re-synthesis noise; the same seed gives the same bytes")
            ->capture_default_str();
        cmd->add_option("--threshold", options_.threshold, "seam score that counts as tiling (see check)")
            ->capture_default_str()
            ->check(finiteRange(1.0, 1e6));
        addEnumOption(*cmd, "--filter", options_.mip.filter, "mip filter of the chain the map is judged on, as pack would make it");
        cmd->add_option("--depth", depth_, "output sample type; keep = the input's")
            ->capture_default_str()
            ->check(CLI::IsMember({"keep", "uint8", "uint16", "float"}));
        addChannelOption(*cmd, channel_);
        addCommonOptions(*cmd);
        cmd->footer(
            "Examples:\n"
            "  heightpack tile painted_not_tileable.png -o painted_tiled.png\n"
            "  heightpack tile pebbles.png --method quilt -o pebbles_tiled.png\n"
            "  heightpack tile painted.png --method crossfade --width 0.1 -o painted_tiled.png\n"
            "  heightpack tile painted.png --method mirror -o painted_mirrored.png\n"
            "The map is judged as check judges it, at every level pack would make, and periodic's result also as\n"
            "the eye sees it tiled (frame, blobs, echo: see check --help); it tries the next seeds and wider\n"
            "bands, then the quilt (best and next-best source, a wider strip; its best source first where the\n"
            "first seed breaks at the finest level), before it falls back to Moisan's component and\n"
            "crossfades. One that tiles is written\n"
            "unchanged (the same bytes, or as float when its heights came from a colour channel); --force applies\n"
            "the method anyway. periodic and quilt replace a band across each wrap line and change the rest only\n"
            "by a smooth (harmonic) field that makes the large scales periodic; every texel may move a little.\n"
            "Heights are never clipped: periodic and quilt ease what would pass the input's extremes into the\n"
            "outer 2% of its range; where another method leaves [0,1] an integer output cannot hold it, so .exr\n"
            "and .tif outputs become float (said in the output) and a .png fails. The heights printed are those\n"
            "of the file written.\n"
            "When the result would still not tile, nothing is written (exit 1).\n");
        return cmd;
    }

    ExitCode run() override {
        if (options_.method != TileMethod::Crossfade && widthGiven()) return usage("--width goes with --method crossfade");
        options_.bits = depth_ == "uint8" ? 8 : depth_ == "uint16" ? 16 : depth_ == "float" ? 32 : 0;
        applyChannel(channel_, options_.load);
        options_.load.silenceDecoderMessages = true;
        options_.mip.threads = common_.threads;
        setLibraryThreads(common_.threads);
        if (const ExitCode code = checkOutputs({input_}, {{output_, "-o", {".png", ".tif", ".tiff", ".exr"}}});
            code != ExitCode::Ok)
            return code;
        Progress progress(!common_.quiet, "tile " + std::filesystem::path(input_).filename().string(),
                          {{"load", 0.2}, {"check", 0.1}, {"tile", 0.5}, {"write", 0.2}});
        options_.progress = [&](std::string_view stage, double f) { progress.update(stage, f); };
        auto report = tileFile(input_, output_, options_);
        if (!report) return fail(report.error());
        progress.clear();
        const TileReport& r = *report;
        const double t = options_.threshold;
        auto chain = [&](const ChainSeams& c) {
            return nlohmann::json{{"tiles", c.tiles()}, {"failure", seamFailureJson(c.failure, t)},
                                  {"levels", seamLevelsJson(c.levels, t)}};
        };
        if (common_.json) {
            printJson({{"command", "tile"}, {"input", r.input}, {"output", r.output}, {"written", r.written},
                       {"method", r.methodUsed}, {"alreadyTiled", r.alreadyTiled},
                       {"width", r.width}, {"height", r.height}, {"bits", r.bits}, {"widenedToFloat", r.widened},
                       {"range", {r.low, r.high}}, {"inputRange", {r.inputLow, r.inputHigh}}, {"threshold", t},
                       {"before", chain(r.before)}, {"after", chain(r.after)}, {"look", lookJson(r.look, r.lookThresholds)},
                       {"band", {r.bandX, r.bandY}}, {"seed", r.seed}, {"match", r.match},
                       {"channel", channelJson(r.source)}});
        } else if (!common_.quiet && !r.written) {
            clearProgressLine();
            const std::string why = r.after.failure ? describeSeamFailure(*r.after.failure, t)
                                                    : "its look does not pass: " + lookText(r.look, r.lookThresholds);
            std::fprintf(stderr, "heightpack: error: %s: --method %s could not make it tile: %s (%s); nothing written\n",
                         r.input.c_str(), nameOf(options_.method), why.c_str(),
                         options_.method == TileMethod::Periodic ? "no seed or band width passed: is it a sheet of unrelated pictures "
                                                 "rather than one map? --method moisan changes it least"
                                               : "try the default --method periodic");
        } else if (chatty()) {
            if (r.alreadyTiled) {
                std::printf("%s already tiles at every level: wrote it unchanged to %s (--force applies %s anyway)\n",
                            r.input.c_str(), r.output.c_str(), nameOf(options_.method));
            } else {
                if (r.before.failure)
                    std::printf("%s: %s\n", r.input.c_str(), describeSeamFailure(*r.before.failure, t).c_str());
                else  // --force on a map that tiles: there is no seam to name
                    std::printf("%s tiles at every level; --force applies %s anyway\n", r.input.c_str(),
                                nameOf(options_.method));
                std::printf("wrote %s: %dx%d, %s, tiles at every level; heights %.4g..%.4g (input %.4g..%.4g)\n",
                            r.output.c_str(), r.width, r.height, r.methodUsed.c_str(), r.low, r.high, r.inputLow,
                            r.inputHigh);
                if (r.seed != 0)
                    std::printf("  re-synthesised %d texels across the left/right wrap line and %d across the "
                                "top/bottom one (seed %llu)\n",
                                r.bandX, r.bandY, static_cast<unsigned long long>(r.seed));
                if (r.match != 0)
                    std::printf("  quilted %d texels across the left/right wrap line and %d across the top/bottom "
                                "one (source match %d)\n",
                                r.bandX, r.bandY, r.match);
                printLook(r.look, r.lookThresholds, false);
            }
            if (r.widened)
                std::printf("note: written as float: %s\n",
                            r.alreadyTiled ? "the heights are not whole steps of the input's integer type"
                                           : "the fixed heights leave [0,1], which the input's integer type cannot "
                                             "hold without clipping");
            std::fflush(stdout);
            printChannelNote(r.source);
        }
        return r.written ? ExitCode::Ok : ExitCode::CheckFailed;
    }

private:
    bool widthGiven() const { return widthOption_ && widthOption_->count() > 0; }

    std::string input_, output_, channel_, depth_ = "keep";
    TileOptions options_;
    CLI::Option* widthOption_ = nullptr;
};

}  // namespace

std::unique_ptr<Command> makeTileCommand() { return std::make_unique<TileCommand>(); }

}  // namespace heightpack::cli
