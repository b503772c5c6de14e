#include "heightpack/bake/normal_job.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>

#include "heightpack/core/parallel.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/image_write.hpp"
#include "heightpack/io/read.hpp"
#include "heightpack/io/texture_write.hpp"

#include "job_steps.hpp"
#include "stored_chain.hpp"

namespace heightpack {

namespace {

std::vector<ExrAttribute> normalAttributes(const NormalJobOptions& options, const SourceInfo& source,
                                           const std::string& hash, int width, int height) {
    const NormalOptions& n = options.normal;
    const double tileHeight = texelHeight(n, width, height, height) * height;
    auto attributes =
        detail::commonAttributes(attributeText(options.layout), n.wrap, options.filter, source, hash, options.version);
    const std::vector<ExrAttribute> own = {
        attribute(attr::kernel, n.kernel),
        attribute(attr::convention, n.convention),
        attribute(attr::alpha, n.alpha),
        attribute(attr::tileWidth, static_cast<float>(n.tileWidth)),
        attribute(attr::tileHeight, static_cast<float>(tileHeight)),
        attribute(attr::heightRange, static_cast<float>(n.heightRange)),
    };
    attributes.insert(attributes.end(), own.begin(), own.end());
    return attributes;
}

// The first `channels` channels of every level.
std::vector<Image> firstChannels(const std::vector<Image>& chain, int channels) {
    std::vector<Image> out;
    for (const Image& level : chain) {
        Image cut(level.width, level.height, channels);
        for (size_t t = 0; t < level.texelCount(); ++t)
            for (int c = 0; c < channels; ++c) cut.pixels[t * channels + c] = level.pixels[t * level.channels + c];
        out.push_back(std::move(cut));
    }
    return out;
}

}  // namespace

Compression defaultNormalCompression(PixelType requested, double tolerance) {
    return requested == PixelType::Float && tolerance <= 0.0 ? Compression::None : Compression::Zip;
}

Result<NormalMaps> makeNormalChain(Image heights, const SourceInfo& source, const NormalJobOptions& options) {
    auto progress = [&](std::string_view stage, double f) {
        if (options.progress) options.progress(stage, f);
    };
    const NormalOptions& n = options.normal;
    NormalMaps maps;
    if (options.format == NormalFormat::Png8) {
        progress("normal", 0.0);
        const int w0 = heights.width, h0 = heights.height;
        maps.chain.push_back(normalsFromHeights(heights, texelWidth(n, w0, w0), texelHeight(n, w0, h0, h0), n));
    } else {
        MipOptions mip;
        mip.filter = options.filter;
        mip.wrap = n.wrap;
        mip.threads = n.threads;
        auto resized = detail::ensurePowerOfTwo(heights, source.path, options.resizeToPowerOfTwo, mip, true);
        if (!resized) return resized.error();
        maps.resized = *resized;
        progress("mip", 0.0);
        const std::vector<Image> heightChain = generateMipChain(heights, mip);
        progress("normal", 0.0);
        std::vector<Image> momentChain;
        if (n.alpha == NormalAlpha::SlopeVariance) {
            const Image& top = heightChain[0];
            momentChain = generateMipChain(
                slopeMoment(top, texelWidth(n, top.width, top.width), texelHeight(n, top.width, top.height, top.height), n),
                mip);
        }
        maps.chain = generateNormalChain(heightChain, n, momentChain);
        progress("normal", 1.0);
    }
    const Image& top = maps.chain[0];
    double minZ = 1.0;
    for (size_t i = 0; i < top.texelCount(); ++i) minZ = std::min(minZ, double(top.pixels[i * top.channels + 2]));
    maps.maxSlopeDegrees = std::acos(minZ) * 180.0 / 3.14159265358979323846;
    return maps;
}

Result<NormalReport> makeNormalMap(const std::string& input, const std::string& output,
                                   const NormalJobOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    auto progress = [&](std::string_view stage, double f) {
        if (options.progress) options.progress(stage, f);
    };
    if (Status s = checkWritable(output); !s) return s.error();
    if (options.layout == Layout::Xy && (options.format == NormalFormat::Png8 || options.normal.alpha != NormalAlpha::None))
        return withFix(inconsistentOptions(output, "an xy normal map is two channels of a mip-mapped texture: no alpha, no PNG",
                                           "store rgb normals for an alpha channel or an 8-bit PNG"),
                       options.format == NormalFormat::Png8 ? Fix::RgbNormalsInPng : Fix::RgbNormalsForAlpha);
    if (options.format == NormalFormat::Png8 && options.normal.alpha == NormalAlpha::SlopeVariance)
        return withFix(inconsistentOptions(output, "the slope variance describes mip levels, which a PNG does not have",
                                           "write a mip-mapped texture"),
                       Fix::VarianceNeedsLevels);
    if (options.layout != Layout::Rgb && options.layout != Layout::Xy)
        return Error{ErrorKind::Internal, output, std::string("a normal map has no '") + nameOf(options.layout) + "' layout",
                     "please report this"};
    // A mip-mapped output's container, decided here once from its name: the planner and the writer take it.
    std::optional<TextureOutput> mipMapped;
    if (options.format == NormalFormat::Exr) {
        auto named = textureOutput(output);
        if (!named) return named.error();
        mipMapped = *named;
    }

    NormalReport report;
    report.layout = options.layout;
    report.input = input;
    report.output = output;
    progress("load", 0.0);
    auto loaded = detail::loadInput(input, options.load, options.normal.threads);
    if (!loaded) return loaded.error();
    report.source = loaded->source;
    report.sourceHash = loaded->hash;

    auto maps = makeNormalChain(std::move(loaded->heights), report.source, options);
    if (!maps) return maps.error();
    const std::vector<Image>& chain = maps->chain;
    report.resized = maps->resized;
    report.maxSlopeDegrees = maps->maxSlopeDegrees;
    for (const Image& level : chain) report.levelSizes.emplace_back(level.width, level.height);

    if (options.format == NormalFormat::Png8) {
        Image& normals = maps->chain[0];
        for (size_t i = 0; i < normals.texelCount(); ++i) {
            float* t = &normals.pixels[i * normals.channels];
            for (int c = 0; c < 3; ++c) t[c] = 0.5f + 0.5f * t[c];
        }
        FlatImageOptions flat;
        flat.bits = 8;
        flat.attributes = normalAttributes(options, report.source, report.sourceHash, normals.width, normals.height);
        if (Status s = writeFlatImage(output, normals, flat); !s) return s.error();
    } else {
        // xy: the first two channels alone, what the shader reads before rebuilding z.
        const std::vector<Image> stored = options.layout == Layout::Xy ? firstChannels(chain, 2) : chain;
        ChainToWrite content;
        content.width = stored[0].width;
        content.height = stored[0].height;
        content.channelNames = {"R", "G", "B", "A"};
        content.channelNames.resize(size_t(stored[0].channels));
        content.fillRows = [&](int level, int y0, int rows, float* dst) {
            const Image& l = stored[level];
            std::copy(l.row(y0), l.row(y0) + static_cast<size_t>(rows) * l.width * l.channels, dst);
        };
        content.attributes = normalAttributes(options, report.source, report.sourceHash, content.width, content.height);
        TextureWriteOptions write;
        write.storage = options.storage;
        if (write.storage.tolerance <= 0.0 && options.toleranceMetres > 0.0) {
            const NormalOptions& n = options.normal;
            const double across = n.tileWidth / chain[0].width;
            const double down = n.tileHeight > 0.0 ? n.tileHeight / chain[0].height : across;
            write.storage.tolerance = options.toleranceMetres / std::max(across, down);
        }
        report.tolerance = write.storage.tolerance;
        write.threads = options.normal.threads;
        write.writer = "heightpack " + options.version;
        write.progress = [&](double f) { progress("write", f); };
        auto storage = detail::chooseStorage({*mipMapped}, content, {&stored}, write);
        if (!storage) return storage.error();
        write.storage.pixelType = storage->pixelType;
        report.pixelType = storage->pixelType;
        report.lookupError = storage->lookupError;
        report.angleError = storage->angleError;
        report.toleranceInDegrees = write.storage.toleranceInDegrees;
        const std::vector<ExrAttribute> errors = detail::lookupErrorAttributes(*storage);
        content.attributes.insert(content.attributes.end(), errors.begin(), errors.end());
        if (Status s = writeTexture(*mipMapped, content, write, storage->plan); !s) return s.error();
    }
    progress("write", 1.0);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

}  // namespace heightpack
