#include "shift_gl.hpp"

#include <vector>

#include "texture_upload.hpp"

namespace heightpack::view {

GLuint uploadShiftArray(const HeightLayer& layer) {
    if (!layer.horizontal) return 0;
    std::vector<const UploadChain*> chains;
    for (const HeightFrame& frame : layer.frames) chains.insert(chains.end(), {&frame.shiftX, &frame.shiftY});
    return uploadStoredArray(chains, false, layer.wrap);  // texelFetch wraps its own indices
}

GLuint uploadZeroShift() {
    const UploadChain zero = storeFloats({Image(1, 1, 4, 0.0f)});
    return uploadStoredArray({&zero, &zero}, false, Wrap::Periodic);
}

void bindArrayTexture(int unit, GLuint texture) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D_ARRAY, texture);
}

}  // namespace heightpack::view
