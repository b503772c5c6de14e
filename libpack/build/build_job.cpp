#include "heightpack/build/build_job.hpp"

#include <unistd.h>
#include <xxhash.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "heightpack/io/read.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/build/fresnel_job.hpp"
#include "heightpack/io/info.hpp"
#include "heightpack/build/normal_job.hpp"
#include "heightpack/build/pack_job.hpp"
#include "heightpack/core/parallel.hpp"

namespace heightpack {

namespace fs = std::filesystem;

namespace {

constexpr int kStateFormat = 1;
using ProgressFn = std::function<void(std::string_view stage, double fraction)>;

std::string hex128(XXH128_hash_t h) {
    char text[33];
    std::snprintf(text, sizeof text, "%016llx%016llx", static_cast<unsigned long long>(h.high64),
                  static_cast<unsigned long long>(h.low64));
    return text;
}

std::string hashText(const std::string& text) { return hex128(XXH3_128bits(text.data(), text.size())); }

// XXH3-128 of a file's bytes, streamed.
Result<std::string> hashFile(const std::string& path) {
    if (Status s = checkReadable(path); !s) return s.error();  // a FIFO or device would hang the read
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!f) return badInput(path, "cannot be read", "check that it exists and is readable");
    std::unique_ptr<XXH3_state_t, XXH_errorcode (*)(XXH3_state_t*)> state(XXH3_createState(), XXH3_freeState);
    XXH3_128bits_reset(state.get());
    std::vector<char> buffer(1 << 20);
    size_t n = 0;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), f.get())) > 0) XXH3_128bits_update(state.get(), buffer.data(), n);
    if (std::ferror(f.get())) return badInput(path, "could not be read to the end", "check the disk");
    return hex128(XXH3_128bits_digest(state.get()));
}

std::string number(double v) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", v);
    return text;
}

}  // namespace

Status checkOutputPath(const fs::path& path) {
    std::error_code ec;
    if (fs::exists(fs::symlink_status(path, ec))) return checkWritable(path.string());
    // The nearest folder above it that exists must be a writable folder (from the absolute path, so a
    // relative output folder that does not exist yet is judged by the current folder).
    for (fs::path up = fs::absolute(path, ec).parent_path(); !ec && !up.empty(); up = up.parent_path()) {
        if (!fs::exists(up, ec)) {
            if (up == up.parent_path()) break;
            continue;
        }
        if (!fs::is_directory(up, ec))
            return cannotWrite(path.string(), up.string() + " is not a folder", "choose another output folder");
        if (::access(up.c_str(), W_OK) != 0)
            return cannotWrite(path.string(), "folder " + up.string() + " is not writable", "choose another output folder");
        return Done{};
    }
    return cannotWrite(path.string(), "has no existing folder above it", "choose another output folder");
}

namespace {

// Writes text to path atomically.
Status writeText(const std::string& path, const std::string& text) {
    if (Status s = checkWritable(path); !s) return s;
    TemporaryFile temp(path);
    {
        std::ofstream out(temp.path(), std::ios::binary);
        out << text;
        out.flush();
        if (!out) return cannotWrite(path, "could not be written", "check free disk space");
    }
    return temp.commit();
}

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    if (in) text << in.rdbuf();
    return text.str();
}

// One output file and how to make it.
struct Step {
    AssetReport report;
    bool mustTile = false;
    std::string optionsText;  // every option that shapes the output, one per line
    std::string checkText;    // every option that shapes the check
    CheckOptions check;
    std::function<Status(const std::string& output, int threads, const ProgressFn& progress)> make;
    // Worked out while building:
    std::string checkKey;
    bool needBuild = false, needCheck = false;
    std::optional<Error> error;
};

std::string settingsText(const MapSettings& s) {
    std::string text = "wrap=";
    text.append(wrapName(s.wrap)).append("\nfilter=").append(filterName(s.filter));
    text.append("\ncompression=").append(compressionName(s.compression));
    text.append("\nresize=").append(s.resize ? "1" : "0");
    text.append("\nchannel=").append(std::to_string(static_cast<int>(s.channel))).append("\n");
    return text;
}

LoadOptions loadOptions(const MapSettings& s) {
    LoadOptions load;
    load.channel = s.channel;
    load.silenceDecoderMessages = true;
    return load;
}

