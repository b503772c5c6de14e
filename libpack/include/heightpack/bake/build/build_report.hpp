// What a build reports: per output, its status, key and check; per material, the outputs, the check
// failures and the files it read. Shared by the build's rooms (plan, state, job) and its callers.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "heightpack/core/names.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/core/tile/look.hpp"
#include "heightpack/core/tile/tileable.hpp"

namespace heightpack {

// The build's record of what it made, kept beside the outputs: for each output the key it was made
// with and the output's own hash. Deleting it rebuilds everything.
inline constexpr const char* kBuildStateFile = ".heightpack-build.json";
inline constexpr const char* kMaterialFile = "material.json";

enum class AssetStatus {
    UpToDate,  // its key matched and the output is the file this build made
    Rebuilt,   // written by this build
    Restored,  // written by this build from the shared cache: another build had made it with the same key
    Checked,   // --check-only: checked, nothing written
    Skipped,   // --check-only and no check asked for
};
template <>
struct NameTable<AssetStatus> {
    static constexpr EnumName<AssetStatus> entries[] = {
        {AssetStatus::UpToDate, "up to date", "its key matched and the output is the file this build made"},
        {AssetStatus::Rebuilt, "rebuilt", "written by this build"},
        {AssetStatus::Restored, "restored from cache", "copied from the shared cache, where another build stored it"},
        {AssetStatus::Checked, "checked", "checked, nothing written"},
        {AssetStatus::Skipped, "skipped", "no check asked for"},
    };
};
inline const char* assetStatusName(AssetStatus status) { return nameOf(status); }

// The tileability verdict on one asset's source, if a check ran (or passed in an earlier build).
struct AssetCheck {
    bool ran = false;       // in this build
    bool earlier = false;   // not run: it passed in the build that made the output, with the same key
    bool tiles = true;
    LevelSeams worst;       // per edge pair, the highest scores over the judged levels
    std::string failure;    // what failed, for a person: edge, level, score
    TileLook look;          // level 0's frame, blobs and echo (a warning when over: the build still passes)
    LookThresholds lookThresholds;
};

// What the shared cache did for one output: only with a cache, and only for an output that had to be made.
struct AssetCacheUse {
    bool looked = false;      // the output had to be made, and the cache was asked for it first (not when forced)
    bool hit = false;         // restored from the cache (status Restored): nothing baked
    bool stored = false;      // baked, then stored in the cache
    std::string rejected;     // the cache held an entry that failed verification: why (then baked and stored)
    std::string storeFailed;  // baked but not stored: why (the build goes on; the cache only saves time)
    bool unavailable = false;       // the cache could not be asked (down or refusing: its outage says why)
    bool storeUnavailable = false;  // baked, and not stored: the cache was down or refused to store
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
    AssetCacheUse cache;
};

// What the shared cache did for a build: how many outputs it restored (hits), how many it answered
// without a sound entry for (misses, the rejected among them), how many of the baked it stored, and for
// how many it failed (errors: it could not be asked or written, or an entry could not be stored).
struct CacheCounts {
    int hits = 0, misses = 0, stored = 0, rejected = 0, errors = 0;
    void add(const AssetCacheUse& use);
    CacheCounts& operator+=(const CacheCounts& other);
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
    int restored() const;
    CacheCounts cache() const;
};

// What the build tells its caller while it runs; calls are serialised.
struct BuildEvent {
    enum class Type { Start, Progress, Done } type;
    const AssetReport& asset;
    std::string_view stage;  // "hash", "check", "load", "mip", "write"
    double fraction = 0.0;
};

}  // namespace heightpack
