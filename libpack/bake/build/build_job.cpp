#include "heightpack/bake/build/build_job.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <set>

#include "heightpack/bake/build/build_state.hpp"
#include "heightpack/bake/build/cache_key.hpp"
#include "heightpack/bake/material_describe.hpp"
#include "heightpack/core/parallel.hpp"
#include "heightpack/io/files.hpp"

#include "build_common.hpp"
#include "build_failures.hpp"
#include "build_plan.hpp"
#include "work_queue.hpp"

namespace heightpack {

namespace fs = std::filesystem;
using detail::forEachParallel;
using detail::describeFailure;
using detail::guarded;
using detail::planSharedSteps;
using detail::planSteps;
using detail::readText;
using detail::Step;
using detail::tileFailure;

int BuildReport::rebuilt() const {
    return static_cast<int>(std::count_if(assets.begin(), assets.end(), [](const AssetReport& a) { return a.status == AssetStatus::Rebuilt; }));
}
int BuildReport::upToDate() const {
    return static_cast<int>(std::count_if(assets.begin(), assets.end(), [](const AssetReport& a) { return a.status == AssetStatus::UpToDate; }));
}
int BuildReport::restored() const {
    return static_cast<int>(std::count_if(assets.begin(), assets.end(), [](const AssetReport& a) { return a.status == AssetStatus::Restored; }));
}

void CacheCounts::add(const AssetCacheUse& use) {
    stored += use.stored;
    errors += use.unavailable || use.storeUnavailable || !use.storeFailed.empty();
    if (!use.looked) return;
    hits += use.hit;
    misses += !use.hit && !use.unavailable;
    rejected += !use.rejected.empty();
}
CacheCounts& CacheCounts::operator+=(const CacheCounts& other) {
    hits += other.hits;
    misses += other.misses;
    stored += other.stored;
    rejected += other.rejected;
    errors += other.errors;
    return *this;
}
CacheCounts BuildReport::cache() const {
    CacheCounts counts;
    for (const AssetReport& a : assets) counts.add(a.cache);
    return counts;
}

// Everything a build holds between preparing (hashes, checks) and running (writing).
struct MaterialBuild::Impl {
    Manifest m;
    BuildOptions options;
    std::vector<Step> steps;
    fs::path folder;
    std::string statePath;
    BuildState state;
    BuildReport report;
    int jobs = 1, threads = 1;
    bool ran = false;
    std::mutex mutex;  // guards state, events and the steps' shared fields

    void emit(BuildEvent::Type type, const Step& s, std::string_view stage, double fraction) {
        if (!options.onEvent) return;
        std::lock_guard<std::mutex> lock(mutex);
        options.onEvent({type, s.report, stage, fraction});
    }
    Error inAsset(Error e, const Step& s) const { return detail::inAsset(std::move(e), s, m.path); }
    std::optional<Error> firstError() const {
        for (const Step& s : steps)
            if (s.error) return s.error;
        return std::nullopt;
    }

