#include "foam_loop.hpp"

#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>

#include "heightpack/bake/build/build_state.hpp"
#include "heightpack/bake/build/cache_key.hpp"
#include "heightpack/core/sea/foam.hpp"
#include "heightpack/core/parallel.hpp"
#include "heightpack/core/sea/spectrum.hpp"
#include "heightpack/io/files.hpp"

namespace heightpack::detail {

namespace {

namespace fs = std::filesystem;

// The file: a text header, one "name=value" a line and an empty line after, then every frame's coverage,
// size x size floats in this machine's byte order (the file never leaves the build that wrote it):
//   heightpack-foam-loop 1 / key=KEY / frames=F / size=N / frame0=HASH ... / (empty) / frame 0's floats ...
constexpr const char* kMagic = "heightpack-foam-loop 1";

std::string bytesOf(const float* values, size_t count) {
    return std::string(reinterpret_cast<const char*>(values), count * sizeof(float));
}

// Frame f of the loop's file, when the file is this loop's and the frame's bytes are the ones it records.
std::optional<Image> readFrame(const fs::path& path, const FoamLoop& loop, int frame) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    const int size = loop.sea.spectrum.size, frames = loop.sea.frames;
    const std::vector<std::string> expected = {kMagic, "key=" + loop.key, "frames=" + std::to_string(frames),
                                               "size=" + std::to_string(size)};
    std::string line, hash;
    for (const std::string& want : expected)
        if (!std::getline(in, line) || line != want) return std::nullopt;
    for (int f = 0; f < frames; ++f) {
        if (!std::getline(in, line) || line.rfind("frame" + std::to_string(f) + "=", 0) != 0) return std::nullopt;
        if (f == frame) hash = line.substr(line.find('=') + 1);
    }
    if (!std::getline(in, line) || !line.empty()) return std::nullopt;
    Image image(size, size, 1);
    const std::streamsize bytes = std::streamsize(image.pixels.size() * sizeof(float));
    in.seekg(in.tellg() + std::streamoff(frame) * bytes);
    if (!in.read(reinterpret_cast<char*>(image.pixels.data()), bytes)) return std::nullopt;
    if (hashText(bytesOf(image.pixels.data(), image.pixels.size())) != hash) return std::nullopt;
    return image;
}

// Every frame's coverage, as synthesise() works it out: each frame's Jacobian at the loop's choppiness,
// the densities over the loop (or frozen, for one frame), 1 - exp(-density).
std::vector<std::vector<float>> computeLoop(const SynthSource& sea, int threads, const ProgressFn& progress) {
    std::vector<Image> jacobians;
    {
        const Ocean ocean(sea.spectrum, OceanOptions{threads, sea.frames > 1});
        for (int f = 0; f < sea.frames; ++f) {
            progress("foam", 0.9 * f / sea.frames);
            jacobians.push_back(ocean.fields(synthFrameTime(sea, f), {false, false, true}, sea.choppiness, threads).jacobian);
        }
    }
    std::vector<std::vector<float>> coverage = loopingFoamDensity(jacobians, sea.spectrum.loopPeriod, sea.foamOptions);
    jacobians.clear();
    parallelFor(sea.frames, threads, [&](int f0, int f1) {
        for (int f = f0; f < f1; ++f)
            for (float& v : coverage[f]) v = foamCoverageOf(v);
    });
    progress("foam", 1.0);
    return coverage;
}

Status writeLoop(const fs::path& path, const FoamLoop& loop, const std::vector<std::vector<float>>& coverage) {
    std::ostringstream header;
    header << kMagic << "\nkey=" << loop.key << "\nframes=" << loop.sea.frames << "\nsize=" << loop.sea.spectrum.size << "\n";
    for (size_t f = 0; f < coverage.size(); ++f)
        header << "frame" << f << "=" << hashText(bytesOf(coverage[f].data(), coverage[f].size())) << "\n";
    header << "\n";
    TemporaryFile temp(path.string());
    {
        std::ofstream out(temp.path(), std::ios::binary);
        out << header.str();
        for (const std::vector<float>& frame : coverage)
            out.write(reinterpret_cast<const char*>(frame.data()), std::streamsize(frame.size() * sizeof(float)));
        out.flush();
        if (!out) return cannotWrite(path.string(), "could not be written", "check free disk space");
    }
    return temp.commit();
}

}  // namespace

FoamLoop foamLoopOf(const SynthSource& sea, const std::string& name, const std::string& version) {
    FoamLoop loop{sea, (fs::path(kSynthFolder) / (name + ".foam")).string(), ""};
    const std::string text = "kind=foamLoop\nframes=" + std::to_string(sea.frames) + "\nchoppiness=" + number(sea.choppiness) +
                             "\n" + keyText(sea.spectrum, "synth.") + keyText(sea.foamOptions, "foam.");
    loop.key = cacheKey(version, text, "");
    return loop;
}

Result<Image> foamLoopFrame(const FoamLoop& loop, const fs::path& folder, int frame, int threads, const ProgressFn& progress) {
    const fs::path path = folder / loop.file;
    if (auto made = readFrame(path, loop, frame)) return std::move(*made);
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) return cannotWrite(path.parent_path().string(), "cannot be created as a folder", "check the permissions");
    const FileLock lock(path.string() + ".lock");
    if (auto made = readFrame(path, loop, frame)) return std::move(*made);  // made while this step waited
    std::vector<std::vector<float>> coverage = computeLoop(loop.sea, threads, progress);
    if (Status written = writeLoop(path, loop, coverage); !written) return written.error();
    Image image(loop.sea.spectrum.size, loop.sea.spectrum.size, 1);
    image.pixels = std::move(coverage[frame]);
    return image;
}

Status writeFoamLoop(const FoamLoop& loop, const fs::path& path, int threads, const ProgressFn& progress) {
    return writeLoop(path, loop, computeLoop(loop.sea, threads, progress));
}

std::vector<std::string> foamLoopFiles(const FoamLoop& loop) { return {loop.file, loop.file + ".lock"}; }

}  // namespace heightpack::detail
