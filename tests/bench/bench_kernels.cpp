// Google Benchmark timings of libpack's kernels on a 2048x2048 map, and of the sea's inverse DFT (synth's
// one transform a field) at 4096x4096.
#include <benchmark/benchmark.h>

#include <complex>
#include <random>
#include <vector>

#include "dft.hpp"

#include "heightpack/core/mip.hpp"
#include "heightpack/core/pack.hpp"
#include "heightpack/io/read.hpp"

using namespace heightpack;

namespace {

const Image& map2048() {
    static const Image image = [] {
        Image img(2048, 2048);
        std::mt19937 rng(1);
        std::uniform_real_distribution<float> d(0, 1);
        for (float& v : img.pixels) v = d(rng);
        return img;
    }();
    return image;
}

void BM_MipChain(benchmark::State& state) {
    MipOptions options;
    options.filter = static_cast<Filter>(state.range(0));
    options.threads = static_cast<int>(state.range(1));
    for (auto _ : state) benchmark::DoNotOptimize(generateMipChain(map2048(), options));
    state.SetLabel(std::string(filterName(options.filter)) + ", threads " + std::to_string(options.threads));
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(map2048().pixels.size() * sizeof(float)));
}
BENCHMARK(BM_MipChain)->ArgsProduct({{0, 1, 2, 3}, {1, 2}})->Unit(benchmark::kMillisecond);

void BM_Pack(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(packNeighbour4(map2048(), Wrap::Periodic));
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(map2048().pixels.size() * sizeof(float) * 4));
}
BENCHMARK(BM_Pack)->Unit(benchmark::kMillisecond);

void BM_Hash(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(hashPixels(map2048()));
    state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(map2048().pixels.size() * sizeof(float)));
}
BENCHMARK(BM_Hash)->Unit(benchmark::kMillisecond);

}  // namespace

// One real 4096^2 field from its half spectrum, in float, on state.range(0) threads: synth's floor is
// start-up + this + writing the file. The spectrum is refilled each time (the transform overwrites it).
void BM_SeaInverseDft(benchmark::State& state) {
    const int n = 4096, threads = int(state.range(0));
    std::vector<std::complex<float>> spectrum(size_t(n) * (n / 2 + 1)), scratch(spectrum.size());
    std::mt19937 rng(1);
    std::normal_distribution<float> d;
    for (auto& z : spectrum) z = {d(rng), d(rng)};
    std::vector<float> field(size_t(n) * n);
    for (auto _ : state) {
        scratch = spectrum;
        detail::inverseRealDftOfHalf(scratch.data(), n, n, threads,
                                     [&](int y, const float* row) { std::copy(row, row + n, field.begin() + size_t(y) * n); });
        benchmark::DoNotOptimize(field.data());
    }
}
BENCHMARK(BM_SeaInverseDft)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