    Status prepare();
    Status run();
    void hashStep(Step& s);
    void checkStep(Step& s);
    void makeStep(Step& s, std::atomic<bool>& stop);
    Result<std::string> restoreStep(Step& s, const std::string& output);
    void storeStep(Step& s, const std::string& output, const std::string& hash);
    Status recordMadeOutputs();
};

Status MaterialBuild::Impl::prepare() {
    report.manifest = m.path;
    report.material = m.name;
    report.outputDir = options.outputDir;
    steps = planSteps(m, options.version);
    if (!options.only.empty() && options.only != kMaterialFile) {
        for (Step& shared : planSharedSteps(m, options.version)) steps.push_back(std::move(shared));
        const auto one = std::find_if(steps.begin(), steps.end(), [&](const Step& s) { return s.report.output == options.only; });
        if (one == steps.end())
            return Error{ErrorKind::InconsistentOptions, m.path, "makes no output named '" + options.only + "'",
                         "name an output as the plan does (its path inside the output folder), or material.json"};
        std::vector<Step> alone;
        alone.push_back(std::move(*one));
        steps = std::move(alone);
    }

    std::set<std::string> dependencies{fs::absolute(m.path).lexically_normal().string()};
    for (const Step& s : steps)
        if (!s.report.input.empty()) dependencies.insert(fs::absolute(s.report.input).lexically_normal().string());
    report.dependencies.assign(dependencies.begin(), dependencies.end());

    folder = fs::path(options.outputDir);
    // An output over a source would destroy the source: refuse before anything is written.
    std::map<fs::path, std::string> sources;  // canonical path -> the source as listed
    for (const std::string& source : dependencies) sources.emplace(fs::weakly_canonical(source), source);
    for (const Step& s : steps) {
        const auto clash = sources.find(fs::weakly_canonical(folder / s.report.output));
        if (clash != sources.end())
            return cannotWrite((folder / s.report.output).string(),
                               "is also a source this material reads (" + clash->second + ")", "choose another output folder");
    }
    statePath = (folder / kBuildStateFile).string();
    // Every path the build will write is judged before anything is: a build that cannot finish must
    // not leave half its outputs behind.
    if (!options.checkOnly) {
        std::vector<fs::path> outputs{statePath, folder / kMaterialFile};
        if (options.only != kMaterialFile)  // which only reads them (in a sandbox, links to an executor's files)
            for (const Step& s : steps) outputs.push_back(folder / s.report.output);
        for (const fs::path& p : outputs)
            if (Status ok = checkOutputPath(p); !ok) return ok.error();
        state = readBuildState(statePath);
    }
    jobs = std::max(1, options.jobs);
    threads = options.threads > 0 ? options.threads : std::max(1, resolveThreadCount(0) / jobs);

    // 1. What changed: hash every input and every recorded output.
    forEachParallel(steps.size(), jobs, [&](size_t i) { guarded(steps[i], [&] { hashStep(steps[i]); }); });
    if (auto e = firstError()) return *e;
    if (options.only == kMaterialFile)
        if (Status taken = recordMadeOutputs(); !taken) return taken;

    // 2. Tileability, before anything is written: a map that must tile and does not stops the build.
    forEachParallel(steps.size(), jobs, [&](size_t i) {
        Step& s = steps[i];
        if (s.mustTile) s.report.check = AssetCheck{false, !s.needCheck, true, {}, {}, {}, {}};
        if (s.needCheck) guarded(s, [&] { checkStep(s); });
    });
    if (auto e = firstError()) return *e;
    for (const Step& s : steps)
        if (s.report.check && !s.report.check->tiles) report.checkFailures.push_back(tileFailure(s, m.path));
    for (Step& s : steps) {
        s.report.status = options.checkOnly ? (s.needCheck ? AssetStatus::Checked : AssetStatus::Skipped)
                                            : AssetStatus::UpToDate;
        report.assets.push_back(s.report);
    }
    return Done{};
}

void MaterialBuild::Impl::hashStep(Step& s) {
    emit(BuildEvent::Type::Progress, s, "hash", 0.0);
    std::string inputHash;
    if (!s.report.input.empty()) {
        auto h = hashFile(s.report.input);
        if (!h) return void(s.error = inAsset(h.error(), s));
        inputHash = *h;
    }
    s.report.inputHash = inputHash;
    s.report.key = cacheKey(options.version, s.optionsText, inputHash);
    s.checkKey = cacheKey(options.version, s.checkText, inputHash);
    if (options.checkOnly) {
        s.needCheck = s.mustTile;
        return;
    }
    if (!options.only.empty()) {  // an action: made when the executor says, checked when made
        s.needBuild = options.only != kMaterialFile;
        s.needCheck = s.needBuild && s.mustTile;
        return;
    }
    const auto entry = state.find(s.report.output);
    bool upToDate = !options.force && entry != state.end() && entry->second.key == s.report.key;
    if (upToDate) {
        const std::string output = (folder / s.report.output).string();
        std::error_code ec;
        auto h = fs::is_regular_file(output, ec) ? hashFile(output) : Result<std::string>(Error{});
        upToDate = h.ok() && *h == entry->second.hash;
    }
    s.needBuild = !upToDate;
    s.needCheck = s.mustTile && (s.needBuild || entry == state.end() || entry->second.checked != s.checkKey);
}

void MaterialBuild::Impl::checkStep(Step& s) {
    emit(BuildEvent::Type::Start, s, "check", 0.0);
    CheckOptions check = s.check;
    check.mip.threads = threads;
    auto r = checkFile(s.report.input, check);
    if (!r) return void(s.error = inAsset(r.error(), s));
    AssetCheck& c = *s.report.check;
    c.ran = true;
    c.tiles = r->tiles;
    c.worst = r->worst;
    c.look = r->look;
    c.lookThresholds = r->lookThresholds;
    if (!r->tiles) c.failure = describeFailure(*r);
    emit(BuildEvent::Type::Progress, s, "check", 1.0);
}

void MaterialBuild::Impl::makeStep(Step& s, std::atomic<bool>& stop) {
    s.report.status = s.needBuild ? AssetStatus::Rebuilt : AssetStatus::UpToDate;
    if (stop) return;
    if (!s.needBuild) {
        emit(BuildEvent::Type::Done, s, "", 1.0);
        if (!s.needCheck) return;
        std::lock_guard<std::mutex> lock(mutex);
        state[s.report.output].checked = s.checkKey;  // an up-to-date output newly checked
        return;
    }
    guarded(s, [&] {
        const auto start = std::chrono::steady_clock::now();
        const std::string output = (folder / s.report.output).string();
        auto hash = restoreStep(s, output);
        if (!hash) return void(s.error = inAsset(hash.error(), s));
        if (hash->empty()) {
            emit(BuildEvent::Type::Start, s, "load", 0.0);
            Status made = s.make(output, threads, [&](std::string_view stage, double f) {
                emit(BuildEvent::Type::Progress, s, stage, f);
            });
            if (!made) return void(s.error = inAsset(made.error(), s));
            hash = hashFile(output);
            if (!hash) return void(s.error = hash.error());
            storeStep(s, output, *hash);
        }
        s.report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!options.only.empty()) return;  // the plan's last action records every output
        // A restored output is recorded exactly as a baked one (same key, hash and check), so a later build
        // without the cache finds it up to date.
        std::lock_guard<std::mutex> lock(mutex);
        state[s.report.output] = {s.report.key, *hash, s.mustTile ? s.checkKey : ""};
        if (Status saved = writeTextFile(statePath, buildStateText(state)); !saved) s.error = saved.error();
    });
    if (s.error) stop = true;
    else emit(BuildEvent::Type::Done, s, "", 1.0);
}

