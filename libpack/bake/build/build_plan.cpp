#include "build_plan.hpp"

#include <filesystem>
#include <optional>

#include "heightpack/bake/build/cache_key.hpp"
#include "heightpack/bake/fresnel_job.hpp"
#include "heightpack/bake/normal_job.hpp"
#include "heightpack/bake/pack_job.hpp"
#include "heightpack/core/sea/spectrum.hpp"
#include "heightpack/io/attributes.hpp"
#include "heightpack/io/shift_read.hpp"
#include "heightpack/io/foam_read.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/image_write.hpp"

#include "foam_loop.hpp"

namespace heightpack::detail {

namespace fs = std::filesystem;

namespace {

LoadOptions loadOptions(const MapSettings& s) {
    LoadOptions load;
    load.channel = s.channel;
    load.silenceDecoderMessages = true;
    return load;
}

// The steps of one asset made from a file: one per frame, with the tileability check it asks for.
// options are the job's options; make(options, input, output, threads, progress) runs the job.
template <class Options, class MakeFn>
void addSourcedSteps(std::vector<Step>& steps, const SourcedAsset& a, const std::string& name, const char* kind,
                     double threshold, const Options& options, MakeFn make) {
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
        // The source's file name is recorded in the output (heightpack:source), so it shapes it too.
        step.optionsText = std::string("kind=") + kind + "\nsource=" + fs::path(a.frames[f]).filename().string() +
                           "\n" + keyText(options, std::string(kind) + ".");
        step.check.load = loadOptions(a.settings);
        step.check.mip.wrap = a.settings.wrap;
        step.check.mip.filter = a.settings.filter;
        step.check.threshold = threshold;
        step.checkText = "check\n" + keyText(step.check, "check.");
        const std::string input = a.frames[f];
        step.make = [make, options, input](const std::string& output, int threads, const ProgressFn& progress) {
            return make(options, input, output, threads, progress);
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
    pack.storage = s.storage;
    pack.version = version;
    return pack;
}

// A packed (or plain) chain, with the threads and progress of the moment.
Status makePacked(PackOptions o, const std::string& in, const std::string& out, int threads, const ProgressFn& progress) {
    o.mip.threads = threads;
    o.progress = progress;
    auto r = packHeightMap(in, out, o);
    return r ? Status(Done{}) : Status(r.error());
}

Status makeNormals(NormalJobOptions o, const std::string& in, const std::string& out, int threads,
                   const ProgressFn& progress) {
    o.normal.threads = threads;
    o.progress = progress;
    auto r = makeNormalMap(in, out, o);
    return r ? Status(Done{}) : Status(r.error());
}

NormalJobOptions normalOptions(const NormalAsset& n, const std::string& version) {
    NormalJobOptions job;
    job.load = loadOptions(n.settings);
    job.normal.tileWidth = n.layer.tileSize;
    job.normal.heightRange = n.layer.heightRange;
    job.normal.kernel = n.kernel;
    job.normal.wrap = n.settings.wrap;
    job.normal.convention = n.layer.convention;
    job.normal.alpha = n.layer.alpha;
    job.filter = n.settings.filter;
    job.resizeToPowerOfTwo = n.settings.resize;
    job.storage = n.settings.storage;
    job.layout = n.layer.layout;
    job.version = version;
    return job;
}

// Frame f of a synthesised sea: the heights in metres at f * loop / frames, with pack.shift Dx, Dy
// (metres per unit of choppiness), and with a foam loop Dx, Dy and the frame's foam coverage, the channels
// `heightpack synth --shift` (--foam) writes, into the intermediate file (with the loop's timing,
// which the packed frame then carries), packed from there like any source, and the intermediate removed.
// Its name is fixed, not a temporary one, because the packed header records the source's name and the
// bytes must be the same on every run.
Status makeSynthesised(const SynthSource& sea, int frame, const std::string& intermediate, const PackOptions& pack,
                       const std::optional<FoamLoop>& foamLoop, const std::string& output, int threads,
                       const ProgressFn& progress) {
    const fs::path folder = fs::path(output).parent_path(), path = folder / intermediate;
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) return cannotWrite(path.parent_path().string(), "cannot be created as a folder", "check the permissions");
    // The loop first: the one step that computes it reports its progress before its own frame's.
    std::optional<Image> foam;
    if (foamLoop) {
        auto coverage = foamLoopFrame(*foamLoop, folder, frame, threads, progress);
        if (!coverage) return coverage.error();
        foam = std::move(*coverage);
    }
    progress("synth", 0.0);
    const double t = synthFrameTime(sea, frame);
    const bool withD = pack.shift || foam;  // synth's foam brings Dx, Dy with it
    const int channels = 1 + (withD ? 2 : 0) + (foam ? 1 : 0), size = sea.spectrum.size;
    // Y, Dx, Dy (, Foam) interleaved, the channels synth writes and pack --shift (--foam) reads.
    Image image(size, size, channels);
    float* first = image.pixels.data();
    SeaFieldTargets to;
    to.heights = {first, channels};
    if (withD) to.shiftX = {first + 1, channels}, to.shiftY = {first + 2, channels};
    Ocean(sea.spectrum, threads).fieldsInto(t, to, 1.0, threads);
    FlatImageOptions flat;
    if (withD) flat.channelNames = {"Y", layerName::dx, layerName::dy};
    if (foam) {
        for (size_t i = 0; i < image.texelCount(); ++i) image.pixels[i * channels + 3] = foam->pixels[i];
        flat.channelNames.push_back(layerName::foam);
    }
    flat.threads = threads;
    // The tile's size, as synth records it: the packed frame carries it (heights in metres, synthesised).
    flat.attributes = {attribute(attr::layout, attr::synthesised), attribute(attr::tileWidth, static_cast<float>(sea.spectrum.tileSize)),
                       attribute(attr::version, pack.version)};
    if (sea.frames > 1) {
        flat.attributes.push_back(attribute(attr::frame, std::to_string(frame) + "/" + std::to_string(sea.frames)));
        flat.attributes.push_back(attribute(attr::loopPeriod, static_cast<float>(sea.spectrum.loopPeriod)));
        flat.attributes.push_back(attribute(attr::time, static_cast<float>(t)));
    }
    Status made = writeFlatImage(path.string(), image, flat);
    if (made) made = makePacked(pack, path.string(), output, threads, progress);
    fs::remove(path, ec);  // an intermediate only: the key, not this file, says whether to rebuild
    return made;
}

// The steps of a synthesised displacement map: one per frame, each keyed on the spectrum, the frame and
// the packing, with no input file (so no input hash and no tileability check: it tiles by construction).
// With foam kept (pack.foam), every frame shares one foam loop, and its key has the foam's options and
// the choppiness the foam is worked out for.
void addSynthSteps(std::vector<Step>& steps, const DisplacementAsset& d, const PackOptions& pack) {
    const SynthSource sea = *d.synth;
    const int frames = static_cast<int>(d.frames.size());
    std::optional<FoamLoop> foamLoop;
    if (pack.foam) foamLoop = foamLoopOf(sea, d.layer.name, pack.version);
    for (int f = 0; f < frames; ++f) {
        Step step;
        step.report.name = d.layer.name;
        step.report.kind = "displacement";
        step.report.frame = frames > 1 ? f : -1;
        step.report.line = d.line;
        step.report.output = frameFileName(d.output, f, frames);
        step.mustTile = false;
        // The cascade's own band, tile size and seed are in its spectrum; its place among the others, a
        // line only with cascades (so every key made before them still matches). Dx, Dy are pack's line,
        // and so is foam; its options, lines only with it.
        const std::string cascade = sea.cascades > 1 ? "synth.cascade=" + std::to_string(sea.cascade) + "/" +
                                                           std::to_string(sea.cascades) + "\n"
                                                     : "";
        step.optionsText = "kind=displacement\nsynth.frame=" + std::to_string(f) + "/" + std::to_string(frames) +
                           "\n" + cascade + keyText(sea.spectrum, "synth.") + keyText(pack, "displacement.");
        if (foamLoop) {
            step.optionsText.append("synth.choppiness=").append(number(sea.choppiness)).append("\n");
            step.optionsText.append(keyText(sea.foamOptions, "synth.foam."));
            for (const std::string& file : foamLoopFiles(*foamLoop))  // beside the output, as its intermediates
                step.intermediates.push_back((fs::path(step.report.output).parent_path() / file).string());
        }
        const std::string intermediate = d.frames[f];
        step.make = [sea, f, intermediate, pack, foamLoop](const std::string& output, int threads, const ProgressFn& progress) {
            return makeSynthesised(sea, f, intermediate, pack, foamLoop, output, threads, progress);
        };
        steps.push_back(std::move(step));
    }
}

}  // namespace

std::vector<Step> planSteps(const Manifest& m, const std::string& version) {
    std::vector<Step> steps;
    for (const DisplacementAsset& d : m.displacement) {
        PackOptions pack = packOptions(d.settings, version);
        pack.scale = static_cast<float>(d.layer.heightScale);
        pack.offset = static_cast<float>(d.layer.heightOffset);
        pack.layout = d.layer.layout;
        // Dx, Dy (and foam) go wherever the output's container puts them: an EXR's further channels, a
        // KTX2's or DDS's further array layers.
        if (d.synth) {
            // shift = true synthesises Dx, Dy and keeps them as a file's would be kept (below).
            pack.shift = d.synth->shift && d.layer.choppiness > 0;
            // foam = true synthesises the loop's foam and keeps it as a file's would be (below).
            pack.foam = d.synth->foam;
            addSynthSteps(steps, d, pack);
        } else {
            // Dx, Dy ride along when the source has them (synth's shift), unless choppiness turns them
            // off. Judged from the header, so a painted map's key stays what it was.
            pack.shift = d.layer.choppiness > 0 && hasShift(d.frames.front());
            // Foam likewise, unless foam = false.
            pack.foam = d.keepFoam && hasFoam(d.frames.front());
            addSourcedSteps(steps, d, d.layer.name, "displacement", m.threshold, pack, makePacked);
        }
    }
    if (m.normals)
        addSourcedSteps(steps, *m.normals, m.normals->layer.name, "normals", m.threshold,
                        normalOptions(*m.normals, version), makeNormals);
    if (m.fresnel) {
        const FresnelAsset& f = *m.fresnel;
        Step step;
        step.report.name = f.layer.name;
        step.report.kind = "fresnel";
        step.report.line = f.line;
        step.report.output = f.output;
        const FresnelOptions& o = f.options;
        step.optionsText = "kind=fresnel\n" + keyText(o, "fresnel.");  // a mip-less ramp, in the output's container
        // A line only when not the default, so the key of every float ramp stays as it was.
        if (f.pixelType != PixelType::Float) step.optionsText += "fresnel.pixelType=" + std::to_string(int(f.pixelType)) + "\n";
        const PixelType type = f.pixelType;
        step.make = [o, version, type](const std::string& out, int, const ProgressFn&) {
            return writeFresnelRamp(out, o, RampFormat::Exr, version, type);
        };
        steps.push_back(std::move(step));
    }
    if (m.foam && m.foam->texture) {
        PackOptions pack = packOptions(m.foam->texture->settings, version);
        pack.layout = Layout::Plain;
        addSourcedSteps(steps, *m.foam->texture, m.foam->layer.name, "foam", m.threshold, pack, makePacked);
    }
    return steps;
}

std::vector<Step> planSharedSteps(const Manifest& m, const std::string& version) {
    std::vector<Step> steps;
    for (const DisplacementAsset& d : m.displacement) {
        if (!d.synth || !d.synth->foam) continue;
        const FoamLoop loop = foamLoopOf(*d.synth, d.layer.name, version);
        Step step;
        step.report.name = d.layer.name;
        step.report.kind = "foam loop";
        step.report.line = d.line;
        step.report.output = (fs::path(d.output).parent_path() / loop.file).string();
        step.optionsText = "kind=foamLoop\nloop=" + loop.key + "\n";
        step.make = [loop](const std::string& output, int threads, const ProgressFn& progress) {
            return writeFoamLoop(loop, output, threads, progress);
        };
        steps.push_back(std::move(step));
    }
    return steps;
}

}  // namespace heightpack::detail
