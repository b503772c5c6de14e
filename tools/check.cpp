// heightpack check: does a map tile, at every mip level? Exit 0 when it does, 1 when it does not.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "heightpack/bake/check_job.hpp"
#include "heightpack/core/parallel.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/threads.hpp"

#include "command.hpp"
#include "enum_option.hpp"
#include "hints.hpp"
#include "look_report.hpp"

namespace heightpack::cli {

namespace {

class CheckCommand final : public Command {
public:
    CLI::App* attach(CLI::App& app) override {
        CLI::App* cmd = app.add_subcommand("check", "tell whether a height map tiles, per edge and mip level (exit 1 if not)");
        cmd->add_option("input", input_, "a height map, or a texture heightpack wrote (packed, plain, normal)")->required();
        cmd->add_option("--threshold", options_.threshold,
                        "largest seam score that passes: how far the tile edge stands out from every other cut, in "
                        "robust standard deviations")
            ->capture_default_str()
            ->check(finiteRange(1.0, 1e6));
        previewOption_ = cmd->add_option("--preview", options_.previewPath, "write a PNG of the map tiled 2x2 with failing seams marked");
        cmd->add_flag("--look-fails", options_.lookFails,
                      "fail (exit 1) when the frame, blob or echo statistic is over its threshold, not only warn");
        cmd->add_option("--frame-threshold", options_.look.frame, "largest frame score that passes (a z-score)")
            ->capture_default_str()
            ->check(finiteRange(0.5, 1e6));
        cmd->add_option("--blob-threshold", options_.look.blobs, "largest blob score that passes (a z-score)")
            ->capture_default_str()
            ->check(finiteRange(0.5, 1e6));
        cmd->add_option("--echo-threshold", options_.look.echo, "largest echo (an autocorrelation) that passes")
            ->capture_default_str()
            ->check(finiteRange(0.0, 1.0));
        addEnumOption(*cmd, "--wrap", options_.mip.wrap, "wrap of the mip chain made from a flat image, as pack would");
        addEnumOption(*cmd, "--filter", options_.mip.filter, "filter of that chain");
        addChannelOption(*cmd, channel_);
        addCommonOptions(*cmd);
        cmd->footer(
            "Examples:\n"
            "  heightpack check examples/maps/painted_not_tileable.png\n"
            "  heightpack check examples/maps/swell.png --json\n"
            "  heightpack check swell.png --preview out/swell_check.png\n"
            "  heightpack check out/swell.exr\n"
            "A score says how far the tile edge stands out from every other place the tile could be cut, in\n"
            "robust standard deviations: 0 to about 5 by chance, large at a seam. value scores jumps in height,\n"
            "slope scores kinks. Every level pack would make is judged (levels under 32 texels a side are too\n"
            "small to judge). Level 0 is also judged as the eye sees it tiled: frame (a band of other contrast\n"
            "around every tile), blobs (along the edges, at the corners) and echo (one feature shown twice in a\n"
            "tile); over a threshold is a warning, or a failure with --look-fails.\n"
            "Exit codes: 0 tiles, 1 does not, 2 usage, 3 bad input, 4 cannot write.\n");
        return cmd;
    }

    ExitCode run() override {
        applyChannel(channel_, options_.load);
        options_.load.silenceDecoderMessages = true;
        options_.mip.threads = common_.threads;
        setLibraryThreads(common_.threads);
        // A sequence is checked frame by frame; it tiles when every frame does. --json prints one document.
        const std::vector<std::string> inputs = expandSequence(input_);
        bool all = true;
        const std::string preview = options_.previewPath;
        if (previewOption_ && previewOption_->count() > 0) {
            std::vector<OutputRule> outputs;
            for (size_t f = 0; f < inputs.size(); ++f)
                outputs.push_back({frameFileName(preview, int(f), int(inputs.size())), "--preview", {".png"}, inputs.size() > 1});
            if (const ExitCode code = checkOutputs(inputs, outputs); code != ExitCode::Ok) return code;
        }
        nlohmann::json frames = nlohmann::json::array();
        // A sequence's previews land together once every frame was read: a bad frame leaves none.
        StagedOutputs staged;
        const bool stage = inputs.size() > 1 && !preview.empty();
        std::vector<std::pair<CheckReport, std::string>> held;  // staged frames' reports, printed once in place
        for (size_t f = 0; f < inputs.size(); ++f) {
            shownPreview_ = preview.empty() ? preview : frameFileName(preview, int(f), int(inputs.size()));
            options_.previewPath = stage ? staged.stage(shownPreview_) : shownPreview_;
            Progress progress(!common_.quiet, "check " + std::filesystem::path(inputs[f]).filename().string(),
                              {{"load", 0.3}, {"mip", 0.3}, {"check", 0.4}});
            options_.progress = [&](std::string_view stage, double fraction) { progress.update(stage, fraction); };
            auto report = checkFile(inputs[f], options_);
            if (!report) return fail(report.error());
            progress.clear();
            all = all && report->passed();
            if (common_.json && inputs.size() > 1)
                frames.push_back(toJson(*report));
            else if (stage)
                held.emplace_back(std::move(*report), shownPreview_);
            else
                print(*report);
        }
        if (Status committed = staged.commit(); !committed) return fail(committed.error());
        for (const auto& [report, shown] : held) {
            shownPreview_ = shown;
            print(report);
        }
        if (common_.json && inputs.size() > 1)
            printJson({{"command", "check"}, {"input", input_}, {"tiles", all}, {"frames", frames}});
        return all ? ExitCode::Ok : ExitCode::CheckFailed;
    }

private:
    nlohmann::json toJson(const CheckReport& r) const {
        const double t = r.threshold;
        nlohmann::json doc = {{"command", "check"}, {"input", r.input}, {"kind", r.kind}, {"tiles", r.tiles},
                              {"threshold", t}, {"levels", seamLevelsJson(r.levels, t)},
                              {"failure", seamFailureJson(r.failure, t)},
                              {"worst", {{"leftRight", seamScoreJson(r.worst.leftRight, t)},
                                         {"topBottom", seamScoreJson(r.worst.topBottom, t)}}}};
        if (!r.note.empty()) doc["note"] = cliNote(r.note, r.noteFix);
        if (r.packing)
            doc["packing"] = {{"consistent", r.packing->consistent}, {"maxError", r.packing->maxError},
                              {"firstBadLevel", r.packing->firstBadLevel}};
        if (!shownPreview_.empty()) doc["preview"] = shownPreview_;
        if (!r.source.channelUsed.empty()) doc["channel"] = channelJson(r.source);
        doc["look"] = lookJson(r.look, r.lookThresholds);
        doc["passed"] = r.passed();
        return doc;
    }

