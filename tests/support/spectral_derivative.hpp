// d/dx or d/dy of a periodic field by the tests' own forward and inverse DFT (OpenCV's, not the FFT the
// library synthesises with): i k times the spectrum, the Nyquist row/column zeroed as a real field needs.
#pragma once

#include <opencv2/core.hpp>

#include <functional>

namespace heightpack::test {

// field(x, y) on an n x n grid covering one tile of tileSize metres; axis 0 is x, 1 is y. The result is
// n x n CV_64F, row y, column x, in field units per metre.
cv::Mat spectralDerivative(const std::function<double(int x, int y)>& field, int n, int axis, double tileSize);

}  // namespace heightpack::test
