#include "heightpack/core/fresnel.hpp"

#include <algorithm>
#include <cmath>

namespace heightpack {

double fresnelReflectance(double cosTheta, double ior, FresnelModel model) {
    const double ci = std::clamp(cosTheta, 0.0, 1.0);
    if (model == FresnelModel::Schlick) {
        const double r0 = (ior - 1) / (ior + 1);
        return r0 * r0 + (1 - r0 * r0) * std::pow(1 - ci, 5);
    }
    // Snell: sin t = sin i / n; from air into a denser medium there is no total internal reflection.
    const double sinT2 = (1 - ci * ci) / (ior * ior);
    const double ct = std::sqrt(std::max(0.0, 1 - sinT2));
    const double rs = (ci - ior * ct) / (ci + ior * ct);
    const double rp = (ct - ior * ci) / (ct + ior * ci);
    return 0.5 * (rs * rs + rp * rp);
}

double rampCosine(int texel, int size, FresnelIndex index) {
    const double u = (texel + 0.5) / size;
    return index == FresnelIndex::NdotV ? u : 0.5 * u;
}

Image makeFresnelRamp(const FresnelOptions& options) {
    Image ramp(options.size, 1, 4);
    for (int i = 0; i < options.size; ++i) {
        const double c = rampCosine(i, options.size, options.index);
        for (int ch = 0; ch < 3; ++ch)
            ramp.at(i, 0, ch) = static_cast<float>(options.shallow[ch] + (options.deep[ch] - options.shallow[ch]) * c);
        ramp.at(i, 0, 3) = static_cast<float>(fresnelReflectance(c, options.ior, options.model));
    }
    return ramp;
}

std::array<float, 4> sampleRamp(const Image& ramp, double u) {
    const double p = std::clamp(u * ramp.width - 0.5, 0.0, double(ramp.width - 1));
    const int i = std::min(static_cast<int>(p), ramp.width - 1);
    const int j = std::min(i + 1, ramp.width - 1);
    const double f = p - i;
    std::array<float, 4> out{};
    for (int c = 0; c < 4; ++c)
        out[c] = static_cast<float>(ramp.at(i, 0, c) + (ramp.at(j, 0, c) - ramp.at(i, 0, c)) * f);
    return out;
}

}  // namespace heightpack
