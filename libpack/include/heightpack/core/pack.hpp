// 4-neighbour packing (GPU Gems 2, ch. 18.2.4) and the CPU mirror of the vertex shader's lookups.
#pragma once

#include <vector>

#include "heightpack/core/image.hpp"

namespace heightpack {

// Packs a one-channel level into four channels: texel (i, j) holds R = H(i, j), G = H(i+1, j),
// B = H(i, j+1), A = H(i+1, j+1), indices brought into the level with the wrap mode. One nearest fetch
// then carries everything a bilinear lookup needs.
Image packNeighbour4(const Image& level, Wrap wrap);

// The same for `rows` rows starting at y0, written to dst as rows * width RGBA texels. Lets a writer pack
// a band at a time instead of holding the whole packed chain in memory.
void packNeighbour4Rows(const Image& level, Wrap wrap, int y0, int rows, float* dst);

// One channel of one packed row alone: `count` values of channel `channel` (0 R, 1 G, 2 B, 3 A) of row y
// from texel x0 (x0 + count <= width), as packNeighbour4Rows puts them at dst[4 x + channel]. A channel
// of a row is a run of the level's row y or y + 1 from x0 or x0 + 1, so it is a copy: a writer that lays
// the channels of a row apart (EXR tiles) takes them so, with no RGBA band between.
void packNeighbour4Run(const Image& level, Wrap wrap, int y, int x0, int count, int channel, float* dst);

std::vector<Image> packMipChain(const std::vector<Image>& chain, Wrap wrap);

// Bilinear height at texture coordinate (u, v) from one packed level, as the viewer's vertex shader does
// it (Listing 18-2): p = uv * size - 0.5, one nearest fetch at floor(p), two lerps by frac(p). With Clamp,
// p is first clamped to [0, size - 1] so the result equals clamp-to-edge bilinear filtering outside the
// map (the packed G/B/A of the edge texel alone cannot express that). Equals hardware bilinear filtering
// of the plain level with the same wrap.
float samplePackedBilinear(const Image& packed, double u, double v, Wrap wrap);

// Where Listing 18-3 blends two levels: below `lower` of the fractional LOD it uses the finer level
// alone, above `upper` the coarser alone, and in between a linear blend, saving a fetch in most places.
struct TrilinearBands {
    double lower = 0.3;
    double upper = 0.7;
};

// Trilinear height at (u, v) and level of detail `lod` (clamped to the chain) from a packed chain, with
// the snapped bands of Listing 18-3. The result is continuous in lod.
float samplePackedTrilinear(const std::vector<Image>& packedChain, double u, double v, double lod, Wrap wrap,
                            const TrilinearBands& bands = {});

}  // namespace heightpack
