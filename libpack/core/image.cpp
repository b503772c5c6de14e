#include "heightpack/core/image.hpp"

namespace heightpack {

Image transposed(const Image& image) {
    assert(image.channels == 1);
    Image out(image.height, image.width, 1);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) out.at(y, x) = image.at(x, y);
    return out;
}

}  // namespace heightpack
