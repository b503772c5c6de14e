// heightpack synth: tileable, optionally time-looping ocean height maps from a wave spectrum.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "heightpack/build/synth_job.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/version.hpp"

#include "command.hpp"

namespace heightpack::cli {

namespace {

// A number with an optional unit, as metres per second ("12m/s", "12", "20kn") or seconds ("8s", "8").
std::optional<double> parseWithUnit(const std::string& text, const std::vector<std::pair<std::string, double>>& units) {
    const char* begin = text.c_str();
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    if (end == begin || !std::isfinite(value) || value <= 0) return std::nullopt;
    const std::string unit(end);
    if (unit.empty()) return value;
    for (const auto& [name, factor] : units)
        if (unit == name) return value * factor;
    return std::nullopt;
}

const std::vector<std::pair<std::string, double>> kSpeedUnits = {{"m/s", 1.0}, {"kn", 0.514444}, {"km/h", 1 / 3.6}};
const std::vector<std::pair<std::string, double>> kTimeUnits = {{"s", 1.0}, {"min", 60.0}};

CLI::Validator unitValidator(const std::vector<std::pair<std::string, double>>& units, double max, const char* example) {
    return CLI::Validator(
        [&units, max, example](std::string& text) {
            const auto v = parseWithUnit(text, units);
            char most[32];
            std::snprintf(most, sizeof most, "%g", max);
            return v && *v <= max ? std::string()
                                  : "'" + text + "' is not a positive value up to " + most + " (SI units) like " + example;
        },
        "VALUE");
}

class SynthCommand final : public Command {
public:
    CLI::App* attach(CLI::App& app) override {
        CLI::App* cmd = app.add_subcommand("synth", "synthesise a tileable (and looping) ocean height map from a wave spectrum");
        cmd->add_option("-o,--output", output_, ".exr: heights in metres; .png or .tif: 16-bit, mapped onto [0,1]")
            ->required();
        cmd->add_option("--spectrum", spectrum_, "phillips or jonswap (fetch-limited)")
            ->capture_default_str()
            ->check(CLI::IsMember(allNames<SpectrumModel>()));
        cmd->add_option("--wind", wind_, "wind speed at 10 m: 12m/s, 20kn, 40km/h")->required()->check(unitValidator(kSpeedUnits, 100.0, "12m/s"));
        cmd->add_option("--direction", options_.spectrum.windDirection, "wind direction in degrees, from +x toward +y")
            ->capture_default_str()
            ->check(finiteRange(-360.0, 360.0));
        fetchOption_ = cmd->add_option("--fetch", fetch_, "JONSWAP fetch: 100km, 5000m (jonswap only)")
                           ->default_str("100km")
                           ->check(lengthValidator(1e7));
        gammaOption_ = cmd->add_option("--gamma", options_.spectrum.gamma, "JONSWAP peak enhancement (jonswap only)")
                           ->capture_default_str()
                           ->check(finiteRange(1.0, 10.0));
        cmd->add_option("--tile-size", tileSize_, "metres across the tile: 256m")->required()->check(lengthValidator(1e5));
        cmd->add_option("--size", options_.spectrum.size, "texels across (a power of two)")->capture_default_str();
        cmd->add_option("--seed", options_.spectrum.seed, "random seed: the same seed gives the same bytes")->capture_default_str();
        cmd->add_option("--frames", options_.frames, "write this many frames of a loop (needs --loop)")->capture_default_str();
        cmd->add_flag("--displacement", options_.displacement,
                      "also write Tessendorf's horizontal displacement (choppiness) as channels Dx, Dy (.exr)");
        cmd->add_option("--loop", loop_, "loop period: 8s; the sea at t + period is the sea at t")->check(unitValidator(kTimeUnits, 1e6, "8s"));
        addCommonOptions(*cmd);
        cmd->footer(
            "Examples:\n"
            "  heightpack synth --spectrum phillips --wind 12m/s --direction 30 --tile-size 256m --size 512 -o out/swell.png\n"
            "  heightpack synth --spectrum jonswap --wind 20m/s --fetch 100km --tile-size 1024m --size 1024 --seed 7 -o swell.exr\n"
            "  heightpack synth --spectrum jonswap --wind 8m/s --tile-size 64m --size 256 --frames 32 --loop 8s -o out/ripple_seq.exr\n"
            "Frames go to NAME.0000.EXT ... NAME.<frames-1>.EXT: frame f is the sea at f * loop / frames.\n");
        return cmd;
    }

