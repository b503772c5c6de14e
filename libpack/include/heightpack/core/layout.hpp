// How a texture arranges what it stores in its channels: the choice between one fetch per bilinear
// lookup (neighbour4), a quarter of the memory (plain, for textureGather or hardware filtering), and for
// normal maps three channels or two (z rebuilt in the shader).
#pragma once

#include "heightpack/core/names.hpp"

namespace heightpack {

enum class Layout {
    Neighbour4,  // heights: R, G, B, A = H(i,j), H(i+1,j), H(i,j+1), H(i+1,j+1) (pack.hpp)
    Plain,       // heights: one channel, the height itself
    Rgb,         // normals: unit x, y, z
    Xy,          // normals: x and y; the shader rebuilds z = sqrt(1 - x^2 - y^2)
};
template <>
struct NameTable<Layout> {
    static constexpr EnumName<Layout> entries[] = {
        {Layout::Neighbour4, "neighbour4", "each texel holds its height and its three neighbours': one fetch per lookup"},
        {Layout::Plain, "plain", "one channel, the height itself: textureGather or hardware bilinear filtering"},
        {Layout::Rgb, "rgb", "normal x, y, z in three channels"},
        {Layout::Xy, "xy", "normal x and y in two channels; the shader rebuilds z"},
    };
};

// Whether a layout holds heights (neighbour4, plain) rather than normals (rgb, xy).
constexpr bool isHeightLayout(Layout layout) { return layout == Layout::Neighbour4 || layout == Layout::Plain; }

// The channels a texel of the layout has (a normal map's alpha, when it has one, comes on top of rgb).
constexpr int layoutChannels(Layout layout) {
    switch (layout) {
        case Layout::Neighbour4: return 4;
        case Layout::Plain: return 1;
        case Layout::Rgb: return 3;
        case Layout::Xy: return 2;
    }
    return 4;
}

}  // namespace heightpack
