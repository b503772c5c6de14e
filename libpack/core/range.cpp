#include "range.hpp"

#include <algorithm>
#include <cmath>

#include "heightpack/core/parallel.hpp"

namespace heightpack::detail {

void easeIntoRange(Image& out, SampleRange in, int threads) {
    const SampleRange now = sampleRange(out, threads);
    const double margin = 0.02 * (double(in.high) - in.low);
    if (!(margin > 0)) return;
    // The knees: values beyond them are eased, each towards its own extreme.
    const double upper = in.high - margin, lower = in.low + margin;
    const bool over = now.high > in.high, under = now.low < in.low;
    if (!over && !under) return;
    float* values = out.pixels.data();
    const size_t n = out.pixels.size(), chunk = 1 << 16;
    parallelFor(static_cast<int>((n + chunk - 1) / chunk), threads, [&](int begin, int end) {
        for (size_t i = begin * chunk; i < std::min(n, end * chunk); ++i) {
            float& v = values[i];
            if (over && v > upper) v = static_cast<float>(upper + margin * std::tanh((v - upper) / margin));
            else if (under && v < lower) v = static_cast<float>(lower - margin * std::tanh((lower - v) / margin));
        }
    });
}

}  // namespace heightpack::detail
