// The packer and the CPU lookup through heightpack::core alone: a plane h = a + b u + c v, packed, must
// be sampled back exactly (bilinear interpolation reproduces a plane) at points between texels.
#include <heightpack/core/mip.hpp>
#include <heightpack/core/pack.hpp>
#include <heightpack/version.hpp>

#include <cmath>
#include <cstdio>

int main() {
    const int n = 16;
    auto plane = [](double u, double v) { return 0.25 + 0.5 * u + 0.125 * v; };
    heightpack::Image level(n, n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) level.at(x, y) = float(plane((x + 0.5) / n, (y + 0.5) / n));
    const auto chain = heightpack::generateMipChain(level, heightpack::Filter::Box);
    const auto packed = heightpack::packMipChain(chain, heightpack::Wrap::Clamp);
    double worst = 0.0;
    // Inside the texel centres, where clamping plays no part.
    for (int i = 0; i < 200; ++i) {
        const double u = (0.5 + (n - 1) * (i * 0.618034 - std::floor(i * 0.618034))) / n;
        const double v = (0.5 + (n - 1) * (i * 0.414214 - std::floor(i * 0.414214))) / n;
        const double h = heightpack::samplePackedBilinear(packed[0], u, v, heightpack::Wrap::Clamp);
        worst = std::max(worst, std::abs(h - plane(u, v)));
    }
    const bool ok = chain.size() == 5 && packed.size() == 5 && worst < 1e-6;
    std::printf("heightpack %s core consumer: worst error %.2g: %s\n", heightpack::kVersion, worst, ok ? "ok" : "WRONG");
    return ok ? 0 : 1;
}
