// Making a map tile by quilting: the band around each wrap line replaced by a strip of the map copied from
// where it best continues both sides, cut in along the least visible paths and healed in the gradient
// domain. For maps a Gaussian field does not describe (pebbles, cells, painted strokes, sharp rock), whose
// structure the band re-synthesis (tile/resynthesis.hpp) turns into blur.
#pragma once

#include "heightpack/core/image.hpp"

namespace heightpack {

struct QuiltOptions {
    // Width of the strip changed across each wrap line (the copied core and an overlap of a quarter of it
    // on each side), as a fraction of the tile across it; 0 chooses 1/8. At least 8 texels, at most half
    // the tile.
    double band = 0.0;
    // Which source: 0 the best match, 1 the best one not within half a strip of it, and so on (for each
    // wrap line).
    int match = 0;
    // The map's height step (1/255 for 8 bits, 1/65535 for 16, 0 for float): a map recognised as an
    // enlargement of a smaller one (resized 2x to 16x) is quilted at that one's size and enlarged back.
    double quantum = 0.0;
    bool atSourceSize = true;  // false: an enlarged map quilted at its own size all the same
    int threads = 0;  // 0 = all cores; the result does not depend on it
};

struct QuiltResult {
    Image map;
    int bandX = 0;  // texels changed across the left/right wrap line (a vertical strip)
    int bandY = 0;  // texels changed across the top/bottom wrap line
    int enlargement = 1;  // the factor of the source it was quilted at; 1: at its own size
    // Where each strip was copied from: the offset from a texel to its source, in texels.
    int sourceX[2] = {0, 0};  // the left/right strip's (dx, dy)
    int sourceY[2] = {0, 0};  // the top/bottom strip's (dx, dy)
};

// For the left/right wrap line, then the top/bottom one (by then the map wraps left to right):
//   1. the strip: `band` texels centred on the wrap line; its two outer quarters are overlaps;
//   2. the source: the shift whose copy of the map matches the overlaps best by the sum of squared
//      differences, for every shift at once by FFT cross-correlation; only shifts whose copy is one
//      piece of the map (crossing none of its own seams that would stay visible) count;
//   3. the cut: in each overlap, the path along the wrap line where the map and the copy differ least
//      visibly (the squared gradient of their difference, plus the squared difference over the overlap's
//      width squared; dynamic programming, one place per line, moving at most one texel between lines);
//      the copy lies between the two paths, the map beyond them;
//   4. the healing, in the gradient domain: the result whose steps are closest (least squares, periodic
//      Poisson on the whole torus) to the map's steps beyond the paths and the copy's between them,
//      blended over half an overlap across each path. It changes the map beyond the strips by a harmonic
//      field (smooth: no line where a strip ends), which makes the steps across the paths continuous.
// Before the strips, Moisan's smooth field of a low-pass of the map (1/16 of the tile) is taken off, as the
// re-synthesis does, so the strips need not bridge a large-scale mismatch (a slope across a terrain); so
// beyond the strips the map changes by two harmonic fields alone. Values that would pass the map's own
// extremes are eased into the last 2% of its range. Deterministic: the same map and options give the same
// bytes whatever the thread count. Maps smaller than 16 texels on a side get Moisan's periodic component.
QuiltResult quiltTile(const Image& map, const QuiltOptions& options = {});

}  // namespace heightpack
