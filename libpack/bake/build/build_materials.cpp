#include "heightpack/bake/build/build_materials.hpp"

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>

#include "heightpack/bake/build/cache_session.hpp"
#include "heightpack/bake/build/depfile.hpp"
#include "heightpack/io/files.hpp"

namespace heightpack {

namespace fs = std::filesystem;

namespace {

// Refuses m when an earlier manifest already named its material (names: material -> manifest path).
Status uniqueName(std::map<std::string, std::string>& names, const Manifest& m, std::size_t count) {
    const auto [it, fresh] = names.emplace(m.name, m.path);
    if (!fresh && count > 1)
        return badInput(m.path, "names its material '" + m.name + "', as " + it->second + " does",
                        "give each material its own name: each is built into OUTPUT/NAME");
    return Done{};
}

// Whether path lies in the output folder (or deeper), whose folders the build creates.
bool madeByBuild(const std::string& path, const std::string& output) {
    const fs::path rel = fs::absolute(path).lexically_normal().lexically_relative(fs::absolute(output).lexically_normal());
    return !rel.empty() && *rel.begin() != ".." && rel != ".";
}

// The depfile and the stamp are judged before any material is written, as the materials' own outputs
// are in prepare(): a build that cannot write them must not write anything.
Status checkBuildFiles(const MaterialsOptions& o, const std::string& output, const std::vector<MaterialBuild>& builds) {
    for (const std::string& path : {o.depfile, o.stamp}) {
        if (path.empty()) continue;
        // A missing folder is refused, unless the build makes it (the output folder or one in it).
        if (Status s = madeByBuild(path, output) ? checkOutputPath(path) : checkWritable(path); !s) return s;
        for (const MaterialBuild& b : builds)
            for (const std::string& source : b.report().dependencies)
                if (std::error_code ec; fs::equivalent(path, source, ec))
                    return cannotWrite(path, "is also a source the build reads (" + source + ")",
                                       "give the depfile and the stamp their own names");
    }
    return Done{};
}

// The depfile or the stamp, atomically, in its folder (made if the build makes it).
Status writeBuildFile(const std::string& path, const std::string& output, const std::string& text) {
    if (madeByBuild(path, output)) {
        std::error_code ec;
        fs::create_directories(fs::path(path).parent_path(), ec);
    }
    return writeTextFile(path, text);
}

}  // namespace

std::string materialOutputDir(const std::string& output, const Manifest& m, std::size_t count) {
    return count == 1 ? output : (fs::path(output) / m.name).string();
}

Result<std::vector<Manifest>> parseManifests(const std::vector<std::string>& paths, SourceCheck sources) {
    std::vector<Manifest> manifests;
    std::map<std::string, std::string> names;
    for (const std::string& path : paths) {
        auto m = parseManifest(path, sources);
        if (!m) return m.error();
        if (Status s = uniqueName(names, *m, paths.size()); !s) return s.error();
        manifests.push_back(std::move(*m));
    }
    return manifests;
}

Result<MaterialsReport> buildMaterials(const std::vector<Manifest>& manifests, const BuildOptions& options,
                                       const MaterialsOptions& materials) {
    std::map<std::string, std::string> names;
    for (const Manifest& m : manifests)
        if (Status s = uniqueName(names, m, manifests.size()); !s) return s.error();

    // The cache is judged before any work, as the output folders are.
    std::shared_ptr<SharedCache> cache = options.sharedCache;
    if (!options.checkOnly && options.cache.location && !cache) {
        auto opened = SharedCache::open(options.cache);
        if (!opened) return opened.error();
        cache = *opened;
    }

    // 1. Every material hashed and checked before any is written.
    MaterialsReport report;
    std::vector<MaterialBuild> builds;
    for (const Manifest& m : manifests) {
        BuildOptions one = options;
        one.sharedCache = cache;
        one.outputDir = materialOutputDir(options.outputDir, m, manifests.size());
        auto build = MaterialBuild::prepare(m, one);
        if (!build) return build.error();
        if (materials.onPrepared) materials.onPrepared(build->report());
        report.checksPassed = report.checksPassed && build->report().checkFailures.empty();
        builds.push_back(std::move(*build));
    }
    const bool writes = report.checksPassed && !options.checkOnly;
    if (writes)
        if (Status s = checkBuildFiles(materials, options.outputDir, builds); !s) return s.error();

    // 2. Every material made, when all passed.
    for (MaterialBuild& build : builds) {
        if (writes && build.runnable()) {
            if (materials.onBuilding) materials.onBuilding(build.report());
            const auto began = std::chrono::steady_clock::now();
            auto ran = build.run();
            if (!ran) return ran.error();
            if (materials.onBuilt)
                materials.onBuilt(*ran, std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count());
        }
        const BuildReport& r = build.report();
        report.dependencies.insert(report.dependencies.end(), r.dependencies.begin(), r.dependencies.end());
        report.materials.push_back(r);
    }

    // Least recently used entries beyond the cache's size go once every material has used it.
    if (writes && cache) report.cacheTrim = cache->trim();
    if (cache) report.cacheOutages = cache->outages();

    // 3. The depfile and the stamp, for a build system.
    if (writes) {
        if (!materials.depfile.empty()) {
            const std::string target =
                materials.stamp.empty() ? (fs::path(options.outputDir) / kMaterialFile).string() : materials.stamp;
            if (Status s = writeBuildFile(materials.depfile, options.outputDir, depfileText(target, report.dependencies)); !s)
                return s.error();
        }
        if (!materials.stamp.empty())
            if (Status s = writeBuildFile(materials.stamp, options.outputDir, "heightpack build stamp\n"); !s)
                return s.error();
    }
    return report;
}

}  // namespace heightpack
