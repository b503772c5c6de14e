// The whole `build` operation: every texture of a material manifest, rebuilt only where an input's
// bytes or an option that affects it changed, checked for tiling first, written atomically, described
// in material.json.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "heightpack/bake/build/build_report.hpp"
#include "heightpack/bake/manifest.hpp"
#include "heightpack/bake/material.hpp"
#include "heightpack/bake/build/cache_session.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/version.hpp"

namespace heightpack {

struct BuildOptions {
    std::string outputDir;
    int jobs = 1;             // assets made at once
    int threads = 0;          // threads per asset; 0 = the cores shared among the jobs
    bool checkOnly = false;   // validate and run the tileability checks; write nothing
    bool force = false;       // rebuild every output whatever its key (baked, not restored from a cache)
    // The shared cache (cache_session.hpp): an output to make is first looked for there (by its key), and
    // what is baked is stored there (unless read-only). Not used by a check-only build. sharedCache is the
    // cache opened from `cache`, shared by every material of a build (buildMaterials opens it; prepare
    // opens one of its own when it is empty and `cache` names one).
    CacheOptions cache;
    std::shared_ptr<SharedCache> sharedCache;
    // One action of a plan (action_plan.hpp), run side by side with the others by an executor that
    // decided it is due: an output's name (as the plan and the state name it) makes that output alone,
    // always (restored from the cache where it holds it), and writes neither the build state nor
    // material.json; kMaterialFile takes every output as made (each must be there), records them all
    // in the state and writes it and material.json, always (the executor judges by their times).
    std::string only;
    std::string version = kVersion;  // this library's (heightpack/version.hpp); recorded in outputs, part of cache keys
    std::function<void(const BuildEvent&)> onEvent;
};

// A build in two steps, so a caller with several materials can check them all before writing any.
class MaterialBuild {
public:
    // Plans the outputs, hashes every source and recorded output, and runs the tileability checks that
    // are due. Writes nothing. A failing check is not an Error: report().checkFailures lists it.
    static Result<MaterialBuild> prepare(const Manifest& manifest, const BuildOptions& options);

    // After prepare: every asset (with its check), the dependencies, the check failures. After run:
    // the statuses and times of what was made, and whether material.json was written.
    const BuildReport& report() const;
    // Whether run() may go ahead: not check-only, every check passed, not run yet.
    bool runnable() const;
    // Makes what changed, then the build state and material.json.
    Result<BuildReport> run();

    MaterialBuild(MaterialBuild&&) noexcept;
    MaterialBuild& operator=(MaterialBuild&&) noexcept;
    ~MaterialBuild();

private:
    struct Impl;
    explicit MaterialBuild(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

// prepare() and, when runnable, run(): the whole build of one material. Fails (Error) on an unreadable
// source, an unwritable output folder and the like; a failing tileability check is not an Error but a
// report with checkFailures and nothing written.
Result<BuildReport> buildMaterial(const Manifest& manifest, const BuildOptions& options);

}  // namespace heightpack
