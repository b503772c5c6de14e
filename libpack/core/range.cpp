#include "range.hpp"

#include <algorithm>
#include <cmath>

namespace heightpack::detail {

void easeIntoRange(Image& out, const Image& source) {
    const auto [sourceLow, sourceHigh] = std::minmax_element(source.pixels.begin(), source.pixels.end());
    const auto [outLow, outHigh] = std::minmax_element(out.pixels.begin(), out.pixels.end());
    const double margin = 0.02 * (double(*sourceHigh) - *sourceLow);
    if (!(margin > 0)) return;
    // The knees: values beyond them are eased, each towards its own extreme.
    const double upper = *sourceHigh - margin, lower = *sourceLow + margin;
    const bool over = *outHigh > *sourceHigh, under = *outLow < *sourceLow;
    for (float& v : out.pixels) {
        if (over && v > upper) v = static_cast<float>(upper + margin * std::tanh((v - upper) / margin));
        else if (under && v < lower) v = static_cast<float>(lower - margin * std::tanh((lower - v) / margin));
    }
}

}  // namespace heightpack::detail
