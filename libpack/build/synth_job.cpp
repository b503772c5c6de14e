#include "heightpack/build/synth_job.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "heightpack/io/files.hpp"
#include "heightpack/io/image_write.hpp"

namespace heightpack {

Result<SynthReport> synthesise(const std::string& output, const SynthOptions& options) {
    for (int f = 0; f < options.frames; ++f)
        if (Status s = checkWritable(frameFileName(output, f, options.frames)); !s) return s.error();
    const std::string ext = lowerExtension(output);
    const bool metres = ext == ".exr";

    const Ocean ocean(options.spectrum);
    const double period = options.spectrum.loopPeriod;
    auto progress = [&](std::string_view stage, double f) {
        if (options.progress) options.progress(stage, f);
    };
    std::vector<Image> frames;
    for (int f = 0; f < options.frames; ++f) {
        progress("synth", double(f) / options.frames);
        frames.push_back(ocean.heights(options.frames > 1 ? f * period / options.frames : 0.0));
    }
    progress("synth", 1.0);

    SynthReport report;
    report.expectedSignificantWaveHeight = 4.0 * std::sqrt(ocean.resolvedVariance());
    double sum = 0, sq = 0;
    for (float v : frames[0].pixels) sum += v, sq += double(v) * v;
    const double n = double(frames[0].pixels.size());
    report.significantWaveHeight = 4.0 * std::sqrt(std::max(0.0, sq / n - (sum / n) * (sum / n)));
    report.minHeight = report.maxHeight = frames[0].pixels[0];
    for (const Image& frame : frames) {
        const auto [lo, hi] = std::minmax_element(frame.pixels.begin(), frame.pixels.end());
        report.minHeight = std::min(report.minHeight, double(*lo));
        report.maxHeight = std::max(report.maxHeight, double(*hi));
    }
    // Integer files: one mapping onto [0,1] for the whole sequence, so frames compare.
    const double offset = metres ? 0.0 : report.minHeight;
    const double scale = metres ? 1.0 : std::max(report.maxHeight - report.minHeight, 1e-9);

    const SpectrumOptions& s = options.spectrum;
    char wind[64];
    std::snprintf(wind, sizeof wind, "%.4g m/s from %.4g deg", s.windSpeed, s.windDirection);
    for (int f = 0; f < options.frames; ++f) {
        progress("write", double(f) / options.frames);
        Image image = frames[f];
        if (!metres)
            for (float& v : image.pixels) v = static_cast<float>((v - offset) / scale);
        FlatImageOptions flat;
        if (options.displacement && metres) {
            const Image d = ocean.displacement(options.frames > 1 ? f * period / options.frames : 0.0);
            Image withD(image.width, image.height, 3);
            for (size_t i = 0; i < image.texelCount(); ++i) {
                withD.pixels[3 * i] = image.pixels[i];
                withD.pixels[3 * i + 1] = d.pixels[2 * i];
                withD.pixels[3 * i + 2] = d.pixels[2 * i + 1];
            }
            image = std::move(withD);
            flat.channelNames = {"Y", "Dx", "Dy"};
        }
        flat.bits = metres ? 32 : 16;
        flat.attributes = {
            attribute(attr::layout, "synthesised"),
            attribute(attr::spectrum, s.model),
            attribute(attr::wind, std::string(wind)),
            attribute(attr::tileWidth, static_cast<float>(s.tileSize)),
            attribute(attr::seed, std::to_string(s.seed)),
            attribute(attr::heightScale, static_cast<float>(scale)),
            attribute(attr::heightOffset, static_cast<float>(offset)),
            attribute(attr::version, options.version),
        };
        if (s.model == SpectrumModel::Jonswap) flat.attributes.push_back(attribute(attr::fetch, static_cast<float>(s.fetch)));
        if (options.frames > 1) {
            flat.attributes.push_back(attribute(attr::frame, std::to_string(f) + "/" + std::to_string(options.frames)));
            flat.attributes.push_back(attribute(attr::loopPeriod, static_cast<float>(period)));
            flat.attributes.push_back(attribute(attr::time, static_cast<float>(f * period / options.frames)));
        }
        const std::string path = frameFileName(output, f, options.frames);
        if (Status w = writeFlatImage(path, image, flat); !w) return w.error();
        report.outputs.push_back(path);
    }
    return report;
}

}  // namespace heightpack
