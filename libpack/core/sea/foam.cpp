#include "heightpack/core/sea/foam.hpp"

#include <cassert>
#include <cmath>

#include "heightpack/core/parallel.hpp"

namespace heightpack {

void advanceFoam(std::vector<float>& density, const Image& jacobian, double dt, const FoamOptions& o) {
    assert(density.size() == jacobian.texelCount() && jacobian.channels == 1);
    const double q = std::exp(-dt / o.decay);
    const double gain = o.buildUp * o.decay * (1.0 - q);
    for (size_t i = 0; i < density.size(); ++i) {
        const double below = o.threshold - double(jacobian.pixels[i]);
        density[i] = static_cast<float>(q * density[i] + (below > 0.0 ? gain * below : 0.0));
    }
}

float frozenFoamDensity(float jacobian, const FoamOptions& o) {
    return static_cast<float>(o.buildUp * o.decay * std::fmax(0.0, o.threshold - jacobian));
}

float foamCoverageOf(float density) {
    // Most of a sea has no foam: no exponential to take there (-expm1(-0) is +0 all the same).
    return density == 0.0f ? 0.0f : static_cast<float>(-std::expm1(-double(density)));
}

Image foamCoverage(const std::vector<float>& density, int width, int height, int threads) {
    assert(density.size() == size_t(width) * height);
    Image out(width, height, 1);
    parallelFor(height, threads, [&](int y0, int y1) {
        for (size_t i = size_t(y0) * width; i < size_t(y1) * width; ++i)
            out.pixels[i] = foamCoverageOf(density[i]);
    });
    return out;
}

std::vector<std::vector<float>> loopingFoamDensity(const std::vector<Image>& jacobians, double period,
                                                   const FoamOptions& o) {
    const size_t frames = jacobians.size();
    assert(frames > 0);
    const size_t texels = jacobians[0].texelCount();
    std::vector<std::vector<float>> out;
    if (frames == 1 || period <= 0.0) {
        // Frozen: the fixed point of advanceFoam for any dt.
        for (const Image& j : jacobians) {
            std::vector<float> d(texels, 0.0f);
            for (size_t i = 0; i < texels; ++i) d[i] = frozenFoamDensity(j.pixels[i], o);
            out.push_back(std::move(d));
        }
        return out;
    }
    const double dt = period / double(frames);
    // The warm-up: one period from nothing, ending just before frame 0 (after frame F-1 of the period before).
    std::vector<double> warm(texels, 0.0);
    const double q = std::exp(-dt / o.decay), gain = o.buildUp * o.decay * (1.0 - q);
    for (const Image& j : jacobians)
        for (size_t i = 0; i < texels; ++i) warm[i] = q * warm[i] + gain * std::fmax(0.0, o.threshold - j.pixels[i]);
    // What one period leaves of a start is exp(-period / decay) of it: the periodic state is the warm-up's
    // sum of a geometric series. In double, so frame F returns to frame 0 to float rounding.
    const double keep = std::exp(-period / o.decay);
    for (double& w : warm) w /= 1.0 - keep;
    for (const Image& j : jacobians) {
        std::vector<float> d(texels);
        for (size_t i = 0; i < texels; ++i) {
            warm[i] = q * warm[i] + gain * std::fmax(0.0, o.threshold - j.pixels[i]);
            d[i] = static_cast<float>(warm[i]);
        }
        out.push_back(std::move(d));
    }
    return out;
}

}  // namespace heightpack
