// heightpack build: every texture of one or more water material manifests, rebuilt only where inputs
// or options changed, with material.json for the viewer and engines.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>

#include "heightpack/bake/build/action_plan.hpp"
#include "heightpack/bake/build/build_materials.hpp"
#include "heightpack/bake/build/cache_session.hpp"
#include "heightpack/core/parallel.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/threads.hpp"
#include "heightpack/version.hpp"

#include "build_report_json.hpp"
#include "cache_report.hpp"
#include "command.hpp"
#include "enum_option.hpp"
#include "hints.hpp"
#include "look_report.hpp"
#include "option_values.hpp"

namespace heightpack::cli {

namespace {

namespace fs = std::filesystem;

class BuildCommand final : public Command {
public:
    CLI::App* attach(CLI::App& app) override {
        CLI::App* cmd = app.add_subcommand("build", "build every texture of a water material manifest, incrementally");
        cmd->add_option("manifests", manifests_, "material manifests (.toml; see " + manifestReference() + ")");
        cmd->add_option("-o,--output", output_,
                        "output folder: the material's own for one manifest, else one subfolder per material name");
        cmd->add_option("-j,--jobs", jobs_, "assets built at once (output bytes are the same for any number)")
            ->capture_default_str()
            ->check(CLI::Range(1, 256));
        cmd->add_flag("--check-only", checkOnly_, "validate the manifests and run the tileability checks; write nothing");
        cmd->add_flag("--force", force_, "rebuild every output, even those up to date");
        cmd->add_option("--depfile", depfile_, "write a Make/Ninja depfile listing the manifest and every source it reads");
        cmd->add_option("--stamp", stamp_, "touch this file after a successful build; the depfile's target (for CMake)");
        cmd->add_option("--cache", cache_,
                        "shared cache: a folder (local or a network share) or an http(s):// server that takes PUT "
                        "(default: $HEIGHTPACK_CACHE; a server's token from $HEIGHTPACK_CACHE_TOKEN): outputs another "
                        "build made with the same inputs and options are copied from it, not baked; what is baked is stored")
            ->type_name("FOLDER|URL");
        cacheModeOption_ = addEnumOption(*cmd, "--cache-mode", cacheMode_,
                                         "read-only: restore from the cache, never write to it (default: "
                                         "$HEIGHTPACK_CACHE_MODE, else read-write)");
        cmd->add_option("--cache-size", cacheSize_,
                        "the most a cache folder may hold after the build; least recently used entries go (default 10G; "
                        "not for a server, which keeps its own size)")
            ->check(byteSizeValidator());
        plan_ = addEnumOption(*cmd, "--plan", planFormat_,
                              "write the build as actions on stdout (one per output, each `build --only OUTPUT`) "
                              "for Ninja, Bazel or a farm to run (bazel-workspace: Bazel's rule for this heightpack, "
                              "no manifest); build nothing")
                    ->default_str("");
        cmd->add_option("--only", only_, "make this one output (as the plan names it), or with material.json record "
                                         "every output made and describe the material: a plan's action")
            ->type_name("OUTPUT");
        addCommonOptions(*cmd);
        cmd->footer(
            "Examples:\n"
            "  heightpack build examples/ocean.toml -o out/ocean\n"
            "  heightpack build examples/ocean.toml -o out/ocean --plan ninja > ocean.ninja && ninja -f ocean.ninja -j 8\n"
            "  heightpack build --plan bazel-workspace > WORKSPACE && heightpack build ocean.toml -o out/ocean --plan bazel > BUILD.bazel\n"
            "  heightpack build examples/*.toml -o out --jobs 2 --json\n"
            "  heightpack build examples/ocean.toml --check-only\n"
            "  heightpack build examples/ocean.toml -o out/ocean --cache /mnt/share/hp-cache --cache-size 50G\n"
            "  heightpack build examples/ocean.toml -o out/ocean --cache http://cache.studio:8080/hp --cache-mode read-only\n"
            "  heightpack-view out/ocean/material.json\n"
            "Only outputs whose source bytes or options changed are rebuilt (content hashes, not timestamps).\n"
            "With --cache, each output to rebuild is first looked up by its key (inputs, options, version) and,\n"
            "when another build stored it, copied after checking its size and hash: 'restored from cache'.\n"
            "Exit codes: 0 built or up to date, 1 a map that must tile does not (nothing written), 2 usage,\n"
            "3 bad manifest or source (FILE:LINE named), 4 cannot write output.\n");
        return cmd;
    }

