#include "texel_encode.hpp"

#include <Imath/half.h>
#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "heightpack/core/parallel.hpp"
#include "heightpack/io/attributes.hpp"

namespace heightpack::detail {

namespace {

template <class T>
void putLe(std::uint8_t* dst, T value) {
    std::memcpy(dst, &value, sizeof value);  // every target heightpack builds for is little-endian
}

// Fills rows of a layer's level into band (sourceChannels floats a texel), in parallel.
void fillBand(const MipChainSource& content, int layer, int level, int y0, int rows, int width, int channels,
              int threads, std::vector<float>& band) {
    band.resize(size_t(rows) * width * channels);
    parallelFor(rows, threads, [&](int a, int b) {
        fillLayerRows(content, layer, level, y0 + a, b - a, band.data() + size_t(a) * width * channels);
    });
}

// A float's bits as a signed integer that orders like the float (-0 just below +0, NaNs beyond the
// infinities). Integer minima and maxima vectorise; float ones do not, since they must keep the first of
// two equal zeros.
std::int32_t orderKey(float v) {
    std::int32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return bits ^ ((bits >> 31) & 0x7fffffff);
}
float fromOrderKey(std::int32_t key) {
    const std::int32_t bits = key ^ ((key >> 31) & 0x7fffffff);
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
}

// The range of a run of values and its first value that cannot be stored, as a loop with std::min and
// std::max over doubles, stopping at that value, finds them.
struct Scan {
    double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
    size_t bad = SIZE_MAX;  // index into the run
};

Scan scanValues(const float* v, size_t n, bool half) {
    std::int32_t lo = std::numeric_limits<std::int32_t>::max(), hi = std::numeric_limits<std::int32_t>::min();
    for (size_t i = 0; i < n; ++i) {
        const std::int32_t key = orderKey(v[i]);
        lo = std::min(lo, key);
        hi = std::max(hi, key);
    }
    Scan scan;
    if (n == 0) return scan;
    const float limit = half ? 65520.0f : std::numeric_limits<float>::infinity();  // halfCanHold's bounds
    if (lo <= orderKey(-limit) || hi >= orderKey(limit)) {
        // Rare: a value beyond the type (or not finite). The loop replaced, value by value, finds the first.
        for (size_t i = 0; i < n; ++i) {
            if (!std::isfinite(v[i]) || (half && !halfCanHold(v[i]))) {
                scan.bad = i;
                break;
            }
            scan.lo = std::min<double>(scan.lo, v[i]);
            scan.hi = std::max<double>(scan.hi, v[i]);
        }
        return scan;
    }
    // Equal floats are equal bits, except +0 and -0: std::min and std::max kept the first zero met.
    auto firstZero = [&] { return *std::find(v, v + n, 0.0f); };
    const float low = fromOrderKey(lo), high = fromOrderKey(hi);
    scan.lo = low == 0.0f ? firstZero() : low;
    scan.hi = high == 0.0f ? firstZero() : high;
    return scan;
}

// Whether every value is finite, by their exponent bits (a test that vectorises).
bool allFinite(const float* v, size_t n) {
    std::uint32_t infinite = 0;
    for (size_t i = 0; i < n; ++i) {
        std::uint32_t bits;
        std::memcpy(&bits, v + i, sizeof bits);
        infinite |= std::uint32_t((bits & 0x7f800000u) == 0x7f800000u);
    }
    return infinite == 0;
}

// Encodes texels of `from` floats each into `to` components of type T (an RGB texel gets alpha 1).
template <class T, class Code>
void encodeTexels(const float* in, int from, int to, size_t texels, std::uint8_t* out, Code code) {
    if (from == to) {
        for (size_t i = 0; i < texels * size_t(to); ++i) putLe(out + i * sizeof(T), T(code(in[i])));
        return;
    }
    for (size_t t = 0; t < texels; ++t)
        for (int c = 0; c < to; ++c) putLe(out + (t * to + c) * sizeof(T), T(code(c < from ? in[t * from + c] : 1.0f)));
}

#if defined(__x86_64__) || defined(__i386__)
// F16C's conversion, eight values an instruction, where the processor has it (x86-64 since 2012). It
// rounds to nearest even as Imath does: the same bits for every float but NaNs, which are never stored
// (compared over all 2^32 floats when this was written).
__attribute__((target("avx,f16c"))) void halvesF16c(const float* in, size_t n, std::uint8_t* out) {
    size_t i = 0;
    for (; i + 8 <= n; i += 8)
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 2 * i),
                         _mm256_cvtps_ph(_mm256_loadu_ps(in + i), _MM_FROUND_TO_NEAREST_INT));
    for (; i < n; ++i) putLe(out + 2 * i, Imath::half(in[i]).bits());
}
// AVX with the OS saving its state (the builtin checks that), and F16C from CPUID: clang 14 knows no "f16c" name.
bool hasF16c() {
    unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
    return __builtin_cpu_supports("avx") && __get_cpuid(1, &eax, &ebx, &ecx, &edx) && (ecx & bit_F16C) != 0;
}
const bool kHasF16c = hasF16c();
#else
void halvesF16c(const float*, size_t, std::uint8_t*) {}
constexpr bool kHasF16c = false;
#endif