// The steps of one asset made from a file: one per frame, with the tileability check it asks for.
template <class MakeFn>
void addSourcedSteps(std::vector<Step>& steps, const SourcedAsset& a, const std::string& name, const char* kind,
                     const std::string& optionsText, double threshold, MakeFn make) {
    const int frames = static_cast<int>(a.frames.size());
    for (int f = 0; f < frames; ++f) {
        Step step;
        step.report.name = name;
        step.report.kind = kind;
        step.report.frame = frames > 1 ? f : -1;
        step.report.line = a.line;
        step.report.input = a.frames[f];
        step.report.output = frameFileName(a.output, f, frames);
        step.mustTile = a.mustTile;
        step.optionsText = std::string("kind=") + kind + "\nsource=" + fs::path(a.frames[f]).filename().string() + "\n" +
                           settingsText(a.settings) + optionsText;
        step.check.load = loadOptions(a.settings);
        step.check.mip.wrap = a.settings.wrap;
        step.check.mip.filter = a.settings.filter;
        step.check.threshold = threshold;
        step.checkText = "check\n" + settingsText(a.settings) + "threshold=" + number(threshold) + "\n";
        const std::string input = a.frames[f];
        step.make = [make, input](const std::string& output, int threads, const ProgressFn& progress) {
            return make(input, output, threads, progress);
        };
        steps.push_back(std::move(step));
    }
}

PackOptions packOptions(const MapSettings& s, const std::string& version) {
    PackOptions pack;
    pack.load = loadOptions(s);
    pack.mip.wrap = s.wrap;
    pack.mip.filter = s.filter;
    pack.resizeToPowerOfTwo = s.resize;
    pack.compression = s.compression;
    pack.version = version;
    return pack;
}

// The step's work for a packed (or plain) chain: pack with the threads and progress of the moment.
auto packMaker(const PackOptions& pack) {
    return [pack](const std::string& in, const std::string& out, int threads, const ProgressFn& progress) {
        PackOptions o = pack;
        o.mip.threads = threads;
        o.progress = progress;
        auto r = packHeightMap(in, out, o);
        return r ? Status(Done{}) : Status(r.error());
    };
}

std::vector<Step> planSteps(const Manifest& m, const std::string& version) {
    std::vector<Step> steps;
    for (const DisplacementAsset& d : m.displacement) {
        PackOptions pack = packOptions(d.settings, version);
        pack.scale = static_cast<float>(d.layer.heightScale);
        pack.offset = static_cast<float>(d.layer.heightOffset);
        const std::string text = "scale=" + number(pack.scale) + "\noffset=" + number(pack.offset) + "\n";
        addSourcedSteps(steps, d, d.layer.name, "displacement", text, m.threshold, packMaker(pack));
    }
    if (m.normals) {
        const NormalAsset& n = *m.normals;
        NormalJobOptions job;
        job.load = loadOptions(n.settings);
        job.normal.tileWidth = n.layer.tileSize;
        job.normal.heightRange = n.layer.heightRange;
        job.normal.kernel = n.kernel;
        job.normal.wrap = n.settings.wrap;
        job.normal.convention = n.layer.convention == "directx" ? NormalConvention::DirectX : NormalConvention::OpenGL;
        job.normal.alpha = n.layer.alpha == "height"     ? NormalAlpha::Height
                           : n.layer.alpha == "variance" ? NormalAlpha::Variance
                                                         : NormalAlpha::None;
        job.filter = n.settings.filter;
        job.resizeToPowerOfTwo = n.settings.resize;
        job.compression = n.settings.compression;
        job.version = version;
        const std::string text = "tileSize=" + number(n.layer.tileSize) + "\nheight=" + number(n.layer.heightRange) +
                                 "\nkernel=" + slopeKernelName(n.kernel) + "\nconvention=" + n.layer.convention +
                                 "\nalpha=" + n.layer.alpha + "\n";
        addSourcedSteps(steps, n, n.layer.name, "normals", text, m.threshold,
                        [job](const std::string& in, const std::string& out, int threads, const ProgressFn& progress) {
                            NormalJobOptions o = job;
                            o.normal.threads = threads;
                            o.progress = progress;
                            auto r = makeNormalMap(in, out, o);
                            return r ? Status(Done{}) : Status(r.error());
                        });
    }
    if (m.fresnel) {
        const FresnelAsset& f = *m.fresnel;
        Step step;
        step.report.name = f.layer.name;
        step.report.kind = "fresnel";
        step.report.line = f.line;
        step.report.output = f.output;
        const FresnelOptions& o = f.options;
        step.optionsText = "kind=fresnel\nior=" + number(o.ior) + "\nmodel=" + fresnelModelName(o.model) + "\nindex=" +
                           fresnelIndexName(o.index) + "\nsize=" + std::to_string(o.size) + "\n";
        for (double c : o.deep) step.optionsText += "deep=" + number(c) + "\n";
        for (double c : o.shallow) step.optionsText += "shallow=" + number(c) + "\n";
        step.make = [o, version](const std::string& out, int, const ProgressFn&) {
            return writeFresnelRamp(out, o, RampFormat::Exr, version);
        };
        steps.push_back(std::move(step));
    }
    if (m.foam && m.foam->texture) {
        const SourcedAsset& t = *m.foam->texture;
        PackOptions pack = packOptions(t.settings, version);
        pack.packed = false;
        addSourcedSteps(steps, t, m.foam->layer.name, "foam", "plain=1\n", m.threshold, packMaker(pack));
    }
    return steps;
}