    ExitCode run() override {
        const bool workspace = plan_->count() && planFormat_ == PlanFormat::BazelWorkspace;
        if (workspace && (!manifests_.empty() || !output_.empty()))
            return usage("--plan bazel-workspace prints how Bazel finds this heightpack: it takes no manifest and no -o");
        if (workspace) return printPlan({}, "");
        if (manifests_.empty()) return usage("give the material manifests to build (.toml)");
        if (!checkOnly_ && output_.empty()) return usage("give the output folder with -o (or use --check-only)");
        if (checkOnly_ && (!depfile_.empty() || !stamp_.empty()))
            return usage("--depfile and --stamp write files; --check-only writes nothing");
        // An explicit --cache with --check-only is a mistake to point out; $HEIGHTPACK_CACHE, set once for
        // every build of a machine, is simply not used by a build that writes nothing.
        if (checkOnly_ && cache_) return usage("--cache stores what a build writes; --check-only writes nothing");
        if (cache_ && cache_->empty()) return usage("--cache needs a folder or a URL");
        const char* cacheFromEnvironment = std::getenv("HEIGHTPACK_CACHE");
        const std::string cacheText = cache_ ? *cache_ : checkOnly_ || !cacheFromEnvironment ? "" : cacheFromEnvironment;
        std::optional<CacheLocation> cacheLocation;
        if (!cacheText.empty()) {
            auto parsed = parseCacheLocation(cacheText);
            if (!parsed)
                return usage(std::string(cache_ ? "--cache" : "HEIGHTPACK_CACHE") + ": " + parsed.error().what + " (" +
                             parsed.error().hint + ")");
            cacheLocation = *parsed;
        }
        if (ExitCode e = resolveCacheMode(cacheLocation.has_value()); e != ExitCode::Ok) return e;
        if (cacheLocation && cacheLocation->backend == CacheBackend::Http && !cacheSize_.empty())
            return usage("--cache-size limits a cache folder; a server keeps its own size (leave --cache-size out)");
        // Printed, recorded and handed on: never holds a URL's credentials.
        const std::string cacheFolder = cacheLocation ? cacheLocation->where : "";
        if (plan_->count() && (checkOnly_ || !only_.empty() || !depfile_.empty() || !stamp_.empty() || force_))
            return usage("--plan writes the build as actions and builds nothing: it goes without --check-only, --only, "
                         "--force, --depfile and --stamp");
        if (plan_->count() && planFormat_ == PlanFormat::Bazel && cache_)
            return usage("--plan bazel's actions share results through Bazel's own cache (bazel build "
                         "--remote_cache=URL), not --cache");
        if (!only_.empty() && manifests_.size() != 1) return usage("--only names an output of one manifest: give one");
        setLibraryThreads(common_.threads);

        // Everything is parsed before anything is built: a bad manifest stops the build before it starts.
        // An action that makes one output may run where only the files that output reads are (Bazel's sandbox).
        const bool oneOutput = !only_.empty() && only_ != kMaterialFile;
        auto manifests = parseManifests(manifests_, oneOutput ? SourceCheck::MayBeAbsent : SourceCheck::MustExist);
        if (!manifests) return fail(manifests.error());
        if (plan_->count()) return printPlan(*manifests, cacheFolder);

        const auto start = std::chrono::steady_clock::now();
        Tracker tracker(*this);  // one bar for the whole build, every material's outputs
        BuildOptions options;
        options.outputDir = output_;
        options.jobs = jobs_;
        options.threads = common_.threads;
        options.checkOnly = checkOnly_;
        options.force = force_;
        options.only = only_;
        options.cache.location = cacheLocation;
        options.cache.mode = cacheMode_;
        if (const char* token = std::getenv("HEIGHTPACK_CACHE_TOKEN")) options.cache.token = token;
        if (!cacheSize_.empty()) options.cache.sizeLimit = *parseByteSize(cacheSize_);
        if (cacheLocation) {
            auto opened = SharedCache::open(options.cache);
            if (!opened) return fail(opened.error());
            options.sharedCache = *opened;
        }
        options.onEvent = [&tracker](const BuildEvent& e) { tracker.event(e); };
        MaterialsOptions files;
        files.depfile = depfile_;
        files.stamp = stamp_;
        files.onPrepared = [&](const BuildReport& r) {
            tracker.progress.clear();
            tracker.total += static_cast<double>(r.assets.size());
            for (const Error& e : r.checkFailures) printError(e);
        };
        files.onBuilding = [&](const BuildReport& r) {
            if (chatty()) std::printf("building %s (%s) into %s\n", r.material.c_str(), r.manifest.c_str(), r.outputDir.c_str());
            std::fflush(stdout);
        };
        files.onBuilt = [&](const BuildReport& r, double seconds) {
            tracker.progress.clear();
            if (!common_.quiet && options.sharedCache) warnAboutEntries(r, *options.sharedCache);
            if (chatty()) printSummary(r, seconds);
        };
        auto built = buildMaterials(*manifests, options, files);
        tracker.progress.clear();
        if (!built) return fail(built.error());
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

        // Nothing was made when a check failed or only checks were asked for: say so per material.
        const bool checksPassed = built->checksPassed;
        CacheCounts cacheCounts;
        for (const BuildReport& report : built->materials) cacheCounts += report.cache();
        const CacheTrim& trim = built->cacheTrim;
        if (!common_.quiet && cacheLocation) warnAboutOutages(options.cache, built->cacheOutages);
        if (cacheLocation && chatty() && checksPassed && !checkOnly_) printCacheSummary(options.cache, cacheCounts, trim);
        nlohmann::json materials = nlohmann::json::array();
        for (size_t i = 0; i < built->materials.size(); ++i) {
            const BuildReport& report = built->materials[i];
            if ((checkOnly_ || !checksPassed) && chatty()) {
                if (checkOnly_ || !report.checkFailures.empty())
                    printSummary(report, 0.0);
                else
                    std::printf("%s: nothing written: another material's maps failed their checks\n", report.material.c_str());
            }
            materials.push_back(buildReportJson(report, (*manifests)[i].threshold, checkOnly_));
        }
        if (common_.json) {
            nlohmann::json cache = nullptr;
            if (cacheLocation) cache = cacheReportJson(options.cache, cacheCounts, trim, built->cacheOutages);
            printJson({{"command", "build"}, {"checkOnly", checkOnly_}, {"ok", checksPassed}, {"jobs", jobs_},
                       {"seconds", seconds}, {"cache", cache}, {"materials", materials}});
        }
        return checksPassed ? ExitCode::Ok : ExitCode::CheckFailed;
    }

private:
    // The plan on stdout; each action carries the cache this build would use (but Bazel's, which has
    // its own: --remote_cache).
    ExitCode printPlan(const std::vector<Manifest>& manifests, const std::string& cacheFolder) const {
        std::error_code ec;
        const fs::path self = fs::read_symlink("/proc/self/exe", ec);
        const bool bazel = planFormat_ == PlanFormat::Bazel;
        std::vector<std::string> extra;
        if (!cacheFolder.empty() && !bazel) {
            extra = {"--cache", cacheFolder};
            if (!cacheSize_.empty()) extra.insert(extra.end(), {"--cache-size", cacheSize_});
            if (cacheMode_ == CacheMode::ReadOnly) extra.insert(extra.end(), {"--cache-mode", "read-only"});
        }
        const std::string program = ec ? std::string("heightpack") : self.string();
        auto actions = planActions(manifests, output_, program, kVersion, bazel);
        for (BuildAction& a : actions) {
            a.command = {program, "build", a.manifest, "-o", a.folder, "--only", a.only, "-q"};
            a.command.insert(a.command.end(), extra.begin(), extra.end());
        }
        std::string text;
        if (planFormat_ == PlanFormat::BazelWorkspace) {
            text = bazelWorkspace(program);
        } else if (bazel) {
            auto build = bazelBuildFile(actions);
            if (!build) return fail(build.error());
            text = *build;
        } else {
            text = planFormat_ == PlanFormat::Ninja ? ninjaFile(actions) : actionsJson(actions);
        }
        std::fwrite(text.data(), 1, text.size(), stdout);
        return ExitCode::Ok;
    }

