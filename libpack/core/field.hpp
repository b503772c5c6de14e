// Internal: a row-major field of doubles, the working precision of the tile fixes and statistics
// (tile/resynthesis.cpp, tile/look.cpp), viewable as an OpenCV matrix for its DFT.
#pragma once

#include <opencv2/core.hpp>

#include <utility>

#include "buffer.hpp"

namespace heightpack::detail {

struct Field {
    int w = 0, h = 0;
    Buffer<double> v;
    // Every value unset, for a writer that sets them all (see buffer.hpp): Field(w, h, Field::unset).
    enum Unset { unset };
    Field(int width, int height) : w(width), h(height), v(size_t(width) * height, 0.0) {}
    Field(int width, int height, Unset) : w(width), h(height), v(size_t(width) * height) {}
    Field(int width, int height, Buffer<double> values) : w(width), h(height), v(std::move(values)) {}
    double& at(int x, int y) { return v[size_t(y) * w + x]; }
    double at(int x, int y) const { return v[size_t(y) * w + x]; }
    // The same values as a CV_64F matrix (no copy: it lives as long as v is not resized).
    cv::Mat mat() { return cv::Mat(h, w, CV_64F, v.data()); }
};

}  // namespace heightpack::detail
