#include "heightpack/core/normal.hpp"

#include <algorithm>
#include <cmath>

#include "heightpack/core/parallel.hpp"

namespace heightpack {

double texelWidth(const NormalOptions& options, int level0Width, int levelWidth) {
    (void)level0Width;
    return options.tileWidth / levelWidth;
}

double texelHeight(const NormalOptions& options, int level0Width, int level0Height, int levelHeight) {
    // Square texels unless the tile's height in metres is given.
    const double tileHeight = options.tileHeight > 0 ? options.tileHeight : options.tileWidth * level0Height / level0Width;
    return tileHeight / levelHeight;
}

namespace {

// Where the slope at index i along one axis takes its difference: h[plus] - h[minus] over `span` texels.
// Periodic: the neighbours wrap. Clamp: at the border the one-sided difference over one texel, a real
// slope, not the half slope that repeating the edge texel would fake. A one-texel axis is flat.
struct DifferenceTaps {
    std::vector<int> minus, plus;
    std::vector<double> inverseSpan;  // 1 / (span in texels)
};

DifferenceTaps differenceTaps(int size, Wrap wrap) {
    DifferenceTaps taps;
    for (int i = 0; i < size; ++i) {
        int lo = wrapIndex(i - 1, size, wrap), hi = wrapIndex(i + 1, size, wrap);
        if (wrap == Wrap::Clamp) {
            lo = std::max(0, i - 1);
            hi = std::min(size - 1, i + 1);
        }
        const int span = size == 1 ? 1 : (wrap == Wrap::Clamp ? hi - lo : 2);
        taps.minus.push_back(lo);
        taps.plus.push_back(hi);
        taps.inverseSpan.push_back(1.0 / span);
    }
    return taps;
}

// Weights across the derivative direction: (side, centre, side), summing to one.
void crossWeights(SlopeKernel kernel, double& side, double& centre) {
    switch (kernel) {
        case SlopeKernel::Central: side = 0.0; centre = 1.0; return;
        case SlopeKernel::Sobel3: side = 1.0 / 4; centre = 2.0 / 4; return;
        case SlopeKernel::Scharr: side = 3.0 / 16; centre = 10.0 / 16; return;
    }
}

}  // namespace

Image computeSlopes(const Image& heights, double texelX, double texelY, const NormalOptions& options) {
    assert(heights.channels == 1);
    const int w = heights.width, h = heights.height;
    Image slopes(w, h, 2);
    double side = 0, centre = 1;
    crossWeights(options.kernel, side, centre);
    const Wrap wrap = options.wrap;
    const DifferenceTaps tx = differenceTaps(w, wrap), ty = differenceTaps(h, wrap);
    // Across-direction neighbours (the smoothing taps) follow the wrap mode like every other tap.
    const double scaleX = options.heightRange / texelX, scaleY = options.heightRange / texelY;
    parallelFor(h, options.threads, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
            const float* rows[3] = {heights.row(wrapIndex(y - 1, h, wrap)), heights.row(y),
                                    heights.row(wrapIndex(y + 1, h, wrap))};
            const float* up = heights.row(ty.minus[y]);
            const float* down = heights.row(ty.plus[y]);
            const double invY = ty.inverseSpan[y];
            float* out = slopes.row(y);
            for (int x = 0; x < w; ++x) {
                const int xm = tx.minus[x], xp = tx.plus[x];
                double dx = centre * (double(rows[1][xp]) - rows[1][xm]);
                double dy = centre * (double(down[x]) - up[x]);
                if (side != 0.0) {
                    const int xl = wrapIndex(x - 1, w, wrap), xr = wrapIndex(x + 1, w, wrap);
                    dx += side * ((double(rows[0][xp]) - rows[0][xm]) + (double(rows[2][xp]) - rows[2][xm]));
                    dy += side * ((double(down[xl]) - up[xl]) + (double(down[xr]) - up[xr]));
                }
                out[2 * x] = static_cast<float>(dx * tx.inverseSpan[x] * scaleX);
                out[2 * x + 1] = static_cast<float>(dy * invY * scaleY);
            }
        }
    });
    return slopes;
}

Image slopeMoment(const Image& heights, double texelX, double texelY, const NormalOptions& options) {
    const Image slopes = computeSlopes(heights, texelX, texelY, options);
    Image moment(heights.width, heights.height, 1);
    for (size_t i = 0; i < moment.pixels.size(); ++i) {
        const double sx = slopes.pixels[2 * i], sy = slopes.pixels[2 * i + 1];
        moment.pixels[i] = static_cast<float>(sx * sx + sy * sy);
    }
    return moment;
}

namespace {

Image normalsWithAlpha(const Image& heights, double texelX, double texelY, const NormalOptions& options,
                       const Image* moment) {
    const Image slopes = computeSlopes(heights, texelX, texelY, options);
    const int channels = options.alpha == NormalAlpha::None ? 3 : 4;
    Image normals(heights.width, heights.height, channels);
    // The surface z = h(x, y) has normal (-dh/dx, -dh/dy_up, 1). Rows run down the image, so the slope
    // toward the top is -dh/dy_down: OpenGL's green is +dh/dy_down; DirectX negates it.
    const double green = options.convention == NormalConvention::OpenGL ? 1.0 : -1.0;
    parallelFor(heights.height, options.threads, [&](int y0, int y1) {
        const size_t end = size_t(y1) * heights.width;
        for (size_t i = size_t(y0) * heights.width; i < end; ++i) {
            const double sx = slopes.pixels[2 * i], sy = slopes.pixels[2 * i + 1];
            const double inv = 1.0 / std::sqrt(sx * sx + sy * sy + 1.0);
            float* n = &normals.pixels[i * channels];
            n[0] = static_cast<float>(-sx * inv);
            n[1] = static_cast<float>(green * sy * inv);
            n[2] = static_cast<float>(inv);
            if (options.alpha == NormalAlpha::Height) n[3] = heights.pixels[i];
            if (options.alpha == NormalAlpha::SlopeVariance)
                n[3] = moment ? static_cast<float>(std::max(0.0, double(moment->pixels[i]) - (sx * sx + sy * sy)))
                              : 0.0f;
        }
    });
    return normals;
}

}  // namespace

Image normalsFromHeights(const Image& heights, double texelX, double texelY, const NormalOptions& options) {
    return normalsWithAlpha(heights, texelX, texelY, options, nullptr);
}

std::vector<Image> generateNormalChain(const std::vector<Image>& heightChain, const NormalOptions& options,
                                       const std::vector<Image>& slopeMomentChain) {
    assert(!heightChain.empty());
    assert(options.alpha != NormalAlpha::SlopeVariance || slopeMomentChain.size() == heightChain.size());
    const int w0 = heightChain[0].width, h0 = heightChain[0].height;
    std::vector<Image> chain;
    chain.reserve(heightChain.size());
    for (size_t level = 0; level < heightChain.size(); ++level) {
        const Image& h = heightChain[level];
        const Image* moment = options.alpha == NormalAlpha::SlopeVariance ? &slopeMomentChain[level] : nullptr;
        chain.push_back(normalsWithAlpha(h, texelWidth(options, w0, h.width), texelHeight(options, w0, h0, h.height),
                                         options, moment));
    }
    return chain;
}

}  // namespace heightpack
