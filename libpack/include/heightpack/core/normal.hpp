// Tangent-space normal maps from height maps, in world units, with the wrap mode honoured by every tap.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "heightpack/core/image.hpp"

namespace heightpack {

// How the slope at a texel is measured. Each kernel is scaled so a plane of slope s measures exactly s.
enum class SlopeKernel {
    Central,  // (h[x+1] - h[x-1]) / 2dx
    Sobel3,   // central difference smoothed across by (1 2 1) / 4
    Scharr,   // central difference smoothed across by (3 10 3) / 16
};
template <>
struct NameTable<SlopeKernel> {
    static constexpr EnumName<SlopeKernel> entries[] = {
        {SlopeKernel::Central, "central", "central difference"},
        {SlopeKernel::Sobel3, "sobel3", "central difference smoothed across by (1 2 1) / 4"},
        {SlopeKernel::Scharr, "scharr", "central difference smoothed across by (3 10 3) / 16"},
    };
};
inline const char* slopeKernelName(SlopeKernel kernel) { return nameOf(kernel); }

// Which way green points. OpenGL: +y toward the top of the image as stored (row 0); DirectX: toward the
// bottom (green negated).
enum class NormalConvention { OpenGL, DirectX };
template <>
struct NameTable<NormalConvention> {
    static constexpr EnumName<NormalConvention> entries[] = {
        {NormalConvention::OpenGL, "opengl", "green points toward the top of the stored image"},
        {NormalConvention::DirectX, "directx", "green flipped"},
    };
};

// What the fourth channel holds, if any.
enum class NormalAlpha {
    None,
    Height,    // the painted height in [0,1], as the D3D11 demo stores it
    SlopeVariance,  // slope variance lost by filtering to this level (Toksvig-style): E[|s|^2] - |E[s]|^2
};
template <>
struct NameTable<NormalAlpha> {
    static constexpr EnumName<NormalAlpha> entries[] = {
        {NormalAlpha::None, "none", "three channels"},
        {NormalAlpha::Height, "height", "alpha holds the painted height"},
        {NormalAlpha::SlopeVariance, "variance", "alpha holds the slope variance lost by filtering"},
    };
};

struct NormalOptions {
    double tileWidth = 1.0;    // metres across the map's width
    double tileHeight = 0.0;   // metres across its height; 0 = square texels
    double heightRange = 1.0;  // metres between a stored 0.0 and a stored 1.0
    SlopeKernel kernel = SlopeKernel::Central;
    Wrap wrap = Wrap::Periodic;
    NormalConvention convention = NormalConvention::OpenGL;
    NormalAlpha alpha = NormalAlpha::None;
    int threads = 0;  // 0 = all cores; the result does not depend on it
};

// The slope of the height field at every texel, in metres per metre: channel 0 is dh/dx along +column,
// channel 1 dh/dy along +row (downward in the stored image). texelX and texelY are a texel's size in
// metres; heights are stored values times heightRange. Clamp uses one-sided differences at the border.
Image computeSlopes(const Image& heights, double texelX, double texelY, const NormalOptions& options);

// Unit normals (x, y, z; z up) of one level with the given texel size, in the options' convention.
// Three channels, or four when options.alpha is Height (alpha = the stored height).
Image normalsFromHeights(const Image& heights, double texelX, double texelY, const NormalOptions& options);

// The normal of every level of a height mip chain (see generateMipChain), each computed from that
// level's heights with that level's texel size: tileWidth / levelWidth. Not averaged normals, which
// flatten too little. With NormalAlpha::SlopeVariance, slopeMomentChain must be the chain of |slope|^2 of
// level 0 filtered like the heights (see slopeMoment); alpha is then max(0, moment - |slope|^2).
std::vector<Image> generateNormalChain(const std::vector<Image>& heightChain, const NormalOptions& options,
                                       const std::vector<Image>& slopeMomentChain = {});

// |slope|^2 at every texel of level 0, the quantity whose filtered chain gives the lost variance.
Image slopeMoment(const Image& heights, double texelX, double texelY, const NormalOptions& options);

// The size of one texel of a level, in metres, from the map's size and the options.
double texelWidth(const NormalOptions& options, int level0Width, int levelWidth);
double texelHeight(const NormalOptions& options, int level0Width, int level0Height, int levelHeight);

}  // namespace heightpack
