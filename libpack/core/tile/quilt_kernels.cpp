// The search and the cut of the quilting (tile/quilt_kernels.hpp).
#include "quilt_kernels.hpp"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cstddef>
#include <vector>

#include "dft.hpp"

namespace heightpack::detail {

Field maskedSquaredErrors(Field target, Field mask, Field source, int threads) {
    double constant = 0;
    for (size_t i = 0; i < target.v.size(); ++i) {
        constant += mask.v[i] * target.v[i] * target.v[i];
        target.v[i] *= mask.v[i];
    }
    const cv::Mat sourceSpectrum = forwardDft(source.mat(), threads);
    for (double& x : source.v) x *= x;
    const cv::Mat squaredSpectrum = forwardDft(source.mat(), threads);
    // Correlation: sum_p a(p) b(p + d) is the inverse DFT of B conj(A).
    cv::Mat spectrum, cross;
    cv::mulSpectrums(squaredSpectrum, forwardDft(mask.mat(), threads), spectrum, 0, true);
    cv::mulSpectrums(sourceSpectrum, forwardDft(target.mat(), threads), cross, 0, true);
    cv::scaleAdd(cross, -2.0, spectrum, spectrum);
    Field errors(source.w, source.h);
    cv::Mat out = errors.mat();
    inverseDft(spectrum, out, threads);
    for (double& e : errors.v) e += constant;
    return errors;
}

std::vector<int> minimalCut(const std::vector<double>& cost, int width, int length) {
    std::vector<double> total(cost.begin(), cost.begin() + width);
    total.resize(cost.size());
    std::vector<int> from(cost.size(), 0);
    for (int line = 1; line < length; ++line) {
        const size_t row = size_t(line) * width, previous = row - width;
        for (int place = 0; place < width; ++place) {
            int best = place;
            for (int other : {place - 1, place + 1})
                if (other >= 0 && other < width && total[previous + other] < total[previous + best]) best = other;
            total[row + place] = total[previous + best] + cost[row + place];
            from[row + place] = best;
        }
    }
    std::vector<int> path(length);
    const size_t last = size_t(length - 1) * width;
    path[length - 1] = int(std::min_element(total.begin() + last, total.begin() + last + width) - (total.begin() + last));
    for (int line = length - 1; line > 0; --line) path[line - 1] = from[size_t(line) * width + path[line]];
    return path;
}

}  // namespace heightpack::detail