// Runs body(i) for every i in [0, count) on up to jobs threads, in order of i as each thread frees up.
// Not parallelFor: that splits [0, count) into fixed contiguous chunks, and assets differ too much in
// cost for that (one 4096^2 map beside a 256-texel ramp); here a free thread takes the next asset.
void forEachParallel(size_t count, int jobs, const std::function<void(size_t)>& body) {
    std::atomic<size_t> next{0};
    auto worker = [&] {
        for (size_t i = next++; i < count; i = next++) body(i);
    };
    std::vector<std::thread> pool;
    const size_t extra = std::min<size_t>(count, static_cast<size_t>(std::max(1, jobs))) - (count > 0 ? 1 : 0);
    for (size_t k = 0; k < extra; ++k) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
}

// The first failing edge of a check, in words.
std::string describeFailure(const CheckReport& r) {
    if (r.failure) return describeSeamFailure(*r.failure, r.threshold);
    if (r.packing && !r.packing->consistent) return "its packing is inconsistent";
    return "it fails the check";
}

// The build state file: output -> key, output hash and the check key that passed.
struct StateEntry {
    std::string key, hash, checked;
};
using State = std::map<std::string, StateEntry>;

// A missing or damaged state file only means everything is rebuilt: anything not exactly as stateText
// writes it (not JSON, truncated, a field of another type, a number where a string belongs, another
// format) gives no state at all, never an error.
State loadState(const std::string& path) {
    const nlohmann::json doc = nlohmann::json::parse(readText(path), nullptr, false);
    if (doc.is_discarded() || !doc.is_object()) return {};
    const auto format = doc.find("format");
    const auto outputs = doc.find("outputs");
    if (format == doc.end() || !format->is_number_integer() || *format != kStateFormat || outputs == doc.end() ||
        !outputs->is_object())
        return {};
    State state;
    for (const auto& [output, entry] : outputs->items()) {
        if (!entry.is_object()) return {};
        StateEntry e;
        for (auto [key, field] : {std::pair{"key", &e.key}, std::pair{"hash", &e.hash}, std::pair{"checked", &e.checked}}) {
            const auto value = entry.find(key);
            if (value == entry.end() || !value->is_string()) return {};
            *field = value->get<std::string>();
        }
        state[output] = std::move(e);
    }
    return state;
}

std::string stateText(const State& state) {
    nlohmann::json outputs = nlohmann::json::object();
    for (const auto& [output, e] : state) outputs[output] = {{"key", e.key}, {"hash", e.hash}, {"checked", e.checked}};
    return nlohmann::json{{"format", kStateFormat}, {"outputs", outputs}}.dump(1) + "\n";
}

// A texture's description from its file's header.
Result<MaterialTexture> describeTexture(const std::string& folder, const std::string& output, int frames, double* loopPeriod) {
    const std::string first = (fs::path(folder) / frameFileName(output, 0, frames)).string();
    auto layout = readTextureLayout(first, true);
    if (!layout) return layout.error();
    MaterialTexture t;
    t.file = output;
    t.width = layout->levelSizes[0].first;
    t.height = layout->levelSizes[0].second;
    t.levels = static_cast<int>(layout->levelSizes.size());
    t.frames = frames;
    if (loopPeriod) {
        const std::string period = findAttribute(layout->attributes, "heightpack:loopPeriod");
        *loopPeriod = period.empty() ? 0.0 : std::stod(period);
    }
    return t;
}

