// heightpack synth: tileable, optionally time-looping ocean height maps from a wave spectrum.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "heightpack/bake/synth_job.hpp"
#include "heightpack/core/sea/cascades.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/threads.hpp"
#include "heightpack/version.hpp"

#include "command.hpp"
#include "enum_option.hpp"

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

// --flag VALUE in the units given, bound to a field in SI units: checked and converted once, while parsing.
CLI::Option* addUnitOption(CLI::App& cmd, const std::string& flags, double& field,
                           const std::vector<std::pair<std::string, double>>& units, double max, const char* example,
                           const std::string& description) {
    return cmd.add_option_function<std::string>(
                  flags, [&field, &units](const std::string& text) { field = *parseWithUnit(text, units); }, description)
        ->check(unitValidator(units, max, example));
}

// --swell H,T,DIR: "2.5m,12s,250deg" (units optional): a significant height up to 30 m, a peak period
// from 1 to 30 s, and a direction from -360 to 360 degrees.
std::optional<SwellOptions> parseSwell(const std::string& text) {
    const auto first = text.find(','), second = first == std::string::npos ? first : text.find(',', first + 1);
    if (second == std::string::npos || text.find(',', second + 1) != std::string::npos) return std::nullopt;
    const auto height = parseLength(text.substr(0, first));
    const auto period = parseWithUnit(text.substr(first + 1, second - first - 1), kTimeUnits);
    const std::string dir = text.substr(second + 1);
    char* end = nullptr;
    const double direction = std::strtod(dir.c_str(), &end);
    if (!height || *height > 30.0 || !period || *period < 1.0 || *period > 30.0) return std::nullopt;
    if (end == dir.c_str() || !(std::string(end).empty() || std::string(end) == "deg") || !std::isfinite(direction) ||
        std::abs(direction) > 360.0)
        return std::nullopt;
    SwellOptions swell;
    swell.significantHeight = *height;
    swell.peakPeriod = *period;
    swell.direction = direction;
    return swell;
}

