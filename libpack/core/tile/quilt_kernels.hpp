// Internal: the search and the cut of the quilting (tile/quilt.cpp), apart so tests can check them against
// brute force.
#pragma once

#include <vector>

#include "field.hpp"

namespace heightpack::detail {

// For every shift (dx, dy), the sum over texels p of mask(p) (target(p) - source(p + shift))^2, indices
// wrapped: a field of the source's size indexed by the shift. Three correlations, one inverse DFT: the
// sums of mask target^2 (a constant), of mask target times the shifted source and of mask times the shifted
// source squared. All three fields of one size.
Field maskedSquaredErrors(Field target, Field mask, Field source, int threads);

// The path through a cost array of `length` lines of `width` places each (cost[line * width + place]) that
// takes one place per line, moving at most one place between neighbouring lines, with the least total
// cost (dynamic programming); ties go to the path that stays, then to the smaller place. Returns the
// place per line.
std::vector<int> minimalCut(const std::vector<double>& cost, int width, int length);

}  // namespace heightpack::detail
