// ASTC through astcenc: a context made for the block size and the fixed preset, fed a band of block rows
// at a time as RGBA floats (the chain's values keep their precision into the encoder, as for BC4/BC5).
#include "heightpack/core/astc_compression.hpp"

// Debian's libastcenc is the shared library, whose functions have C linkage: the header declares them so
// only when told it is one.
#define ASTCENC_DYNAMIC_LIBRARY 1
#include <astcenc.h>

#include <algorithm>
#include <memory>
#include <thread>

#include "heightpack/core/parallel.hpp"

namespace heightpack {

namespace {

// Block rows encoded at a time: a 4096-wide band of 32 rows of 4x4 blocks is 8 MiB of RGBA floats.
constexpr int kBandBlockRows = 32;

struct ContextFree {
    void operator()(astcenc_context* context) const { astcenc_context_free(context); }
};
using Context = std::unique_ptr<astcenc_context, ContextFree>;

// HDR colour with LDR alpha: heights are luminance and alpha stays 1, which the HDR luminance modes imply.
astcenc_profile profileOf(BlockFormat format) { return isAstcHdr(format) ? ASTCENC_PRF_HDR_RGB_LDR_A : ASTCENC_PRF_LDR; }

Context makeContext(BlockFormat format, unsigned flags, unsigned threads) {
    const unsigned side = unsigned(blockSide(format));
    astcenc_config config;
    if (astcenc_config_init(profileOf(format), side, side, 1, kAstcQuality, flags, &config) != ASTCENC_SUCCESS)
        return nullptr;
    astcenc_context* context = nullptr;
    if (astcenc_context_alloc(&config, threads, &context) != ASTCENC_SUCCESS) return nullptr;
    return Context(context);
}

// The context last made on this thread, kept for the next image of the same block size, flags and thread
// count: a chain's levels are encoded and decoded one after another, and making a context (astcenc's
// tables of block modes and partitions) takes 10-30 ms, as long as encoding a 256x256 level.
astcenc_context* reusedContext(BlockFormat format, unsigned flags, unsigned threads) {
    struct Kept {
        BlockFormat format;
        unsigned flags, threads;
        Context context;
    };
    thread_local std::vector<Kept> kept;
    for (const Kept& k : kept)
        if (k.format == format && k.flags == flags && k.threads == threads) return k.context.get();
    Context made = makeContext(format, flags, threads);
    if (!made) return nullptr;
    if (kept.size() >= 4) kept.erase(kept.begin());  // an encoder and a decoder a chain, and the other kind's
    kept.push_back({format, flags, threads, std::move(made)});
    return kept.back().context.get();
}

float unit(float v) { return v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v; }

}  // namespace

std::vector<std::uint8_t> encodeAstc(ImageView image, BlockFormat format, int threads, bool normalMap) {
    const int side = blockSide(format);
    const int across = (image.width + side - 1) / side, down = (image.height + side - 1) / side;
    const unsigned workers = unsigned(std::max(1, resolveThreadCount(threads)));  // the same for every level
    astcenc_context* const context = reusedContext(format, normalMap && image.channels == 2 ? ASTCENC_FLG_MAP_NORMAL : 0, workers);
    if (!context) return {};
    std::vector<std::uint8_t> out(blockImageBytes(image.width, image.height, format));
    const astcenc_swizzle identity{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};
    std::vector<float> rgba;
    for (int band = 0; band < down; band += kBandBlockRows) {
        const int y0 = band * side, rows = std::min(kBandBlockRows * side, image.height - y0);
        const int bandBlocks = across * std::min(kBandBlockRows, down - band);
        rgba.resize(size_t(image.width) * size_t(rows) * 4);
        parallelFor(rows, threads, [&](int begin, int end) {
            for (int y = begin; y < end; ++y)
                for (int x = 0; x < image.width; ++x) {
                    float* t = rgba.data() + (size_t(y) * size_t(image.width) + size_t(x)) * 4;
                    const float first = unit(image.at(x, y0 + y, 0));
                    t[0] = t[1] = t[2] = first;
                    t[3] = image.channels == 2 ? unit(image.at(x, y0 + y, 1)) : 1.0f;
                }
        });
        void* slice = rgba.data();
        astcenc_image bandImage{unsigned(image.width), unsigned(rows), 1, ASTCENC_TYPE_F32, &slice};
        std::uint8_t* target = out.data() + size_t(band) * size_t(across) * 16;
        const size_t length = size_t(bandBlocks) * 16;
        std::vector<astcenc_error> results(workers, ASTCENC_SUCCESS);
        std::vector<std::thread> pool;
        for (unsigned t = 1; t < workers; ++t)
            pool.emplace_back([&, t] { results[t] = astcenc_compress_image(context, &bandImage, &identity, target, length, t); });
        results[0] = astcenc_compress_image(context, &bandImage, &identity, target, length, 0);
        for (std::thread& t : pool) t.join();
        // Reset whatever happened: the context is kept for the next image.
        if (astcenc_compress_reset(context) != ASTCENC_SUCCESS) return {};
        for (const astcenc_error e : results)
            if (e != ASTCENC_SUCCESS) return {};
    }
    return out;
}

Image decodeAstc(const std::uint8_t* bytes, int width, int height, BlockFormat format, int channels) {
    Image decoded(width, height, channels);
    astcenc_context* const context = reusedContext(format, ASTCENC_FLG_DECOMPRESS_ONLY, 1);
    if (!context) return decoded;
    const int side = blockSide(format), across = (width + side - 1) / side, down = (height + side - 1) / side;
    const astcenc_swizzle identity{ASTCENC_SWZ_R, ASTCENC_SWZ_G, ASTCENC_SWZ_B, ASTCENC_SWZ_A};
    std::vector<float> rgba;  // a band of block rows at a time, as encoded: not four floats for every texel
    for (int band = 0; band < down; band += kBandBlockRows) {
        const int y0 = band * side, rows = std::min(kBandBlockRows * side, height - y0);
        rgba.resize(size_t(width) * size_t(rows) * 4);
        void* slice = rgba.data();
        astcenc_image image{unsigned(width), unsigned(rows), 1, ASTCENC_TYPE_F32, &slice};
        const size_t length = size_t(across) * size_t(std::min(kBandBlockRows, down - band)) * 16;
        if (astcenc_decompress_image(context, bytes + size_t(band) * size_t(across) * 16, length, &image, &identity, 0) !=
            ASTCENC_SUCCESS)
            return decoded;
        float* out = decoded.row(y0);
        for (size_t i = 0; i < size_t(width) * size_t(rows); ++i) {
            out[i * size_t(channels)] = rgba[i * 4];
            if (channels == 2) out[i * 2 + 1] = rgba[i * 4 + 3];
        }
    }
    return decoded;
}

}  // namespace heightpack