void encodeRow(const EncodePlan& plan, const float* in, size_t texels, std::uint8_t* out) {
    const int from = plan.sourceChannels, to = plan.format.channels;
    switch (plan.format.kind) {
        case ComponentKind::Float32: encodeTexels<float>(in, from, to, texels, out, [](float v) { return v; }); break;
        case ComponentKind::Float16:
            if (kHasF16c && from == to) {
                halvesF16c(in, texels * size_t(to), out);
                break;
            }
            // Imath's conversion inline (floatToHalf's own), not a call a value.
            encodeTexels<std::uint16_t>(in, from, to, texels, out, [](float v) { return Imath::half(v).bits(); });
            break;
        case ComponentKind::Unorm16: {
            const Normalisation n = plan.normalisation.value_or(Normalisation{});
            encodeTexels<std::uint16_t>(in, from, to, texels, out, [n](float v) { return unormCode(v, n); });
            break;
        }
        case ComponentKind::Snorm16: encodeTexels<std::int16_t>(in, from, to, texels, out, snormCode); break;
    }
}

Error notFinite(const std::string& path, int level) {
    return Error{ErrorKind::Internal, path,
                 "internal error: level " + std::to_string(level) + " holds a non-finite value; nothing was written",
                 "please report this with the command line"};
}

}  // namespace

