#include "foam_gl.hpp"

#include <vector>

#include "texture_upload.hpp"

namespace heightpack::view {

GLuint uploadFoamCoverage(const HeightLayer& layer) {
    if (!layer.foam) return 0;
    std::vector<const UploadChain*> frames;
    for (const HeightFrame& frame : layer.frames) frames.push_back(&frame.foam);
    return uploadStoredArray(frames, true, layer.wrap);
}

}  // namespace heightpack::view
