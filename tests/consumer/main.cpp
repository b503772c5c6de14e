// Packs a 4x4 ramp through the installed library and checks one packed texel.
#include <heightpack/core/mip.hpp>
#include <heightpack/core/pack.hpp>
#include <heightpack/version.hpp>

#include <cstdio>

int main() {
    heightpack::Image ramp(4, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) ramp.at(x, y) = float(x + 4 * y);
    const auto chain = heightpack::generateMipChain(ramp, heightpack::Filter::Box);
    const auto packed = heightpack::packNeighbour4(chain[0], heightpack::Wrap::Periodic);
    // Texel (3,3) wraps to (0,3), (3,0) and (0,0): 15, 12, 3, 0.
    const bool ok = chain.size() == 3 && packed.at(3, 3, 0) == 15 && packed.at(3, 3, 1) == 12 &&
                    packed.at(3, 3, 2) == 3 && packed.at(3, 3, 3) == 0;
    std::printf("heightpack %s consumer: %s\n", heightpack::kVersion, ok ? "ok" : "WRONG");
    return ok ? 0 : 1;
}