Result<MaterialDescription> describeMaterial(const Manifest& m, const std::string& folder, const std::string& version) {
    MaterialDescription d;
    d.name = m.name;
    d.generator = "heightpack " + version;
    d.manifest = fs::path(m.path).filename().string();
    for (const DisplacementAsset& a : m.displacement) {
        DisplacementLayer layer = a.layer;
        auto t = describeTexture(folder, a.output, static_cast<int>(a.frames.size()), &layer.loopPeriod);
        if (!t) return t.error();
        layer.texture = *t;
        d.displacement.push_back(std::move(layer));
    }
    if (m.normals) {
        NormalLayer layer = m.normals->layer;
        auto t = describeTexture(folder, m.normals->output, static_cast<int>(m.normals->frames.size()), nullptr);
        if (!t) return t.error();
        layer.texture = *t;
        d.normals = std::move(layer);
    }
    if (m.fresnel) {
        FresnelLayer layer = m.fresnel->layer;
        auto t = describeTexture(folder, m.fresnel->output, 1, nullptr);
        if (!t) return t.error();
        layer.texture = *t;
        d.fresnel = std::move(layer);
    }
    if (m.foam) {
        FoamLayer layer = m.foam->layer;
        if (m.foam->texture) {
            auto t = describeTexture(folder, m.foam->texture->output, 1, nullptr);
            if (!t) return t.error();
            layer.texture = *t;
        }
        d.foam = std::move(layer);
    }
    return d;
}

}  // namespace

const char* assetStatusName(AssetStatus status) {
    switch (status) {
        case AssetStatus::UpToDate: return "up to date";
        case AssetStatus::Rebuilt: return "rebuilt";
        case AssetStatus::Checked: return "checked";
        case AssetStatus::Skipped: return "skipped";
    }
    return "?";
}

int BuildReport::rebuilt() const {
    return static_cast<int>(std::count_if(assets.begin(), assets.end(), [](const AssetReport& a) { return a.status == AssetStatus::Rebuilt; }));
}
int BuildReport::upToDate() const {
    return static_cast<int>(std::count_if(assets.begin(), assets.end(), [](const AssetReport& a) { return a.status == AssetStatus::UpToDate; }));
}

Status writeTextFile(const std::string& path, const std::string& text) { return writeText(path, text); }

std::string depfileText(const std::string& target, const std::vector<std::string>& dependencies) {
    auto escape = [](const std::string& path) {
        std::string out;
        for (char c : path) {
            if (c == ' ' || c == '#' || c == '\\') out += '\\';
            if (c == '$') out += '$';
            out += c;
        }
        return out;
    };
    std::string text = escape(target) + ":";
    for (const std::string& d : dependencies) text.append(" \\\n  ").append(escape(d));
    return text + "\n";
}

// Everything a build holds between preparing (hashes, checks) and running (writing).
struct MaterialBuild::Impl {
    Manifest m;
    BuildOptions options;
    std::vector<Step> steps;
    fs::path folder;
    std::string statePath;
    State state;
    BuildReport report;
    int jobs = 1, threads = 1;
    bool ran = false;
    std::mutex mutex;  // guards state, events and the steps' shared fields

    void emit(BuildEvent::Type type, const Step& s, std::string_view stage, double fraction) {
        if (!options.onEvent) return;
        std::lock_guard<std::mutex> lock(mutex);
        options.onEvent({type, s.report, stage, fraction});
    }
    static void guarded(Step& s, const std::function<void()>& body) {
        try {
            body();
        } catch (const std::bad_alloc&) {
            s.error = Error{ErrorKind::Internal, s.report.input, "out of memory", "use fewer --jobs or --threads"};
        } catch (const std::exception& e) {
            s.error = Error{ErrorKind::Internal, s.report.input, std::string("internal error: ") + e.what(), "please report this"};
        }
    }
    // A source's error names the source file; the hint says which asset of which manifest read it.
    Error inAsset(Error e, const Step& s) const {
        e.hint += (e.hint.empty() ? "" : "; ") + std::string("asset '") + s.report.name + "' of " + m.path + ":" +
                  std::to_string(s.report.line);
        return e;
    }
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
};

