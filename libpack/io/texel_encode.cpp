#include "texel_encode.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>

#include "heightpack/core/parallel.hpp"

namespace heightpack::detail {

namespace {

template <class T>
void putLe(std::uint8_t* dst, T value) {
    std::memcpy(dst, &value, sizeof value);  // every target heightpack builds for is little-endian
}

// Fills rows of level into band (sourceChannels floats a texel), in parallel.
void fillBand(const MipChainSource& content, int level, int y0, int rows, int width, int channels, int threads,
              std::vector<float>& band) {
    band.resize(size_t(rows) * width * channels);
    parallelFor(rows, threads, [&](int a, int b) {
        content.fillRows(level, y0 + a, b - a, band.data() + size_t(a) * width * channels);
    });
}

Error notFinite(const std::string& path, int level) {
    return Error{ErrorKind::Internal, path,
                 "internal error: level " + std::to_string(level) + " holds a non-finite value; nothing was written",
                 "please report this with the command line"};
}

}  // namespace

int fullChainLevels(int width, int height) {
    int levels = 1;
    while ((width >> levels) > 0 || (height >> levels) > 0) ++levels;
    return levels;
}

Result<EncodePlan> planEncoding(const std::string& path, const MipChainSource& content,
                                const TextureWriteOptions& options) {
    EncodePlan plan;
    plan.sourceChannels = static_cast<int>(content.channelNames.size());
    plan.format = texelFormatInfo(texelFormatFor(plan.sourceChannels, options.storage.pixelType));
    plan.levels = fullChainLevels(content.width, content.height);
    if (options.levels > 0) plan.levels = std::min(plan.levels, options.levels);
    if (options.storage.pixelType == PixelType::Float) return plan;
    if (options.planned && options.planned->pixelType == options.storage.pixelType) {
        plan.normalisation = options.planned->normalisation;
        return plan;
    }

    // One pass over the chain: the range (uint16) and what a half cannot hold.
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    std::vector<float> band;
    for (int level = 0; level < plan.levels; ++level) {
        const int w = levelSide(content.width, level), h = levelSide(content.height, level);
        for (int y0 = 0; y0 < h; y0 += kBandRows) {
            const int rows = std::min(kBandRows, h - y0);
            fillBand(content, level, y0, rows, w, plan.sourceChannels, options.threads, band);
            // The band's rows scanned on all threads: each its range and its first value that cannot be
            // stored; the first such value in row order is the one reported, whatever the thread count.
            struct Scan {
                double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
                size_t bad = SIZE_MAX;
            };
            std::vector<Scan> scans(static_cast<size_t>(rows));
            const size_t rowValues = band.size() / size_t(rows);
            parallelFor(rows, options.threads, [&](int begin, int end) {
                for (int r = begin; r < end; ++r) {
                    Scan& scan = scans[size_t(r)];
                    for (size_t i = size_t(r) * rowValues; i < size_t(r + 1) * rowValues; ++i) {
                        const float v = band[i];
                        if (!std::isfinite(v) || (options.storage.pixelType == PixelType::Half && !halfCanHold(v))) {
                            scan.bad = i;
                            break;
                        }
                        scan.lo = std::min<double>(scan.lo, v);
                        scan.hi = std::max<double>(scan.hi, v);
                    }
                }
            });
            for (const Scan& scan : scans) {
                if (scan.bad != SIZE_MAX) {
                    const float v = band[scan.bad];
                    if (!std::isfinite(v)) return notFinite(path, level);
                    return badInput(path,
                                    "level " + std::to_string(level) + " holds " + floatText(v) +
                                        ", beyond the largest half float (65504); nothing was written",
                                    "store float or uint16 pixels, or scale the heights down");
                }
                lo = std::min(lo, scan.lo);
                hi = std::max(hi, scan.hi);
            }
        }
    }
    if (plan.format.kind == ComponentKind::Unorm16) {
        if (plan.sourceChannels == 3) hi = std::max(hi, 1.0), lo = std::min(lo, 1.0);  // the alpha of 1 we add
        Normalisation n{static_cast<float>(lo), static_cast<float>(hi - lo)};
        if (options.gridSpan > 0.0f) {
            // A painted map's values lie on origin + k * step. Start on that grid, below the chain's
            // minimum, and split each step into the most whole sub-steps that still reach the maximum:
            // level 0 then reads back exactly, and at least half of the 65536 codes are used.
            const double step = double(options.gridSpan) / 65535.0;
            const double base = options.gridOrigin + std::floor((lo - options.gridOrigin) / step + 1e-3) * step;
            const double steps = std::max((hi - base) / step, 1.0);
            const double split = std::floor(65535.0 / steps + 1e-9);
            if (split >= 1.0) n = {static_cast<float>(base), static_cast<float>(double(options.gridSpan) / split)};
        }
        if (!(n.scale > 0.0f)) n.scale = 1.0f;  // a flat chain: every texel 0 decodes to offset
        plan.normalisation = n;
    }
    return plan;
}

Status encodeRows(const std::string& path, const MipChainSource& content, const EncodePlan& plan, int level, int y0,
                  int rows, int threads, std::vector<std::uint8_t>& dst) {
    const int w = levelSide(content.width, level);
    const int src = plan.sourceChannels, dstChannels = plan.format.channels;
    const int componentBytes = plan.format.bytesPerComponent();
    std::vector<float> band;
    fillBand(content, level, y0, rows, w, src, threads, band);
    dst.resize(size_t(rows) * w * plan.format.bytesPerTexel());
    const Normalisation n = plan.normalisation.value_or(Normalisation{});
    bool finite = true;
    const size_t texels = size_t(rows) * w;
    std::uint8_t* out = dst.data();
    for (size_t t = 0; t < texels; ++t) {
        for (int c = 0; c < dstChannels; ++c, out += componentBytes) {
            const float v = c < src ? band[t * src + c] : 1.0f;  // RGB gets alpha 1
            finite = finite && std::isfinite(v);
            switch (plan.format.kind) {
                case ComponentKind::Float32: putLe(out, v); break;
                case ComponentKind::Float16: putLe(out, floatToHalf(v)); break;
                case ComponentKind::Unorm16: putLe(out, unormCode(v, n)); break;
                case ComponentKind::Snorm16: putLe(out, snormCode(v)); break;
            }
        }
    }
    if (!finite) return notFinite(path, level);
    return Done{};
}

std::uint16_t unormCode(double value, const Normalisation& n) {
    const double u = std::nearbyint((value - n.offset) * (65535.0 / n.scale));
    return static_cast<std::uint16_t>(std::clamp(u, 0.0, 65535.0));
}

float unormValue(std::uint16_t code, const Normalisation& n) { return n.offset + n.scale * (float(code) / 65535.0f); }

std::int16_t snormCode(float value) {
    return static_cast<std::int16_t>(std::nearbyint(std::clamp(double(value), -1.0, 1.0) * 32767.0));
}

float snormValue(std::int16_t code) { return std::max(float(code) / 32767.0f, -1.0f); }

float storeAndRead(const EncodePlan& plan, float value) {
    switch (plan.format.kind) {
        case ComponentKind::Float32: return value;
        case ComponentKind::Float16: return halfToFloat(floatToHalf(value));
        case ComponentKind::Unorm16: {
            const Normalisation n = plan.normalisation.value_or(Normalisation{});
            return unormValue(unormCode(value, n), n);
        }
        case ComponentKind::Snorm16: return snormValue(snormCode(value));
    }
    return value;
}

Image decodeLevel(const TexelFormatInfo& format, const std::uint8_t* bytes, int width, int height,
                  const std::optional<Normalisation>& normalisation) {
    Image image(width, height, format.channels);
    const Normalisation n = normalisation.value_or(Normalisation{});
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        float& v = image.pixels[i];
        switch (format.kind) {
            case ComponentKind::Float32: std::memcpy(&v, bytes + 4 * i, 4); break;
            case ComponentKind::Float16: {
                std::uint16_t h;
                std::memcpy(&h, bytes + 2 * i, 2);
                v = halfToFloat(h);
                break;
            }
            case ComponentKind::Unorm16: {
                std::uint16_t u;
                std::memcpy(&u, bytes + 2 * i, 2);
                v = unormValue(u, n);
                break;
            }
            case ComponentKind::Snorm16: {
                std::int16_t s;
                std::memcpy(&s, bytes + 2 * i, 2);
                v = snormValue(s);
                break;
            }
        }
    }
    return image;
}

std::string floatText(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", double(value));
    return text;
}

Attributes attributesAsText(const std::vector<ExrAttribute>& attributes) {
    Attributes out;
    for (const ExrAttribute& a : attributes) {
        if (const auto* s = std::get_if<std::string>(&a.value))
            out.emplace_back(a.name, *s);
        else
            out.emplace_back(a.name, floatText(std::get<float>(a.value)));
    }
    return out;
}

Result<std::vector<std::uint8_t>> readWholeFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) return badInput(path, "cannot be opened", "check that the file exists and is readable");
    const std::streamoff size = in.tellg();
    if (size < 0) return badInput(path, "cannot be read", "check that it is a regular file");
    std::vector<std::uint8_t> bytes(static_cast<size_t>(size));
    in.seekg(0);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), size))
        return badInput(path, "cannot be read", "check that it is a regular file");
    return bytes;
}

}  // namespace heightpack::detail