    // The build's progress on the terminal: a line per finished output and one bar for every output of
    // every material. The bar counts finished outputs plus how far each one in progress has come, its
    // stages weighted roughly by their cost, so it only moves forward whatever order the jobs report in;
    // its label counts outputs rather than naming one, so parallel jobs do not make it flicker.
    struct Tracker {
        explicit Tracker(const BuildCommand& command)
            : chatty(command.chatty()), progress(!command.common_.quiet, command.checkOnly_ ? "check" : "build") {}

        void event(const BuildEvent& e) {
            const std::string& output = e.asset.output;
            if (e.type == BuildEvent::Type::Done) {
                inFlight.erase(output);
                done += 1.0;
                if (chatty) {
                    progress.clear();
                    printAsset(e.asset);
                }
            } else {
                const double f = e.fraction;
                const double part = e.stage == "load" ? 0.2 * f
                                    : e.stage == "write" ? 0.5 + 0.5 * f
                                    : e.stage == "hash" || e.stage == "check" ? 0.0
                                                                              : 0.2 + 0.3 * f;  // mip, normal
                inFlight[output] = std::max(inFlight[output], part);
            }
            double fraction = done;
            for (const auto& [name, part] : inFlight) fraction += part;
            const std::string label = e.stage == "check" || e.stage == "hash"
                                          ? std::string("checking")
                                          : std::to_string(static_cast<int>(done)) + "/" +
                                                std::to_string(static_cast<int>(total)) + " outputs";
            progress.update(label, total > 0 ? fraction / total : 0.0);
        }

