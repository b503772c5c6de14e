#include "heightpack/core/normal.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

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

namespace {

// The slopes of a height image, a row at a time: computeSlopes keeps them all, the normals use each row
// as it is made (a 4096^2 level's slopes are 128 MB that are written once and read once).
class SlopeRows {
public:
    SlopeRows(const Image& heights, double texelX, double texelY, const NormalOptions& options)
        : heights_(heights), wrap_(options.wrap), tx_(differenceTaps(heights.width, options.wrap)),
          ty_(differenceTaps(heights.height, options.wrap)), scaleX_(options.heightRange / texelX),
          scaleY_(options.heightRange / texelY) {
        assert(heights.channels == 1);
        crossWeights(options.kernel, side_, centre_);
    }

    // Row y's slopes, x then y for each texel, into out (2 * width floats).
    void row(int y, float* out) const {
        const int w = heights_.width, h = heights_.height;
        // Across-direction neighbours (the smoothing taps) follow the wrap mode like every other tap.
        const float* rows[3] = {heights_.row(wrapIndex(y - 1, h, wrap_)), heights_.row(y), heights_.row(wrapIndex(y + 1, h, wrap_))};
        const float* up = heights_.row(ty_.minus[y]);
        const float* down = heights_.row(ty_.plus[y]);
        const double invY = ty_.inverseSpan[y];
        for (int x = 0; x < w; ++x) {
            const int xm = tx_.minus[x], xp = tx_.plus[x];
            double dx = centre_ * (double(rows[1][xp]) - rows[1][xm]);
            double dy = centre_ * (double(down[x]) - up[x]);
            if (side_ != 0.0) {
                const int xl = wrapIndex(x - 1, w, wrap_), xr = wrapIndex(x + 1, w, wrap_);
                dx += side_ * ((double(rows[0][xp]) - rows[0][xm]) + (double(rows[2][xp]) - rows[2][xm]));
                dy += side_ * ((double(down[xl]) - up[xl]) + (double(down[xr]) - up[xr]));
            }
            out[2 * x] = static_cast<float>(dx * tx_.inverseSpan[x] * scaleX_);
            out[2 * x + 1] = static_cast<float>(dy * invY * scaleY_);
        }
    }

private:
    const Image& heights_;
    Wrap wrap_;
    DifferenceTaps tx_, ty_;
    double scaleX_, scaleY_;
    double side_ = 0.0, centre_ = 1.0;
};

}  // namespace

Image computeSlopes(const Image& heights, double texelX, double texelY, const NormalOptions& options) {
    const SlopeRows slopeRows(heights, texelX, texelY, options);
    Image slopes(heights.width, heights.height, 2);
    parallelFor(heights.height, options.threads, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) slopeRows.row(y, slopes.row(y));
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
    const SlopeRows slopeRows(heights, texelX, texelY, options);
    const int channels = options.alpha == NormalAlpha::None ? 3 : 4;
    Image normals(heights.width, heights.height, channels);
    // The surface z = h(x, y) has normal (-dh/dx, -dh/dy_up, 1). Rows run down the image, so the slope
    // toward the top is -dh/dy_down: OpenGL's green is +dh/dy_down; DirectX negates it.
    const double green = options.convention == NormalConvention::OpenGL ? 1.0 : -1.0;
    parallelFor(heights.height, options.threads, [&](int y0, int y1) {
        std::vector<float> slopes(2 * size_t(heights.width));
        for (int y = y0; y < y1; ++y) {
            slopeRows.row(y, slopes.data());
            for (int x = 0; x < heights.width; ++x) {
                const size_t i = size_t(y) * size_t(heights.width) + size_t(x);
                const double sx = slopes[2 * size_t(x)], sy = slopes[2 * size_t(x) + 1];
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
