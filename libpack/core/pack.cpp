#include "heightpack/core/pack.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace heightpack {

void packNeighbour4Rows(const Image& level, Wrap wrap, int y0, int rows, float* dst) {
    assert(level.channels == 1 && y0 >= 0 && y0 + rows <= level.height);
    const int w = level.width;
    for (int y = y0; y < y0 + rows; ++y) {
        const float* row0 = level.row(y);
        const float* row1 = level.row(wrapIndex(y + 1, level.height, wrap));
        for (int x = 0; x < w; ++x) {
            const int x1 = wrapIndex(x + 1, w, wrap);
            dst[0] = row0[x];
            dst[1] = row0[x1];
            dst[2] = row1[x];
            dst[3] = row1[x1];
            dst += 4;
        }
    }
}

void packNeighbour4Run(const Image& level, Wrap wrap, int y, int x0, int count, int channel, float* dst) {
    assert(level.channels == 1 && channel >= 0 && channel < 4 && x0 >= 0 && count >= 0 && x0 + count <= level.width);
    const float* row = level.row(channel >= 2 ? wrapIndex(y + 1, level.height, wrap) : y);
    const int w = level.width, from = x0 + (channel & 1);  // G and A: the texel to the right
    const int inside = std::min(count, w - from);
    std::copy_n(row + from, inside, dst);
    if (inside < count) dst[inside] = row[wrapIndex(w, w, wrap)];  // only the last can step past the edge
}

Image packNeighbour4(const Image& level, Wrap wrap) {
    Image packed(level.width, level.height, 4);
    packNeighbour4Rows(level, wrap, 0, level.height, packed.pixels.data());
    return packed;
}

std::vector<Image> packMipChain(const std::vector<Image>& chain, Wrap wrap) {
    std::vector<Image> packed;
    packed.reserve(chain.size());
    for (const Image& level : chain) packed.push_back(packNeighbour4(level, wrap));
    return packed;
}

float samplePackedBilinear(const Image& packed, double u, double v, Wrap wrap) {
    assert(packed.channels == 4);
    if (!std::isfinite(u) || !std::isfinite(v)) return std::numeric_limits<float>::quiet_NaN();
    double px = u * packed.width - 0.5;
    double py = v * packed.height - 0.5;
    if (wrap == Wrap::Clamp) {
        px = std::clamp(px, 0.0, double(packed.width - 1));
        py = std::clamp(py, 0.0, double(packed.height - 1));
    }
    const double ix = std::floor(px), iy = std::floor(py);
    const double fx = px - ix, fy = py - iy;
    const int i = wrapIndex(static_cast<long long>(ix), packed.width, wrap);
    const int j = wrapIndex(static_cast<long long>(iy), packed.height, wrap);
    const float* t = packed.row(j) + static_cast<size_t>(i) * 4;
    // Listing 18-2: lerp along x in both rows, then along y.
    const double top = t[0] + (t[1] - t[0]) * fx;
    const double bottom = t[2] + (t[3] - t[2]) * fx;
    return static_cast<float>(top + (bottom - top) * fy);
}

float samplePackedTrilinear(const std::vector<Image>& packedChain, double u, double v, double lod, Wrap wrap,
                            const TrilinearBands& bands) {
    assert(!packedChain.empty() && bands.lower < bands.upper);
    const int last = static_cast<int>(packedChain.size()) - 1;
    lod = std::clamp(lod, 0.0, double(last));
    const int level = std::min(static_cast<int>(std::floor(lod)), last);
    const double fraction = lod - level;
    if (level == last || fraction < bands.lower) return samplePackedBilinear(packedChain[level], u, v, wrap);
    const float coarse = samplePackedBilinear(packedChain[level + 1], u, v, wrap);
    if (fraction > bands.upper) return coarse;
    const float fine = samplePackedBilinear(packedChain[level], u, v, wrap);
    const double t = (fraction - bands.lower) / (bands.upper - bands.lower);
    return static_cast<float>(fine + (coarse - fine) * t);
}

}  // namespace heightpack