// With a cache: the output restored from it, and the hash of its bytes; empty when it must be baked (no
// entry, or one not trusted: why goes into the report). A forced build bakes (and stores) every output:
// whoever forces a rebuild doubts what is there, the cache included.
Result<std::string> MaterialBuild::Impl::restoreStep(Step& s, const std::string& output) {
    if (!options.sharedCache || options.force) return std::string();
    emit(BuildEvent::Type::Start, s, "restore", 0.0);
    s.report.cache.looked = true;
    auto found = options.sharedCache->restore(s.report.key, s.report.output, output);
    if (!found) return found.error();
    s.report.cache.hit = found->hit;
    s.report.cache.rejected = found->rejected;
    s.report.cache.unavailable = found->unavailable;
    if (!found->hit) return std::string();
    s.report.status = AssetStatus::Restored;
    return found->hash;
}

// With a cache: the output just baked stored in it. A failure is reported, not fatal: the output is made.
void MaterialBuild::Impl::storeStep(Step& s, const std::string& output, const std::string& hash) {
    if (!options.sharedCache) return;
    const CacheStore stored = options.sharedCache->store(s.report.key, s.report.output, output, hash);
    s.report.cache.stored = stored.stored;
    s.report.cache.storeUnavailable = stored.unavailable;
    s.report.cache.storeFailed = stored.failed;
}

// The plan's last action: every output, made by the actions before it, recorded as a build that made
// it would (key, hash, and the check its action ran).
Status MaterialBuild::Impl::recordMadeOutputs() {
    for (const Step& s : steps) {
        const std::string output = (folder / s.report.output).string();
        std::error_code ec;
        if (!fs::is_regular_file(output, ec))
            return badInput(output, "is not there: the plan's action that makes it has not run",
                            "run the whole plan (ninja -f PLAN), not its last action alone");
        auto hash = hashFile(output);
        if (!hash) return hash.error();
        state[s.report.output] = {s.report.key, *hash, s.mustTile ? s.checkKey : ""};
    }
    return Done{};
}

