// Internal: the kriging step of the band re-synthesis (tile/resynthesis.cpp): the lines around one wrap
// line replaced by a Gaussian model's sample conditioned on the lines beside them, solved per frequency
// along the lines (Galerne and Leclaire 2017, with the model's exact covariance between lines).
#pragma once

#include "gaussian_model.hpp"
#include "strip_field.hpp"

namespace heightpack::detail {

// Replaces the `band` columns (Axis::X; rows for Axis::Y) around the wrap line between the last and the
// first with the model's sample conditioned on `context` lines on each side, the field's mean being
// `mean`, `noise` the variance of the measurement noise (the nugget). The field must wrap along the lines,
// and keep them (bandLinesReach). Returns the sum of the changes. On `threads` threads (0 = all cores),
// with the same result on any number.
double resynthesiseLines(StripField& field, const GaussianModel& model, const StripField& sample, Axis axis, int band, int context,
                         double noise, double mean, int threads);

// How far from a wrap line the band re-synthesis reads and writes: a band's strip reaches band / 2 + context
// lines on one side, band - band / 2 + context on the other; the texels set from it, (band + 1) / 2 + 1.
inline int bandLinesReach(int band, int context) { return band / 2 + context + 2; }

}  // namespace heightpack::detail
