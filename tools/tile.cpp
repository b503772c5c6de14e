// heightpack tile: make a height map tile.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "command.hpp"
#include "heightpack/parallel.hpp"
#include "heightpack/tile_job.hpp"
#include "heightpack/version.hpp"

namespace heightpack::cli {

namespace {

class TileCommand final : public Command {
public:
    CLI::App* attach(CLI::App& app) override {
        CLI::App* cmd = app.add_subcommand("tile", "make a height map tile, changing it as little as the method allows");
        cmd->add_option("input", input_, "the height map")->required();
        cmd->add_option("-o,--output", output_, "the tiling map to write (.png, .tif, .exr)")->required();
        cmd->add_option("--method", method_,
                        "periodic: subtract the smooth field behind the seams, heights and slopes; moisan: the "
                        "same for heights only (Moisan 2011); crossfade: offset and blend keeping contrast "
                        "(Heitz-Neyret); mirror: mirror tiling, twice the size")
            ->capture_default_str()
            ->check(CLI::IsMember({"periodic", "moisan", "crossfade", "mirror"}));
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
        cmd->add_option("--threshold", options_.threshold, "seam score that counts as tiling (see check)")
            ->capture_default_str()
            ->check(CLI::Range(1.0, 1e6));
        cmd->add_option("--depth", depth_, "output sample type; keep = the input's")
            ->capture_default_str()
            ->check(CLI::IsMember({"keep", "uint8", "uint16", "float"}));
        addChannelOption(*cmd, channel_);
        addCommonOptions(*cmd);
        cmd->footer(
            "Examples:\n"
            "  heightpack tile painted_not_tileable.png -o painted_tiled.png\n"
            "  heightpack tile painted.png --method crossfade --width 0.1 -o painted_tiled.png\n"
            "  heightpack tile painted.png --method mirror -o painted_mirrored.png\n"
            "A map that already tiles is copied unchanged (periodic would still alter it slightly); --force applies\n"
            "the method anyway.\n");
        return cmd;
    }

    ExitCode run() override {
        if (method_ != "crossfade" && widthGiven()) return usage("--width goes with --method crossfade");
        options_.method = method_ == "crossfade" ? TileMethod::Crossfade
                          : method_ == "mirror"  ? TileMethod::Mirror
                          : method_ == "moisan"  ? TileMethod::Moisan
                                                 : TileMethod::Periodic;
        options_.bits = depth_ == "uint8" ? 8 : depth_ == "uint16" ? 16 : depth_ == "float" ? 32 : 0;
        applyChannel(channel_, options_.load);
        options_.load.silenceDecoderMessages = true;
        options_.version = kVersion;
        setLibraryThreads(common_.threads);
        Progress progress(!common_.quiet, "tile " + std::filesystem::path(input_).filename().string(),
                          {{"load", 0.2}, {"check", 0.1}, {"tile", 0.5}, {"write", 0.2}});
        options_.progress = [&](std::string_view stage, double f) { progress.update(stage, f); };
        auto report = tileFile(input_, output_, options_);
        if (!report) return fail(report.error());
        progress.clear();
        const TileReport& r = *report;
        auto scores = [](const LevelSeams& s) {
            return nlohmann::json{{"leftRight", {{"value", s.leftRight.value}, {"slope", s.leftRight.slope}}},
                                  {"topBottom", {{"value", s.topBottom.value}, {"slope", s.topBottom.slope}}}};
        };
        if (common_.json) {
            printJson({{"command", "tile"}, {"input", r.input}, {"output", r.output},
                       {"method", r.alreadyTiled ? "none" : method_}, {"alreadyTiled", r.alreadyTiled},
                       {"width", r.width}, {"height", r.height}, {"bits", r.bits},
                       {"remap", r.remapped ? nlohmann::json{{"scale", r.remapScale}, {"offset", r.remapOffset}}
                                            : nlohmann::json(nullptr)},
                       {"before", scores(r.before)}, {"after", scores(r.after)}, {"channel", channelJson(r.source)}});
        } else if (chatty()) {
            if (r.alreadyTiled) {
                std::printf("%s already tiles (worst score %.2f): wrote it unchanged to %s (--force applies %s anyway)\n",
                            r.input.c_str(), worst(r.before), r.output.c_str(), method_.c_str());
            } else {
                std::printf("wrote %s: %dx%d, %s, worst seam score %.2f -> %.2f", r.output.c_str(), r.width, r.height,
                            method_.c_str(), worst(r.before), worst(r.after));
                if (r.remapped)
                    std::printf(", heights mapped into [0,1] as (h %+.4g) * %.4g rather than clipped (--depth float "
                                "keeps them as they are)",
                                -r.remapOffset, r.remapScale);
                std::printf("\n");
            }
            std::fflush(stdout);
            printChannelNote(r.source);
        }
        return ExitCode::Ok;
    }

private:
    static double worst(const LevelSeams& s) {
        return std::max({s.leftRight.value, s.leftRight.slope, s.topBottom.value, s.topBottom.slope});
    }
    bool widthGiven() const { return widthOption_ && widthOption_->count() > 0; }

    std::string input_, output_, channel_, method_ = "periodic", depth_ = "keep";
    TileOptions options_;
    CLI::Option* widthOption_ = nullptr;
};

}  // namespace

std::unique_ptr<Command> makeTileCommand() { return std::make_unique<TileCommand>(); }

}  // namespace heightpack::cli