    void print(const CheckReport& r) const {
        if (common_.json) {
            printJson(toJson(r));
        } else if (!common_.quiet) {
            printText(r);
        }
    }

    void printText(const CheckReport& r) const {
        const double t = r.threshold;
        std::printf("%s: %s (threshold %s; 0 to about 5 is how any cut scores by chance)\n", r.input.c_str(),
                    r.tiles ? "tiles" : "does NOT tile", seamScoreText(t, t).c_str());
        if (!r.note.empty()) std::printf("  note: %s\n", cliNote(r.note, r.noteFix).c_str());
        if (!r.source.channelNote.empty()) std::printf("  note: %s\n", r.source.channelNote.c_str());
        // Each score right-aligned under the last letter of its heading ("value", "slope"), FAIL after the pair.
        std::printf("  %-5s %-11s %16s %7s      %16s %7s\n", "level", "size", "left/right value", "slope",
                    "top/bottom value", "slope");
        auto cell = [&](const SeamScore& s) {
            char text[64];
            if (!s.measured)
                std::snprintf(text, sizeof text, "%24s     ", "(too small)");
            else
                std::snprintf(text, sizeof text, "%16s %7s%-5s", seamScoreText(s.value, t).c_str(),
                              seamScoreText(s.slope, t).c_str(), seamPasses(s, t) ? "" : " FAIL");
            return std::string(text);
        };
        for (size_t i = 0; i < r.levels.size(); ++i) {
            const LevelSeams& l = r.levels[i];
            const std::string size = std::to_string(l.width) + "x" + std::to_string(l.height);
            const std::string row = cell(l.leftRight) + " " + cell(l.topBottom);
            std::printf("  %-5zu %-11s %s\n", i, size.c_str(), row.substr(0, row.find_last_not_of(' ') + 1).c_str());
        }
        for (SeamEdge edge : {SeamEdge::LeftRight, SeamEdge::TopBottom}) {
            const SeamScore& worst = edge == SeamEdge::LeftRight ? r.worst.leftRight : r.worst.topBottom;
            if (!worst.measured) {
                std::printf("  %s edges: not measured (no level has 32 texels along and 8 across)\n", seamEdgeName(edge));
            } else if (const auto f = firstSeamFailure(r.levels, t, edge)) {
                std::printf("  SEAM: %s\n", describeSeamFailure(*f, t).c_str());
            } else {
                std::printf("  %s edges: tile at every level (worst score %s)\n", seamEdgeName(edge),
                            seamScoreText(std::max(worst.value, worst.slope), t).c_str());
            }
        }
        if (r.packing)
            std::printf("  packing: %s (largest difference %.3g)\n", r.packing->consistent ? "consistent" : "INCONSISTENT",
                        r.packing->maxError);
        printLook(r.look, r.lookThresholds, r.lookFails);
        if (!shownPreview_.empty()) std::printf("  preview: %s\n", shownPreview_.c_str());
    }

    std::string input_, channel_;
    CheckOptions options_;
    CLI::Option* previewOption_ = nullptr;
    std::string shownPreview_;  // the preview's name as the user gave it (a sequence writes a staged one first)
};

}  // namespace

std::unique_ptr<Command> makeCheckCommand() { return std::make_unique<CheckCommand>(); }

}  // namespace heightpack::cli