Status MaterialBuild::Impl::run() {
    if (ran || options.checkOnly || !report.checkFailures.empty())
        return Error{ErrorKind::Internal, m.path, "this build cannot run: it ran already, is check-only or failed its checks",
                     "please report this"};
    ran = true;
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec || !fs::is_directory(folder, ec))
        return cannotWrite(options.outputDir, "cannot be created as a folder", "choose another output folder");
    std::set<fs::path> folders{folder};
    for (const Step& s : steps) {
        const fs::path parent = (folder / s.report.output).parent_path();
        fs::create_directories(parent, ec);
        if (ec) return cannotWrite(parent.string(), "cannot be created as a folder", "check the permissions");
        folders.insert(parent);
    }
    for (const fs::path& f : folders) report.staleTemporariesRemoved += removeStaleTemporaryFiles(f.string());

    // 3. Make what changed. The state is saved after every output, so a killed build redoes only
    // what it had not finished. First it forgets every output about to be replaced: between an output's
    // rename and the next save, a kill would otherwise leave the state vouching for bytes no longer there.
    if (options.only.empty()) {
        bool forgot = false;
        for (const Step& s : steps)
            if (s.needBuild) forgot |= state.erase(s.report.output) > 0;
        if (forgot)
            if (Status saved = writeTextFile(statePath, buildStateText(state)); !saved) return saved.error();
    }
    std::atomic<bool> stop{false};
    forEachParallel(steps.size(), jobs, [&](size_t i) { makeStep(steps[i], stop); });
    // Synthesised maps' intermediates are gone once packed; what steps shared (a foam loop) and their
    // folder go too (the folder only when empty), only now, when no step can be reading or writing them:
    // in a plan, by the last action.
    const bool oneOutput = !options.only.empty() && options.only != kMaterialFile;
    if (!oneOutput) {
        for (const Step& s : steps)
            for (const std::string& shared : s.intermediates) fs::remove(folder / shared, ec);
        for (const fs::path& f : folders) fs::remove(f / kSynthFolder, ec);
    }
    if (auto e = firstError()) return *e;
    report.assets.clear();
    for (const Step& s : steps) report.assets.push_back(s.report);
    if (oneOutput) return Done{};

    // 4. Outputs the manifest no longer names are forgotten (their files are left alone), then the
    // state and material.json, each rewritten only when its bytes change.
    std::set<std::string> current;
    for (const Step& s : steps) current.insert(s.report.output);
    for (auto it = state.begin(); it != state.end();) it = current.count(it->first) ? std::next(it) : state.erase(it);
    // A plan's last action writes both whatever they hold: the executor compares their times with the outputs'.
    const bool always = options.only == kMaterialFile;
    const std::string stateNow = buildStateText(state);
    if (always || readText(statePath) != stateNow)
        if (Status s = writeTextFile(statePath, stateNow); !s) return s.error();
    auto description = describeMaterial(m, options.outputDir, options.version);
    if (!description) return description.error();
    const std::string materialPath = (folder / kMaterialFile).string();
    const std::string json = materialJson(*description);
    if (always || readText(materialPath) != json) {
        if (Status s = writeTextFile(materialPath, json); !s) return s.error();
        report.materialWritten = true;
    }
    return Done{};
}

MaterialBuild::MaterialBuild(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
MaterialBuild::MaterialBuild(MaterialBuild&&) noexcept = default;
MaterialBuild& MaterialBuild::operator=(MaterialBuild&&) noexcept = default;
MaterialBuild::~MaterialBuild() = default;

Result<MaterialBuild> MaterialBuild::prepare(const Manifest& manifest, const BuildOptions& options) {
    auto impl = std::make_unique<Impl>();
    impl->m = manifest;
    impl->options = options;
    if (!options.checkOnly && options.cache.location && !options.sharedCache) {
        auto cache = SharedCache::open(options.cache);
        if (!cache) return cache.error();
        impl->options.sharedCache = *cache;
    }
    if (options.checkOnly) impl->options.sharedCache.reset();
    if (Status s = impl->prepare(); !s) return s.error();
    return MaterialBuild(std::move(impl));
}

const BuildReport& MaterialBuild::report() const { return impl_->report; }

bool MaterialBuild::runnable() const {
    return !impl_->ran && !impl_->options.checkOnly && impl_->report.checkFailures.empty();
}

Result<BuildReport> MaterialBuild::run() {
    if (Status s = impl_->run(); !s) return s.error();
    return impl_->report;
}

Result<BuildReport> buildMaterial(const Manifest& manifest, const BuildOptions& options) {
    auto build = MaterialBuild::prepare(manifest, options);
    if (!build) return build.error();
    if (!build->runnable()) return build->report();
    return build->run();
}

}  // namespace heightpack