class SynthCommand final : public Command {
public:
    CLI::App* attach(CLI::App& app) override {
        CLI::App* cmd = app.add_subcommand("synth", "synthesise a tileable (and looping) ocean height map from a wave spectrum");
        SpectrumOptions& s = options_.spectrum;
        cmd->add_option("-o,--output", output_, ".exr: heights in metres; .png or .tif: 16-bit, mapped onto [0,1]")
            ->required();
        addEnumOption(*cmd, "--spectrum", s.model, "phillips, jonswap (fetch-limited) or pierson-moskowitz (fully developed)");
        addUnitOption(*cmd, "--wind", s.windSpeed, kSpeedUnits, 100.0, "12m/s", "wind speed at 10 m: 12m/s, 20kn, 40km/h")
            ->required();
        cmd->add_option("--direction", s.windDirection, "wind direction in degrees, from +x toward +y")
            ->capture_default_str()
            ->check(finiteRange(-360.0, 360.0));
        fetchOption_ = addLengthOption(*cmd, "--fetch", s.fetch, 1e7, "JONSWAP fetch: 100km, 5000m (jonswap only)")
                           ->default_str("100km");
        gammaOption_ = cmd->add_option("--gamma", s.gamma, "JONSWAP peak enhancement (jonswap only)")
                           ->capture_default_str()
                           ->check(finiteRange(1.0, 10.0));
        addEnumOption(*cmd, "--spreading", s.spreading, "directional spreading: cos2, cos2s (Mitsuyasu's s) or donelan-banner");
        spreadingSOption_ = cmd->add_option("--spreading-s", s.spreadingExponent, "a fixed cos-2s exponent s (cos2s only)")
                                ->check(finiteRange(0.1, 1000.0));
        addLengthOption(*cmd, "--depth", s.depth, 1e4,
                        "water depth: 30m (finite-depth dispersion; TMA for jonswap, pierson-moskowitz)");
        cmd->add_option("--swell", swell_, "a swell summed with the wind sea: HEIGHT,PERIOD,DIRECTION like 2.5m,12s,250deg")
            ->check(CLI::Validator([](std::string& t) { return parseSwell(t) ? std::string() : "'" + t + "' is not a swell "
                "like 2.5m,12s,250deg (height up to 30 m, period 1 to 30 s, direction -360 to 360)"; }, "H,T,DIR"));
        addLengthOption(*cmd, "--tile-size", s.tileSize, 1e5, "metres across the tile: 256m")->required();
        cmd->add_option("--size", s.size, "texels across (a power of two)")->capture_default_str();
        cmd->add_option("--seed", s.seed, "random seed: the same seed gives the same bytes")->capture_default_str();
        cmd->add_option("--frames", options_.frames, "write this many frames of a loop (needs --loop)")->capture_default_str();
        loopOption_ = addUnitOption(*cmd, "--loop", s.loopPeriod, kTimeUnits, 1e6, "8s",
                                    "loop period: 8s; the sea at t + period is the sea at t");
        cmd->add_flag("--shift,--displacement", options_.shift,
                      "also write Tessendorf's shift, the waves' sideways motion (choppiness), as channels Dx, Dy "
                      "(.exr; --displacement is its old name)");
        cmd->add_flag("--foam", options_.foam, "also write looping foam coverage as channel Foam (.exr; implies --shift)");
        cmd->add_option("--choppiness", options_.choppiness, "the lambda of x + lambda D that foam and folds assume")
            ->capture_default_str()
            ->check(finiteRange(0.0, 10.0));
        cmd->add_option("--foam-threshold", options_.foamOptions.threshold, "foam forms where the Jacobian J is below this")
            ->capture_default_str()
            ->check(finiteRange(-2.0, 2.0));
        addUnitOption(*cmd, "--foam-decay", options_.foamOptions.decay, kTimeUnits, 1e4, "2s", "foam's e-folding time: 2s")
            ->default_str("2s");
        cmd->add_option("--foam-build-up", options_.foamOptions.buildUp, "foam gained per second per unit of J below the threshold")
            ->capture_default_str()
            ->check(finiteRange(0.0, 1000.0));
        cmd->add_option("--cascades", options_.cascades, "bake N tiles of sizes tile * (17/61)^c, disjoint bands: NAME_c0.EXT ...")
            ->capture_default_str()
            ->check(CLI::Range(1, kMaxCascades));
        addEnumOption(*cmd, "--compression", options_.compression,
                      "an .exr's compression: none (the default: deflate saves 3-4% of float heights and "
                      "shift, which are noise, in most of the write's time), zip (about 27% with foam), zips",
                      {Compression::None, Compression::Zip, Compression::Zips});
        cmd->add_flag("--report", options_.report, "print the sea state: Hs, peak period, steepness, folds, shift");
        addCommonOptions(*cmd);
        cmd->footer(
            "Examples:\n"
            "  heightpack synth --spectrum phillips --wind 12m/s --direction 30 --tile-size 256m --size 512 -o out/swell.png\n"
            "  heightpack synth --spectrum jonswap --wind 20m/s --fetch 100km --tile-size 1024m --size 1024 --seed 7 -o swell.exr\n"
            "  heightpack synth --spectrum jonswap --wind 8m/s --tile-size 64m --size 256 --frames 32 --loop 8s -o out/ripple_seq.exr\n"
            "  heightpack synth --spectrum jonswap --wind 14m/s --fetch 200km --swell 2.5m,12s,250deg --depth 30m \\\n"
            "    --spreading donelan-banner --tile-size 256m --size 512 --loop 20s --frames 60 --foam --report -o out/sea.exr\n"
            "  heightpack synth --spectrum pierson-moskowitz --wind 10m/s --tile-size 512m --size 256 --cascades 3 -o out/sea.exr\n"
            "Frames go to NAME.0000.EXT ... NAME.<frames-1>.EXT: frame f is the sea at f * loop / frames; cascade c\n"
            "to NAME_cC.EXT. With --foam an .exr holds channels Y, Dx, Dy, Foam; frame <frames> would equal frame 0.\n");
        return cmd;
    }

    ExitCode run() override {
        SpectrumOptions& s = options_.spectrum;
        if (!isPowerOfTwo(s.size) || s.size < 4 || s.size > 8192) return usage("--size must be a power of two from 4 to 8192");
        if (options_.frames < 1 || options_.frames > 10000) return usage("--frames must be 1 to 10000");
        if (options_.frames > 1 && loopOption_->count() == 0) return usage("--frames needs --loop: the period the frames cover");
        const int count = std::max(1, options_.cascades);
        if (count > 1 && s.size < kCascadeMinSize)
            return usage("--cascades needs --size " + std::to_string(kCascadeMinSize) + " or more: each band needs rings of waves");
        std::vector<OutputRule> outputs;
        for (int c = 0; c < count; ++c)
            for (int f = 0; f < options_.frames; ++f)
                outputs.push_back({frameFileName(cascadeFileName(output_, c, count), f, options_.frames), "-o",
                                   {".exr", ".png", ".tif", ".tiff"}});
        if (const ExitCode code = checkOutputs({}, outputs); code != ExitCode::Ok) return code;
        if (spreadingSOption_->count() > 0 && s.spreading != Spreading::Cos2s)
            return usage("--spreading-s sets the cos-2s exponent: give it with --spreading cos2s");
        if (s.model != SpectrumModel::Jonswap && !common_.quiet)
            for (const CLI::Option* o : {fetchOption_, gammaOption_})
                if (o->count() > 0)
                    std::fprintf(stderr, "heightpack: warning: %s is ignored with --spectrum %s (it shapes jonswap only)\n",
                                 o->get_name().c_str(), nameOf(s.model));
        if (!swell_.empty()) s.swell = *parseSwell(swell_);
        options_.shift = options_.shift || options_.foam;
        options_.threads = common_.threads;
        // OpenEXR deflates the frames' blocks on its pool: with four float channels of noise-like data
        // that is most of a 4096 frame's time on one thread.
        setLibraryThreads(common_.threads);
        Progress progress(!common_.quiet, "synth " + std::filesystem::path(output_).filename().string(),
                          {{"synth", 0.8}, {"write", 0.2}});
        options_.progress = [&](std::string_view stage, double f) { progress.update(stage, f); };
        auto report = synthesise(output_, options_);
        if (!report) return fail(report.error());
        progress.clear();
        print(*report);
        return ExitCode::Ok;
    }

private:
    static nlohmann::json tileJson(const SynthTileReport& t) {
        auto optional = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
        return {{"outputs", t.outputs}, {"tileSize", t.tileSize}, {"bandLow", t.bandLow}, {"bandHigh", t.bandHigh},
                {"significantWaveHeight", t.significantWaveHeight},
                {"expectedSignificantWaveHeight", t.expectedSignificantWaveHeight}, {"minHeight", t.minHeight},
                {"maxHeight", t.maxHeight}, {"peakPeriod", t.peakPeriod}, {"peakWavelength", t.peakWavelength},
                {"steepness", t.steepness}, {"foldFraction", optional(t.foldFraction)},
                {"maxDisplacement", optional(t.maxShift)}, {"displacementBound", optional(t.shiftBound)}};
    }

