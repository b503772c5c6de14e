#include "texel_encode.hpp"

#include <Imath/half.h>
#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#include <immintrin.h>
#endif

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
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
// What reading back a half of each value gives, eight values at a time (exactly, F16C's widening).
__attribute__((target("avx,f16c"))) void halfRoundTripF16c(const float* in, size_t n, float* out) {
    size_t i = 0;
    for (; i + 8 <= n; i += 8)
        _mm256_storeu_ps(out + i, _mm256_cvtph_ps(_mm256_cvtps_ph(_mm256_loadu_ps(in + i), _MM_FROUND_TO_NEAREST_INT)));
    for (; i < n; ++i) out[i] = float(Imath::half(in[i]));
}
// unormCode and unormValue four values at a time, with AVX. The same steps in the same precision: the
// difference and product in double, the clamps (maxpd / minpd equal the scalar comparisons for every
// value but NaN, which is never stored), the round to even by adding and subtracting 1.5 * 2^52, the
// truncation of an integer-valued double; the value back in float, divided, multiplied and added as
// unormValue does (no fused multiply-add: this target has none).
__attribute__((target("avx"))) inline __m128i unormCodes4(const float* in, __m256d offset, __m256d k) {
    __m256d u = _mm256_mul_pd(_mm256_sub_pd(_mm256_cvtps_pd(_mm_loadu_ps(in)), offset), k);
    u = _mm256_min_pd(_mm256_max_pd(u, _mm256_setzero_pd()), _mm256_set1_pd(65535.0));
    const __m256d shift = _mm256_set1_pd(6755399441055744.0);
    return _mm256_cvttpd_epi32(_mm256_sub_pd(_mm256_add_pd(u, shift), shift));  // four codes as int32
}
__attribute__((target("avx"))) void unormCodesAvx(const float* in, size_t n, const Normalisation& norm, std::uint8_t* out) {
    const __m256d offset = _mm256_set1_pd(norm.offset), k = _mm256_set1_pd(65535.0 / norm.scale);
    size_t i = 0;
    for (; i + 8 <= n; i += 8)
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 2 * i),
                         _mm_packus_epi32(unormCodes4(in + i, offset, k), unormCodes4(in + i + 4, offset, k)));
    for (; i < n; ++i) putLe(out + 2 * i, unormCode(in[i], norm));
}
__attribute__((target("avx"))) void unormRoundTripAvx(const float* in, size_t n, const Normalisation& norm, float* out) {
    const __m256d offset = _mm256_set1_pd(norm.offset), k = _mm256_set1_pd(65535.0 / norm.scale);
    const __m128 scale = _mm_set1_ps(norm.scale), base = _mm_set1_ps(norm.offset), top = _mm_set1_ps(65535.0f);
    size_t i = 0;
    for (; i + 4 <= n; i += 4) {
        const __m128 codes = _mm_cvtepi32_ps(unormCodes4(in + i, offset, k));
        _mm_storeu_ps(out + i, _mm_add_ps(base, _mm_mul_ps(scale, _mm_div_ps(codes, top))));
    }
    for (; i < n; ++i) out[i] = unormValue(unormCode(in[i], norm), norm);
}
// AVX with the OS saving its state (the builtin checks that), and F16C from CPUID: clang 14 knows no "f16c" name.
bool hasF16c() {
    unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
    return __builtin_cpu_supports("avx") && __get_cpuid(1, &eax, &ebx, &ecx, &edx) && (ecx & bit_F16C) != 0;
}
const bool kHasF16c = hasF16c();
const bool kHasAvx = __builtin_cpu_supports("avx");
#else
void halvesF16c(const float*, size_t, std::uint8_t*) {}
void halfRoundTripF16c(const float*, size_t, float*) {}
void unormCodesAvx(const float*, size_t, const Normalisation&, std::uint8_t*) {}
void unormRoundTripAvx(const float*, size_t, const Normalisation&, float*) {}
constexpr bool kHasF16c = false;
constexpr bool kHasAvx = false;
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
            if (kHasAvx && from == to) {
                unormCodesAvx(in, texels * size_t(to), n, out);
                break;
            }
            encodeTexels<std::uint16_t>(in, from, to, texels, out, [n](float v) { return unormCode(v, n); });
            break;
        }
        case ComponentKind::Snorm16: encodeTexels<std::int16_t>(in, from, to, texels, out, snormCode); break;
        case ComponentKind::Block: break;  // whole levels at a time: encodeBlockLevels
    }
}

}  // namespace

