#include "heightpack/core/image.hpp"

#include <algorithm>

#include "heightpack/core/parallel.hpp"

namespace heightpack {

SampleRange sampleRange(const Image& image, int threads) { return sampleRange(std::span<const float>(image.pixels), threads); }

SampleRange sampleRange(std::span<const float> samples, int threads) {
    const size_t n = samples.size();
    if (n == 0) return {};
    constexpr int kChunks = 64;
    const size_t chunk = (n + kChunks - 1) / kChunks;
    std::vector<SampleRange> ranges(kChunks, SampleRange{samples[0], samples[0]});
    parallelFor(kChunks, threads, [&](int begin, int end) {
        for (int c = begin; c < end; ++c) {
            float low = samples[0], high = low;
            for (size_t i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i) {
                const float v = samples[i];
                low = v < low ? v : low;  // the form minps computes, so the loop vectorises
                high = v > high ? v : high;
            }
            ranges[c] = {low, high};
        }
    });
    SampleRange all = ranges[0];
    for (const SampleRange& r : ranges) {
        all.low = std::min(all.low, r.low);
        all.high = std::max(all.high, r.high);
    }
    return all;
}

Image transposed(const Image& image, int threads) {
    assert(image.channels == 1);
    Image out(image.height, image.width, 1);
    // In 16 x 16 blocks, each output row's 16 texels written in a run: a plain loop writes every texel of
    // a column to another cache line. Blocks of 64 rows, a power-of-two stride apart, all fell into the
    // same few cache sets and evicted each other: 16 x 16 copies a 4096^2 level about 10x faster.
    constexpr int kBlock = 16;
    const int w = image.width, h = image.height;
    parallelFor((h + kBlock - 1) / kBlock, threads, [&](int begin, int end) {
        for (int by = begin * kBlock; by < std::min(end * kBlock, h); by += kBlock) {
            const int y1 = std::min(by + kBlock, h);
            for (int bx = 0; bx < w; bx += kBlock)
                for (int x = bx; x < std::min(bx + kBlock, w); ++x) {
                    float* column = out.pixels.data() + size_t(x) * h;  // out's row x
                    for (int y = by; y < y1; ++y) column[y] = image.pixels[size_t(y) * w + x];
                }
        }
    });
    return out;
}

Image selectChannels(const Image& image, const std::vector<int>& channels) {
    Image out(image.width, image.height, static_cast<int>(channels.size()));
    for (size_t t = 0; t < image.texelCount(); ++t)
        for (size_t c = 0; c < channels.size(); ++c) {
            assert(channels[c] >= 0 && channels[c] < image.channels);
            out.pixels[t * channels.size() + c] = image.pixels[t * image.channels + channels[c]];
        }
    return out;
}

}  // namespace heightpack