    static void printTile(const SynthTileReport& t, const char* indent) {
        std::printf("%sHs %.3f m from the heights (4 std), %.3f m from the spectrum (4 sqrt(m0))\n", indent,
                    t.significantWaveHeight, t.expectedSignificantWaveHeight);
        std::printf("%speak period %.2f s, peak wavelength %.1f m, steepness Hs/Lp %.4f\n", indent, t.peakPeriod,
                    t.peakWavelength, t.steepness);
        if (t.foldFraction) std::printf("%sfolds (J < 0): %.4f %% of texels\n", indent, 100.0 * *t.foldFraction);
        if (t.maxShift)
            std::printf("%sshift (Dx, Dy): largest %.3f m, bound %.3f m\n", indent, *t.maxShift,
                        *t.shiftBound);
    }

    void print(const SynthReport& r) const {
        const SpectrumOptions& s = options_.spectrum;
        if (common_.json) {
            nlohmann::json j = {{"command", "synth"}, {"outputs", r.outputs}, {"spectrum", nameOf(s.model)}, {"windSpeed", s.windSpeed},
                                {"tileSize", s.tileSize}, {"size", s.size}, {"seed", s.seed}, {"frames", options_.frames},
                                {"loopPeriod", s.loopPeriod}, {"depth", s.depth}, {"spreading", nameOf(s.spreading)},
                                {"choppiness", options_.choppiness}, {"significantWaveHeight", r.significantWaveHeight},
                                {"expectedSignificantWaveHeight", r.expectedSignificantWaveHeight},
                                {"minHeight", r.minHeight}, {"maxHeight", r.maxHeight}};
            if (r.tiles.size() == 1) j["report"] = tileJson(r.tiles[0]);
            nlohmann::json cascades = nlohmann::json::array();
            if (r.tiles.size() > 1)
                for (const SynthTileReport& t : r.tiles) cascades.push_back(tileJson(t));
            j["cascades"] = cascades;
            printJson(j);
            return;
        }
        if (!chatty()) return;
        std::printf("wrote %s%s: %dx%d, %s, wind %.3g m/s, tile %.4g m, Hs %.2f m (spectrum %.2f m), heights %.2f..%.2f m\n",
                    r.outputs.front().c_str(), r.outputs.size() > 1 ? (" .. " + r.outputs.back()).c_str() : "", s.size,
                    s.size, nameOf(s.model), s.windSpeed, s.tileSize, r.significantWaveHeight,
                    r.expectedSignificantWaveHeight, r.minHeight, r.maxHeight);
        if (!options_.report) return;
        for (size_t c = 0; c < r.tiles.size(); ++c) {
            const SynthTileReport& t = r.tiles[c];
            if (r.tiles.size() > 1)
                std::printf("cascade %zu: tile %.4g m, |k| in [%.4g, %.4g) rad/m\n", c, t.tileSize, t.bandLow, t.bandHigh);
            printTile(t, "  ");
        }
    }

    std::string output_;
    std::string swell_;
    SynthOptions options_;
    CLI::Option* fetchOption_ = nullptr;
    CLI::Option* loopOption_ = nullptr;
    CLI::Option* gammaOption_ = nullptr;
    CLI::Option* spreadingSOption_ = nullptr;
};

}  // namespace

std::unique_ptr<Command> makeSynthCommand() { return std::make_unique<SynthCommand>(); }

}  // namespace heightpack::cli
