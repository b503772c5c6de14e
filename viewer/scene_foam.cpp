#include "scene_foam.hpp"

#include "heightpack/bake/pack_foam.hpp"
#include "heightpack/io/attributes.hpp"
#include "heightpack/io/foam_read.hpp"

namespace heightpack::view {

Status takeFoam(const std::string& path, const ViewerTexture& file, const HeightChains& split, HeightFrame& frame) {
    if (!file.description.channels.hasFoam()) return Done{};
    if (!file.layers.empty()) {  // an array texture: its layer Foam as stored, F(i, j) of a packed one
        const UploadChain* foam = file.layer(layerName::foam);
        if (!foam) return badInput(path, "records foam but has no layer Foam", "pack it again");
        frame.foam = foam->channels == 1 ? *foam : firstChannel(*foam);
        return Done{};
    }
    frame.foam = storeFloats(split.foam);
    return Done{};
}

Status foamChainOf(const std::string& path, const LoadOptions& load, const SourceInfo& source,
                   const PackOptions& pack, HeightFrame& frame) {
    if (!hasFoam(path)) return Done{};
    auto coverage = loadFoam(path, load);
    if (!coverage) return coverage.error();
    auto chain = foamChain(std::move(*coverage), source, pack);
    if (!chain) return chain.error();
    frame.foam = storeFloats(*chain);
    return Done{};
}

}  // namespace heightpack::view
