#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "heightpack/core/mip.hpp"
#include "heightpack/core/normal.hpp"

#include "support/test_support.hpp"

using namespace heightpack;
using heightpack::test::makeImage;

namespace {

double angleDegrees(const double a[3], const double b[3]) {
    const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const double na = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    const double nb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    return std::acos(std::clamp(dot / (na * nb), -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

// h(x, y) = a sin(2 pi x / L) cos(2 pi y / L) metres over a tile of T metres, y along rows (down).
struct SineField {
    double tile = 8.0, wavelength = 2.0, amplitude = 0.1;
    double heightRange() const { return 2 * amplitude; }  // stored 0..1 spans -a..a
    double stored(double x, double y) const {
        return 0.5 + 0.5 * std::sin(2 * std::numbers::pi * x / wavelength) * std::cos(2 * std::numbers::pi * y / wavelength);
    }
    // The analytic OpenGL normal: (-dh/dx, +dh/dy_down, 1), normalised later.
    void normal(double x, double y, double n[3]) const {
        const double k = 2 * std::numbers::pi / wavelength;
        const double hx = amplitude * k * std::cos(k * x) * std::cos(k * y);
        const double hy = -amplitude * k * std::sin(k * x) * std::sin(k * y);
        n[0] = -hx;
        n[1] = hy;
        n[2] = 1.0;
    }
};

NormalOptions optionsFor(const SineField& f) {
    NormalOptions o;
    o.tileWidth = f.tile;
    o.heightRange = f.heightRange();
    return o;
}

}  // namespace

TEST(Normal, MatchesTheAnalyticNormalsOfASineFieldAtEveryResolvedLevel) {
    const SineField field;
    const int size = 512;
    const Image heights = makeImage(size, size, [&](int i, int j) {
        const double t = field.tile / size;
        return static_cast<float>(field.stored((i + 0.5) * t, (j + 0.5) * t));
    });
    const auto heightChain = generateMipChain(heights, Filter::Kaiser);
    const NormalOptions options = optionsFor(field);
    const auto chain = generateNormalChain(heightChain, options);
    ASSERT_EQ(chain.size(), heightChain.size());
    int checked = 0;
    for (size_t level = 0; level < chain.size(); ++level) {
        const Image& n = chain[level];
        const double texel = field.tile / n.width;
        if (texel >= field.wavelength / 8) break;  // only levels whose texel is smaller than L/8
        std::vector<double> errors;
        for (int j = 0; j < n.height; ++j) {
            for (int i = 0; i < n.width; ++i) {
                double expected[3];
                field.normal((i + 0.5) * texel, (j + 0.5) * texel, expected);
                const double got[3] = {n.at(i, j, 0), n.at(i, j, 1), n.at(i, j, 2)};
                errors.push_back(angleDegrees(got, expected));
            }
        }
        const double limit = level == 0 ? 0.2 : 1.0;
        EXPECT_LT(median(errors), limit) << "level " << level << " (" << n.width << " texels)";
        ++checked;
    }
    EXPECT_EQ(checked, 4);  // 512, 256, 128 and 64 texels across: 128 down to 16 texels a wavelength
}

TEST(Normal, EveryKernelMeasuresAPlanesSlopeExactly) {
    // h = 0.3 x + 0.1 y metres (y down the rows) over an 8 m x 4 m tile; clamped, so every border texel
    // must measure the plane too (one-sided differences), not half its slope.
    const int w = 32, h = 16;
    NormalOptions o;
    o.tileWidth = 8.0;
    o.heightRange = 10.0;
    o.wrap = Wrap::Clamp;
    const double texel = o.tileWidth / w;
    const Image plane = makeImage(w, h, [&](int i, int j) {
        return static_cast<float>((0.3 * (i + 0.5) * texel + 0.1 * (j + 0.5) * texel) / o.heightRange);
    });
    for (SlopeKernel kernel : {SlopeKernel::Central, SlopeKernel::Sobel3, SlopeKernel::Scharr}) {
        o.kernel = kernel;
        const Image slopes = computeSlopes(plane, texel, texel, o);
        for (int j = 0; j < h; ++j) {
            for (int i = 0; i < w; ++i) {
                ASSERT_NEAR(slopes.at(i, j, 0), 0.3, 1e-5) << slopeKernelName(kernel) << " " << i << "," << j;
                ASSERT_NEAR(slopes.at(i, j, 1), 0.1, 1e-5) << slopeKernelName(kernel) << " " << i << "," << j;
            }
        }
        const Image n = normalsFromHeights(plane, texel, texel, o);
        const double len = std::sqrt(0.3 * 0.3 + 0.1 * 0.1 + 1.0);
        EXPECT_NEAR(n.at(5, 5, 0), -0.3 / len, 1e-6);
        EXPECT_NEAR(n.at(5, 5, 1), 0.1 / len, 1e-6);
        EXPECT_NEAR(n.at(5, 5, 2), 1.0 / len, 1e-6);
    }
}

TEST(Normal, PeriodicNormalMapHasNoSeam) {
    // A smooth periodic field with several waves. Shift invariance: the normals of the field rolled by
    // (dx, dy) are the rolled normals, so the tile edge is like any other place; and the angle between
    // neighbours across the edge is distributed like the angle between interior neighbours.
    const int w = 128, h = 64;
    auto field = [&](int i, int j, int dx, int dy) {
        const double x = double(((i - dx) % w + w) % w) / w, y = double(((j - dy) % h + h) % h) / h;
        return static_cast<float>(0.5 + 0.2 * std::sin(2 * std::numbers::pi * (3 * x + 2 * y) + 0.3) +
                                  0.1 * std::cos(2 * std::numbers::pi * (5 * x - 4 * y) + 1.1) + 0.05 * std::sin(2 * std::numbers::pi * 9 * y));
    };
    NormalOptions o;
    o.tileWidth = 4.0;
    o.heightRange = 0.5;
    for (SlopeKernel kernel : {SlopeKernel::Central, SlopeKernel::Sobel3, SlopeKernel::Scharr}) {
        o.kernel = kernel;
        const double texel = o.tileWidth / w;
        const Image n = normalsFromHeights(makeImage(w, h, [&](int i, int j) { return field(i, j, 0, 0); }), texel, texel, o);
        const Image rolled =
            normalsFromHeights(makeImage(w, h, [&](int i, int j) { return field(i, j, 37, 11); }), texel, texel, o);
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i)
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(rolled.at((i + 37) % w, (j + 11) % h, c), n.at(i, j, c), 1e-6) << i << "," << j;

        auto angle = [&](int i0, int j0, int i1, int j1) {
            const double a[3] = {n.at(i0, j0, 0), n.at(i0, j0, 1), n.at(i0, j0, 2)};
            const double b[3] = {n.at(i1, j1, 0), n.at(i1, j1, 1), n.at(i1, j1, 2)};
            return angleDegrees(a, b);
        };
        std::vector<double> edge, interior;
        for (int j = 0; j < h; ++j) {
            edge.push_back(angle(w - 1, j, 0, j));
            for (int i = 0; i + 1 < w; ++i) interior.push_back(angle(i, j, i + 1, j));
        }
        auto mean = [](const std::vector<double>& v) {
            double s = 0;
            for (double x : v) s += x;
            return s / v.size();
        };
        EXPECT_NEAR(mean(edge), mean(interior), 0.15 * mean(interior)) << slopeKernelName(kernel);
        EXPECT_LT(*std::max_element(edge.begin(), edge.end()), *std::max_element(interior.begin(), interior.end()) * 1.01);
    }
}

TEST(Normal, DirectXIsOpenGLWithGreenNegated) {
    const Image heights = heightpack::test::randomImage(32, 16, 4);
    NormalOptions gl;
    gl.tileWidth = 2.0;
    gl.heightRange = 0.05;
    NormalOptions dx = gl;
    dx.convention = NormalConvention::DirectX;
    const Image a = normalsFromHeights(heights, 2.0 / 32, 2.0 / 32, gl);
    const Image b = normalsFromHeights(heights, 2.0 / 32, 2.0 / 32, dx);
    for (size_t i = 0; i < a.texelCount(); ++i) {
        ASSERT_EQ(b.pixels[3 * i], a.pixels[3 * i]);
        ASSERT_EQ(b.pixels[3 * i + 1], -a.pixels[3 * i + 1]);
        ASSERT_EQ(b.pixels[3 * i + 2], a.pixels[3 * i + 2]);
    }
}

TEST(Normal, VarianceInAlphaIsTheSlopeVarianceTheFilterRemoved) {
    // A long wave plus a short one, 4 texels long at level 0. From level 3 on (a texel spans two short
    // wavelengths) the filter has removed the short wave, so the variance lost is the short wave's mean
    // squared slope as level 0 measured it; level 0 loses nothing.
    const int size = 256;
    const double tile = 16.0, a2 = 0.01, l2 = tile / size * 4;  // metres
    NormalOptions o;
    o.tileWidth = tile;
    o.heightRange = 1.0;
    o.alpha = NormalAlpha::SlopeVariance;
    const Image heights = makeImage(size, size, [&](int i, int) {
        const double x = (i + 0.5) * tile / size;
        return static_cast<float>(0.5 + 0.2 * std::sin(2 * std::numbers::pi * x / tile) + a2 * std::sin(2 * std::numbers::pi * x / l2));
    });
    const auto heightChain = generateMipChain(heights, Filter::Kaiser);
    const auto moments = generateMipChain(slopeMoment(heights, tile / size, tile / size, o), Filter::Kaiser);
    const auto chain = generateNormalChain(heightChain, o, moments);
    // What level 0's central difference sees of the short wave: its slope a k, scaled by the difference's
    // response sin(k dx) / (k dx) (0.64 at four texels a wavelength), squared and averaged over a period.
    const double k = 2 * std::numbers::pi / l2, dx = tile / size;
    const double lost = std::pow(a2 * k * std::sin(k * dx) / (k * dx), 2) / 2;
    for (size_t i = 0; i < chain[0].texelCount(); ++i) ASSERT_NEAR(chain[0].pixels[4 * i + 3], 0.0f, 1e-6);
    for (size_t level = 3; level < 6; ++level) {
        double mean = 0;
        for (size_t i = 0; i < chain[level].texelCount(); ++i) mean += chain[level].pixels[4 * i + 3];
        mean /= chain[level].texelCount();
        EXPECT_NEAR(mean, lost, 0.1 * lost) << "level " << level;
    }
}

TEST(Normal, HeightInAlphaIsTheStoredHeight) {
    const Image heights = heightpack::test::randomImage(16, 16, 8);
    NormalOptions o;
    o.alpha = NormalAlpha::Height;
    const Image n = normalsFromHeights(heights, 0.1, 0.1, o);
    ASSERT_EQ(n.channels, 4);
    for (size_t i = 0; i < heights.texelCount(); ++i) ASSERT_EQ(n.pixels[4 * i + 3], heights.pixels[i]);
}

TEST(Normal, NonSquareMapsHaveSquareTexelsUnlessTold) {
    NormalOptions o;
    o.tileWidth = 8.0;
    EXPECT_DOUBLE_EQ(texelWidth(o, 64, 64), 0.125);
    EXPECT_DOUBLE_EQ(texelHeight(o, 64, 16, 16), 0.125);
    EXPECT_DOUBLE_EQ(texelHeight(o, 64, 16, 4), 0.5);
    o.tileHeight = 4.0;
    EXPECT_DOUBLE_EQ(texelHeight(o, 64, 16, 16), 0.25);
}
