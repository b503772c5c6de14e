#include "scene_shift.hpp"

#include "heightpack/bake/pack_shift.hpp"
#include "heightpack/core/pack.hpp"
#include "heightpack/io/attributes.hpp"
#include "heightpack/io/height_sequence.hpp"
#include "heightpack/io/shift_read.hpp"

namespace heightpack::view {

Status takeShift(const std::string& path, const ViewerTexture& file, const HeightChains& split, Wrap wrap,
                        HeightFrame& frame) {
    const TextureDescription& texture = file.description;
    if (!texture.channels.shift()) return Done{};
    const bool packed = texture.shift == Layout::Neighbour4;
    if (!file.layers.empty()) {  // an array texture: its layers Dx, Dy as stored
        const UploadChain *x = file.layer(layerName::dx), *y = file.layer(layerName::dy);
        if (!x || !y) return badInput(path, "records a shift but has no layers Dx and Dy", "pack it again");
        frame.shiftX = packed ? *x : packStoredNeighbour4(*x, wrap);
        frame.shiftY = packed ? *y : packStoredNeighbour4(*y, wrap);
        return Done{};
    }
    std::vector<Image> shiftX, shiftY;
    for (size_t level = 0; level < split.dx.size(); ++level) {
        shiftX.push_back(packed ? split.dx[level] : packNeighbour4(split.dx[level], wrap));
        shiftY.push_back(packed ? split.dy[level] : packNeighbour4(split.dy[level], wrap));
    }
    frame.shiftX = storeFloats(shiftX);
    frame.shiftY = storeFloats(shiftY);
    return Done{};
}

Status packShiftOf(const std::string& path, const LoadOptions& load, const SourceInfo& source,
                          const PackOptions& pack, HeightFrame& frame) {
    if (!hasShift(path)) return Done{};
    auto d = loadShift(path, load);
    if (!d) return d.error();
    auto maps = packShift(std::move(*d), source, pack);
    if (!maps) return maps.error();
    frame.shiftX = storeFloats(maps->packedX);
    frame.shiftY = storeFloats(maps->packedY);
    return Done{};
}

}  // namespace heightpack::view
