#include "support/spectral_derivative.hpp"

#include <numbers>

namespace heightpack::test {

cv::Mat spectralDerivative(const std::function<double(int x, int y)>& field, int n, int axis, double tileSize) {
    cv::Mat f(n, n, CV_64F), F, out;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) f.at<double>(y, x) = field(x, y);
    cv::dft(f, F, cv::DFT_COMPLEX_OUTPUT);
    for (int r = 0; r < n; ++r)
        for (int q = 0; q < n; ++q) {
            const int m = axis == 0 ? (q < n / 2 ? q : q - n) : (r < n / 2 ? r : r - n);
            const double k = (m == -n / 2 ? 0 : m) * 2 * std::numbers::pi / tileSize;
            const cv::Vec2d z = F.at<cv::Vec2d>(r, q);
            F.at<cv::Vec2d>(r, q) = cv::Vec2d(-z[1] * k, z[0] * k);
        }
    cv::dft(F, out, cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT | cv::DFT_SCALE);
    return out;
}

}  // namespace heightpack::test