        bool chatty;
        Progress progress;
        double total = 0.0;  // outputs of every material prepared so far
        double done = 0.0;
        std::map<std::string, double> inFlight;
    };

    static void printAsset(const AssetReport& a) {
        // The status column as wide as the widest status ("restored from cache"), so the outputs line up.
        static const int width = [] {
            size_t widest = 0;
            for (const EnumName<AssetStatus>& e : NameTable<AssetStatus>::entries) widest = std::max(widest, std::strlen(e.name));
            return static_cast<int>(widest);
        }();
        std::string what = a.kind + " '" + a.name + "'";
        if (a.frame >= 0) what += " frame " + std::to_string(a.frame);
        if (a.status == AssetStatus::Rebuilt)
            std::printf("  %-*s %-28s %-30s %6.2f s\n", width, assetStatusName(a.status), a.output.c_str(), what.c_str(),
                        a.seconds);
        else
            std::printf("  %-*s %-28s %s\n", width, assetStatusName(a.status), a.output.c_str(), what.c_str());
        std::fflush(stdout);
    }

    void printSummary(const BuildReport& r, double seconds) const {
        if (checkOnly_) {
            for (const AssetReport& a : r.assets) {
                const char* verdict = a.check         ? (a.check->tiles ? "tiles" : "does NOT tile")
                                      : a.input.empty() ? "nothing to check (made, not painted)"
                                                        : "not checked (tileable = false)";
                const bool lookOver = a.check && a.check->ran && !a.check->look.passes(a.check->lookThresholds);
                std::printf("  %-28s %-30s %s%s\n", a.output.c_str(), (a.kind + " '" + a.name + "'").c_str(), verdict,
                            lookOver ? ("; WARNING look: " + lookText(a.check->look, a.check->lookThresholds)).c_str() : "");
            }
            std::printf("%s: %s\n", r.material.c_str(),
                        r.checkFailures.empty() ? "manifest valid, every map that must tile does" : "checks FAILED");
            return;
        }
        if (!r.checkFailures.empty()) {
            std::printf("%s: nothing written: %zu map(s) must tile and do not\n", r.material.c_str(), r.checkFailures.size());
            return;
        }
        if (r.staleTemporariesRemoved > 0)
            std::printf("  removed %d temporary file(s) an interrupted build left\n", r.staleTemporariesRemoved);
        if (r.rebuilt() == 0 && r.restored() == 0 && !r.materialWritten)
            std::printf("%s: nothing to do, all %zu outputs up to date (%.2f s)\n", r.material.c_str(), r.assets.size(), seconds);
        else if (r.restored() > 0)
            std::printf("%s: %d rebuilt, %d restored from cache, %d up to date, material.json %s (%.2f s)\n",
                        r.material.c_str(), r.rebuilt(), r.restored(), r.upToDate(),
                        r.materialWritten ? "written" : "unchanged", seconds);
        else
            std::printf("%s: %d rebuilt, %d up to date, material.json %s (%.2f s)\n", r.material.c_str(), r.rebuilt(),
                        r.upToDate(), r.materialWritten ? "written" : "unchanged", seconds);
    }

    // The cache's mode: --cache-mode, else $HEIGHTPACK_CACHE_MODE, else read-write; a usage error for a
    // name outside the table, or for --cache-mode without a cache.
    ExitCode resolveCacheMode(bool cached) {
        if (cacheModeOption_->count()) return cached ? ExitCode::Ok : usage("--cache-mode says how to use a cache: give one with --cache");
        const char* fromEnvironment = std::getenv("HEIGHTPACK_CACHE_MODE");
        if (!cached || !fromEnvironment || !*fromEnvironment) return ExitCode::Ok;  // set per machine, used by builds with a cache
        const auto mode = parseName<CacheMode>(fromEnvironment);
        if (!mode)
            return usage("HEIGHTPACK_CACHE_MODE: " + std::string(fromEnvironment) + " not in {" +
                         joinedNames<CacheMode>(",") + "}");
        cacheMode_ = *mode;
        return ExitCode::Ok;
    }

    CLI::Option* cacheModeOption_ = nullptr;
    CacheMode cacheMode_ = CacheMode::ReadWrite;
    CLI::Option* plan_ = nullptr;
    PlanFormat planFormat_ = PlanFormat::Ninja;
    std::string only_;
    std::vector<std::string> manifests_;
    std::optional<std::string> cache_;
    std::string cacheSize_;
    std::string output_, depfile_, stamp_;
    int jobs_ = 1;
    bool checkOnly_ = false, force_ = false;
};

}  // namespace

std::unique_ptr<Command> makeBuildCommand() { return std::make_unique<BuildCommand>(); }

}  // namespace heightpack::cli