void fillLayerRows(const ChainToWrite& content, int layer, int level, int y0, int rows, float* dst) {
    if (content.layerNames.empty()) content.fillRows(level, y0, rows, dst);
    else content.fillLayerRows(layer, level, y0, rows, dst);
}

bool allFinite(const float* v, size_t n) {
    std::uint32_t infinite = 0;
    for (size_t i = 0; i < n; ++i) {
        std::uint32_t bits;
        std::memcpy(&bits, v + i, sizeof bits);
        infinite |= std::uint32_t((bits & 0x7f800000u) == 0x7f800000u);
    }
    return infinite == 0;
}

Error nonFiniteLevel(const std::string& path, int level) {
    return Error{ErrorKind::Internal, path,
                 "internal error: level " + std::to_string(level) + " holds a non-finite value; nothing was written",
                 "please report this with the command line"};
}

Status BandEncoder::encode(int level, int y0, int rows, int layer) {
    const int w = mipLevelSide(content_.width, level);
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
    if (std::find(finite.begin(), finite.end(), 0) != finite.end()) return nonFiniteLevel(path_, level);
    return Done{};
}

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
        case ComponentKind::Block: break;  // a block's values depend on its neighbours: see BlockLevels
    }
    return value;
}

void storeAndReadRow(const EncodePlan& plan, const float* values, size_t n, float* readBack) {
    switch (plan.format.kind) {
        case ComponentKind::Float32: std::copy_n(values, n, readBack); return;
        case ComponentKind::Float16:
            if (kHasF16c) halfRoundTripF16c(values, n, readBack);
            else
                for (size_t i = 0; i < n; ++i) readBack[i] = float(Imath::half(values[i]));
            return;
        case ComponentKind::Unorm16: {
            const Normalisation u = plan.normalisation.value_or(Normalisation{});
            if (kHasAvx) unormRoundTripAvx(values, n, u, readBack);
            else
                for (size_t i = 0; i < n; ++i) readBack[i] = unormValue(unormCode(values[i], u), u);
            return;
        }
        case ComponentKind::Snorm16:
            for (size_t i = 0; i < n; ++i) readBack[i] = snormValue(snormCode(values[i]));
            return;
        case ComponentKind::Block: std::copy_n(values, n, readBack); return;  // see BlockLevels
    }
}

Image decodeLevel(const TexelFormatInfo& format, const std::uint8_t* bytes, int width, int height,
                  const std::optional<Normalisation>& normalisation) {
    const Normalisation n = normalisation.value_or(Normalisation{});
    if (format.isBlock()) {
        Image image = decodeBlocks(bytes, width, height, blockFormatOf(format), format.channels);
        for (float& v : image.pixels) v = n.offset + n.scale * v;
        return image;
    }
    Image image(width, height, format.channels);
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
            case ComponentKind::Block: break;
        }
    }
    return image;
}

Image decodeLayers(const TexelFormatInfo& format, const std::uint8_t* bytes, int width, int height, int layers,
                   const std::optional<Normalisation>& normalisation) {
    if (layers == 1) return decodeLevel(format, bytes, width, height, normalisation);
    const int c = format.channels;
    const size_t texels = size_t(width) * height, layerBytes = imageBytes(format, width, height);
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
    return std::string(text, std::to_chars(text, text + sizeof text, value).ptr);
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