Status MaterialBuild::Impl::prepare() {
    report.manifest = m.path;
    report.material = m.name;
    report.outputDir = options.outputDir;
    steps = planSteps(m, options.version);

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
        for (const Step& s : steps) outputs.push_back(folder / s.report.output);
        for (const fs::path& p : outputs)
            if (Status ok = checkOutputPath(p); !ok) return ok.error();
        state = loadState(statePath);
    }
    jobs = std::max(1, options.jobs);
    threads = options.threads > 0 ? options.threads : std::max(1, resolveThreadCount(0) / jobs);

    // 1. What changed: hash every input and every recorded output.
    forEachParallel(steps.size(), jobs, [&](size_t i) { guarded(steps[i], [&] { hashStep(steps[i]); }); });
    if (auto e = firstError()) return *e;

    // 2. Tileability, before anything is written: a map that must tile and does not stops the build.
    forEachParallel(steps.size(), jobs, [&](size_t i) {
        Step& s = steps[i];
        if (s.mustTile) s.report.check = AssetCheck{false, !s.needCheck, true, {}, {}};
        if (s.needCheck) guarded(s, [&] { checkStep(s); });
    });
    if (auto e = firstError()) return *e;
    for (const Step& s : steps) {
        if (!s.report.check || s.report.check->tiles) continue;
        std::string what = s.report.kind + " '" + s.report.name + "'";
        if (s.report.frame >= 0) what += " frame " + std::to_string(s.report.frame);
        what += " (" + s.report.input + ") does not tile: " + s.report.check->failure;
        // The fix that works: tile judges with the same measure and threshold, on the chain this filter makes,
        // and a float EXR holds whatever heights the fix needs.
        const std::filesystem::path source(s.report.input);
        std::string fix = "heightpack tile " + s.report.input + " -o " +
                          (source.parent_path() / (source.stem().string() + "_tiled.exr")).string();
        if (s.check.mip.filter != Filter::Kaiser) fix += std::string(" --filter ") + filterName(s.check.mip.filter);
        if (s.check.threshold != kDefaultSeamThreshold) {
            char threshold[32];
            std::snprintf(threshold, sizeof threshold, " --threshold %g", s.check.threshold);
            fix += threshold;
        }
        report.checkFailures.push_back(badInput(m.path + ":" + std::to_string(s.report.line), what,
                                                "make it tile with '" + fix + "' and use that as the source, or set "
                                                "tileable = false if it is not meant to tile"));
    }
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
    s.report.key = hashText("heightpack " + options.version + "\n" + s.optionsText + "input=" + inputHash + "\n");
    s.checkKey = hashText("heightpack " + options.version + "\n" + s.checkText + "input=" + inputHash + "\n");
    if (options.checkOnly) {
        s.needCheck = s.mustTile;
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
        emit(BuildEvent::Type::Start, s, "load", 0.0);
        const auto start = std::chrono::steady_clock::now();
        const std::string output = (folder / s.report.output).string();
        Status made = s.make(output, threads, [&](std::string_view stage, double f) {
            emit(BuildEvent::Type::Progress, s, stage, f);
        });
        if (!made) return void(s.error = inAsset(made.error(), s));
        auto hash = hashFile(output);
        if (!hash) return void(s.error = hash.error());
        s.report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::lock_guard<std::mutex> lock(mutex);
        state[s.report.output] = {s.report.key, *hash, s.mustTile ? s.checkKey : ""};
        if (Status saved = writeText(statePath, stateText(state)); !saved) s.error = saved.error();
    });
    if (s.error) stop = true;
    else emit(BuildEvent::Type::Done, s, "", 1.0);
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
    // what it had not finished.
    std::atomic<bool> stop{false};
    forEachParallel(steps.size(), jobs, [&](size_t i) { makeStep(steps[i], stop); });
    if (auto e = firstError()) return *e;
    report.assets.clear();
    for (const Step& s : steps) report.assets.push_back(s.report);

    // 4. Outputs the manifest no longer names are forgotten (their files are left alone), then the
    // state and material.json, each rewritten only when its bytes change.
    std::set<std::string> current;
    for (const Step& s : steps) current.insert(s.report.output);
    for (auto it = state.begin(); it != state.end();) it = current.count(it->first) ? std::next(it) : state.erase(it);
    const std::string stateNow = stateText(state);
    if (readText(statePath) != stateNow)
        if (Status s = writeText(statePath, stateNow); !s) return s.error();
    auto description = describeMaterial(m, options.outputDir, options.version);
    if (!description) return description.error();
    const std::string materialPath = (folder / kMaterialFile).string();
    const std::string json = materialJson(*description);
    if (readText(materialPath) != json) {
        if (Status s = writeText(materialPath, json); !s) return s.error();
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
