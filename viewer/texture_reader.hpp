// Reading a texture for the viewer: the values the file holds (for statistics and the loaders' own
// transforms) and, where the file stores a GPU texel format, those texels as they are, to upload them
// at the precision the user chose.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/texture_description.hpp"
#include "upload_chain.hpp"

namespace heightpack::view {

struct ViewerTexture {
    std::vector<Image> levels;          // level 0 first, every channel, mapped back to the file's values
    std::optional<UploadChain> stored;  // KTX2, DDS and half EXR: the texels as stored
    // What its header says (EXR attributes, KTX2 key/values, a DDS record), typed; its channels are
    // levels' channels (an EXR's, every channel) or, for an array, every layer's in turn.
    TextureDescription description;
    // A KTX2 or DDS array texture (pack --shift, --foam) is split into its layers: levels and stored
    // then hold layer 0, the heights, alone, as a texture without the other layers has them, and each
    // further layer (Dx, Dy, Foam) is here by name, its texels as stored, so it goes to the GPU in the
    // file's type as the heights do. Empty for any other file.
    struct Layer {
        std::string name;
        UploadChain texels;
    };
    std::vector<Layer> layers;
    const UploadChain* layer(const std::string& name) const;
    // An 8- or 16-bit integer image read through OpenImageIO (a painted PNG): values in [0, 1] that stand
    // for something else (a normal's 0.5 + 0.5 n, an sRGB colour). KTX2 and DDS normalised texels are
    // already mapped back through their recorded scale and offset, so this is false for them.
    bool unitIntegers = false;
};

// Any texture heightpack writes (EXR, KTX2, DDS) or that OpenImageIO reads. Fails with BadInput naming
// the file when it cannot be read.
Result<ViewerTexture> readViewerTexture(const std::string& path);

}  // namespace heightpack::view
