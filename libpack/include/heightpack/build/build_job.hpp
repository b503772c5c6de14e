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

#include "heightpack/build/check_job.hpp"
#include "heightpack/build/manifest.hpp"
#include "heightpack/build/material.hpp"
#include "heightpack/core/result.hpp"

namespace heightpack {

// The build's record of what it made, kept beside the outputs: for each output the key it was made
// with and the output's own hash. Deleting it rebuilds everything.
inline constexpr const char* kBuildStateFile = ".heightpack-build.json";
inline constexpr const char* kMaterialFile = "material.json";

enum class AssetStatus {
    UpToDate,  // its key matched and the output is the file this build made
    Rebuilt,   // written by this build
    Checked,   // --check-only: checked, nothing written
    Skipped,   // --check-only and no check asked for
};
const char* assetStatusName(AssetStatus status);

// The tileability verdict on one asset's source, if a check ran (or passed in an earlier build).
struct AssetCheck {
    bool ran = false;       // in this build
    bool earlier = false;   // not run: it passed in the build that made the output, with the same key
    bool tiles = true;
    LevelSeams worst;       // per edge pair, the highest scores over the judged levels
    std::string failure;    // what failed, for a person: edge, level, score
};

// One output of the material (a sequence gives one per frame).
struct AssetReport {
    std::string name;       // the asset's name in the manifest
    std::string kind;       // displacement, normals, fresnel, foam
    int frame = -1;         // frame of a sequence, else -1
    int line = 0;           // manifest line of the asset's table
    std::string input;      // source file; empty for the Fresnel ramp
    std::string inputHash;  // XXH3-128 of the source file's bytes, 32 hex digits
    std::string output;     // relative to the output folder
    std::string key;        // hash of everything the output depends on: input bytes, options, version
    AssetStatus status = AssetStatus::UpToDate;
    double seconds = 0.0;
    std::optional<AssetCheck> check;  // empty when the manifest does not ask for one
};

struct BuildReport {
    std::string manifest;
    std::string material;   // the material's name
    std::string outputDir;
    std::vector<AssetReport> assets;  // in manifest order
    bool materialWritten = false;     // material.json was (re)written
    int staleTemporariesRemoved = 0;  // files an earlier, killed build left behind
    std::vector<Error> checkFailures; // assets that must tile and do not: the build wrote nothing
    std::vector<std::string> dependencies;  // every file the build reads: the manifest and the sources
    int rebuilt() const;
    int upToDate() const;
};

// What the build tells its caller while it runs; calls are serialised.
struct BuildEvent {
    enum class Type { Start, Progress, Done } type;
    const AssetReport& asset;
    std::string_view stage;  // "hash", "check", "load", "mip", "write"
    double fraction = 0.0;
};

struct BuildOptions {
    std::string outputDir;
    int jobs = 1;             // assets made at once
    int threads = 0;          // threads per asset; 0 = the cores shared among the jobs
    bool checkOnly = false;   // validate and run the tileability checks; write nothing
    bool force = false;       // rebuild every output whatever its key
    std::string version;      // recorded in outputs and part of every key
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

// Whether path can be written once the folders above it that are missing are made: the nearest existing
// one is a writable folder, and path itself is not a folder or a read-only file. Creates nothing.
Status checkOutputPath(const std::filesystem::path& path);

// Writes text to path atomically (a temporary file beside it, renamed into place), after checking that
// path can be written; for the depfile and the stamp.
Status writeTextFile(const std::string& path, const std::string& text);

// A Make-style depfile: "target: dep dep ...", paths escaped for Make and Ninja.
std::string depfileText(const std::string& target, const std::vector<std::string>& dependencies);

}  // namespace heightpack