    ExitCode run() override {
        SpectrumOptions& s = options_.spectrum;
        if (!isPowerOfTwo(s.size) || s.size < 4 || s.size > 8192) return usage("--size must be a power of two from 4 to 8192");
        if (options_.frames < 1 || options_.frames > 10000) return usage("--frames must be 1 to 10000");
        if (options_.frames > 1 && loop_.empty()) return usage("--frames needs --loop: the period the frames cover");
        std::vector<OutputRule> outputs;
        for (int f = 0; f < options_.frames; ++f)
            outputs.push_back({frameFileName(output_, f, options_.frames), "-o", {".exr", ".png", ".tif", ".tiff"}});
        if (const ExitCode code = checkOutputs({}, outputs); code != ExitCode::Ok) return code;
        const std::string ext = lowerExtension(output_);
        if (options_.displacement && ext != ".exr") return usage("--displacement needs an .exr output (channels Y, Dx, Dy)");
        s.model = *parseName<SpectrumModel>(spectrum_);
        if (s.model == SpectrumModel::Phillips && !common_.quiet)
            for (const CLI::Option* o : {fetchOption_, gammaOption_})
                if (o->count() > 0)
                    std::fprintf(stderr, "heightpack: warning: %s is ignored with --spectrum phillips (it shapes "
                                         "jonswap only)\n", o->get_name().c_str());
        s.windSpeed = *parseWithUnit(wind_, kSpeedUnits);
        s.tileSize = *parseLength(tileSize_);
        if (!fetch_.empty()) s.fetch = *parseLength(fetch_);
        if (!loop_.empty()) s.loopPeriod = *parseWithUnit(loop_, kTimeUnits);
        options_.version = kVersion;
        Progress progress(!common_.quiet, "synth " + std::filesystem::path(output_).filename().string(),
                          {{"synth", 0.8}, {"write", 0.2}});
        options_.progress = [&](std::string_view stage, double f) { progress.update(stage, f); };
        auto report = synthesise(output_, options_);
        if (!report) return fail(report.error());
        progress.clear();
        const SynthReport& r = *report;
        if (common_.json) {
            printJson({{"command", "synth"}, {"outputs", r.outputs}, {"spectrum", spectrum_}, {"windSpeed", s.windSpeed},
                       {"tileSize", s.tileSize}, {"size", s.size}, {"seed", s.seed}, {"frames", options_.frames},
                       {"loopPeriod", s.loopPeriod}, {"significantWaveHeight", r.significantWaveHeight},
                       {"expectedSignificantWaveHeight", r.expectedSignificantWaveHeight},
                       {"minHeight", r.minHeight}, {"maxHeight", r.maxHeight}});
        } else if (chatty()) {
            std::printf("wrote %s%s: %dx%d, %s, wind %.3g m/s, tile %.4g m, Hs %.2f m (spectrum %.2f m), heights %.2f..%.2f m\n",
                        r.outputs.front().c_str(), r.outputs.size() > 1 ? (" .. " + r.outputs.back()).c_str() : "", s.size,
                        s.size, spectrum_.c_str(), s.windSpeed, s.tileSize, r.significantWaveHeight,
                        r.expectedSignificantWaveHeight, r.minHeight, r.maxHeight);
        }
        return ExitCode::Ok;
    }

private:
    std::string output_, spectrum_ = nameOf(SpectrumOptions{}.model), wind_, fetch_, tileSize_, loop_;
    SynthOptions options_;
    CLI::Option* fetchOption_ = nullptr;
    CLI::Option* gammaOption_ = nullptr;
};

}  // namespace

std::unique_ptr<Command> makeSynthCommand() { return std::make_unique<SynthCommand>(); }

}  // namespace heightpack::cli