void fillLayerRows(const MipChainSource& content, int layer, int level, int y0, int rows, float* dst) {
    if (content.layerNames.empty()) content.fillRows(level, y0, rows, dst);
    else content.fillLayerRows(layer, level, y0, rows, dst);
}

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

    // One pass over the chain, every layer of an array: the range (uint16: one normalisation for the
    // whole texture, as a DDS header has room for one) and what a half cannot hold.
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    std::vector<float> band;
    for (int pass = 0; pass < content.layerCount() * plan.levels; ++pass) {
        const int layer = pass / plan.levels, level = pass % plan.levels;
        const int w = levelSide(content.width, level), h = levelSide(content.height, level);
        for (int y0 = 0; y0 < h; y0 += kBandRows) {
            const int rows = std::min(kBandRows, h - y0);
            fillBand(content, layer, level, y0, rows, w, plan.sourceChannels, options.threads, band);
            // The band's rows scanned on all threads: each its range and its first value that cannot be
            // stored; the first such value in row order is the one reported, whatever the thread count.
            std::vector<Scan> scans(static_cast<size_t>(rows));
            const size_t rowValues = band.size() / size_t(rows);
            const bool half = options.storage.pixelType == PixelType::Half;
            parallelFor(rows, options.threads, [&](int begin, int end) {
                for (int r = begin; r < end; ++r) {
                    scans[size_t(r)] = scanValues(band.data() + size_t(r) * rowValues, rowValues, half);
                    if (scans[size_t(r)].bad != SIZE_MAX) scans[size_t(r)].bad += size_t(r) * rowValues;
                }
            });
            for (const Scan& scan : scans) {
                if (scan.bad != SIZE_MAX) {
                    const float v = band[scan.bad];
                    if (!std::isfinite(v)) return notFinite(path, level);
                    const std::string where =
                        content.layerNames.empty() ? "" : "layer " + content.layerNames[size_t(layer)] + ", ";
                    return badInput(path,
                                    where + "level " + std::to_string(level) + " holds " + floatText(v) +
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

Status BandEncoder::encode(int level, int y0, int rows, int layer) {
    const int w = levelSide(content_.width, level);
    const int from = plan_.sourceChannels;
    const size_t rowValues = size_t(w) * from, rowBytes = size_t(w) * plan_.format.bytesPerTexel();
    bytes_.resize(size_t(rows) * rowBytes);
    // Float texels of the source's channels are the filled floats themselves: filled straight into bytes_.
    const bool direct = plan_.format.kind == ComponentKind::Float32 && plan_.format.channels == from;
    if (!direct) band_.resize(size_t(rows) * rowValues);
    std::vector<char> finite(static_cast<size_t>(rows));
    parallelFor(rows, threads_, [&](int a, int b) {
        float* values = direct ? reinterpret_cast<float*>(bytes_.data() + size_t(a) * rowBytes)
                               : band_.data() + size_t(a) * rowValues;
        fillLayerRows(content_, layer, level, y0 + a, b - a, values);
        for (int r = a; r < b; ++r) {
            const float* row = values + size_t(r - a) * rowValues;
            finite[size_t(r)] = allFinite(row, rowValues);
            if (!direct) encodeRow(plan_, row, size_t(w), bytes_.data() + size_t(r) * rowBytes);
        }
    });
    if (std::find(finite.begin(), finite.end(), 0) != finite.end()) return notFinite(path_, level);
    return Done{};
}

float unormValue(std::uint16_t code, const Normalisation& n) { return n.offset + n.scale * (float(code) / 65535.0f); }

float snormValue(std::int16_t code) { return std::max(float(code) / 32767.0f, -1.0f); }

float storeAndRead(const EncodePlan& plan, float value) {
    switch (plan.format.kind) {
        case ComponentKind::Float32: return value;
        case ComponentKind::Float16: return float(Imath::half(value));  // halfToFloat(floatToHalf(value)), inline
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

Image decodeLayers(const TexelFormatInfo& format, const std::uint8_t* bytes, int width, int height, int layers,
                   const std::optional<Normalisation>& normalisation) {
    if (layers == 1) return decodeLevel(format, bytes, width, height, normalisation);
    const int c = format.channels;
    const size_t texels = size_t(width) * height, layerBytes = texels * format.bytesPerTexel();
    Image all(width, height, c * layers);
    for (int layer = 0; layer < layers; ++layer) {
        const Image one = decodeLevel(format, bytes + layer * layerBytes, width, height, normalisation);
        for (size_t t = 0; t < texels; ++t)
            std::copy_n(one.pixels.data() + t * c, c, all.pixels.data() + (t * layers + layer) * c);
    }
    return all;
}

std::vector<std::string> layerNamesOf(const std::string& recorded, int layers) {
    std::vector<std::string> names;
    for (size_t at = 0; !recorded.empty() && at <= recorded.size();) {
        const size_t comma = std::min(recorded.find(',', at), recorded.size());
        names.push_back(recorded.substr(at, comma - at));
        at = comma + 1;
    }
    if (int(names.size()) == layers) return names;
    names = {layerName::heights};
    for (int i = 1; i < layers; ++i) names.push_back("layer" + std::to_string(i));
    return names;
}

std::string layerList(const std::vector<std::string>& names) {
    std::string list;
    for (const std::string& n : names) list.append(list.empty() ? "" : ",").append(n);
    return list;
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
