// Several materials built as one: every material is hashed and checked before any is written, so a map
// that must tile and does not, in any of them, stops the whole build with nothing written; then each is
// built, and a depfile listing every file read and a stamp are written atomically for a build system.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "heightpack/bake/build/build_job.hpp"
#include "heightpack/bake/build/cache_session.hpp"
#include "heightpack/bake/manifest.hpp"
#include "heightpack/core/result.hpp"

namespace heightpack {

struct MaterialsOptions {
    // Written only by a build that writes (not check-only) and whose checks all passed. Each must lie in
    // an existing folder, or in the output folder (whose folders the build makes).
    std::string depfile;  // a Make-style depfile: the manifests and every source they read
    std::string stamp;    // a file written after the build; the depfile's target (else OUTPUT/material.json)
    // Called from the calling thread, in order, so a caller can print between the stages:
    std::function<void(const BuildReport&)> onPrepared;  // a material hashed and checked, before the next is
    std::function<void(const BuildReport&)> onBuilding;  // a material about to be made
    std::function<void(const BuildReport&, double seconds)> onBuilt;  // a material made
};

struct MaterialsReport {
    bool checksPassed = true;               // no material has a check failure (then nothing was written)
    std::vector<BuildReport> materials;     // in the order given: after the build, else after the checks
    std::vector<std::string> dependencies;  // every material's, in order (the depfile's list)
    CacheTrim cacheTrim;                    // with a cache: what trimming it to its size after the build did
    std::vector<CacheOutage> cacheOutages;  // with a cache: why the build stopped using it, if it did
};

// The folder material m is built into when count materials are built to output: output itself for one,
// else output/NAME.
std::string materialOutputDir(const std::string& output, const Manifest& m, std::size_t count);

// Parses the manifests at paths, in order, stopping at the first that is bad; with more than one, two
// that name the same material are refused (each is built into OUTPUT/NAME). sources: see parseManifest.
Result<std::vector<Manifest>> parseManifests(const std::vector<std::string>& paths,
                                             SourceCheck sources = SourceCheck::MustExist);

// Builds the manifests: options.outputDir is the output folder (see materialOutputDir); options.onEvent
// sees every material's assets. Prepares every material (MaterialBuild::prepare), then, when not
// check-only and every check passed, judges the depfile and the stamp, runs every material and writes
// the depfile and the stamp; with a cache (options.cache), opens it first and trims it to its size
// last. A failing check is not an Error: checksPassed is false and nothing is
// written. Fails on the first Error of any stage (an unreadable source, an unwritable output).
Result<MaterialsReport> buildMaterials(const std::vector<Manifest>& manifests, const BuildOptions& options,
                                       const MaterialsOptions& materials = {});

}  // namespace heightpack
