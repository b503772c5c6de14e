#include "scene_foam.hpp"

#include <algorithm>

#include "heightpack/bake/pack_foam.hpp"
#include "heightpack/io/attributes.hpp"
#include "heightpack/io/foam_read.hpp"

namespace heightpack::view {

Status takeFoam(const std::string& path, ViewerTexture& file, HeightFrame& frame) {
    const std::string stored = findAttribute(file.attributes, attr::foam);
    if (stored.empty()) return Done{};
    if (!file.layers.empty()) {  // an array texture: its layer Foam as stored, F(i, j) of a packed one
        const StoredChain* foam = file.layer(layerName::foam);
        if (!foam) return badInput(path, "records foam but has no layer Foam", "pack it again");
        frame.foam = foam->channels == 1 ? *foam : firstChannel(*foam);
        return Done{};
    }
    const std::string name = stored == "neighbour4" ? "Foam.R" : "Foam";
    const auto at = std::find(file.channelNames.begin(), file.channelNames.end(), name);
    if (at == file.channelNames.end()) return badInput(path, "records foam but has no channel " + name, "pack it again");
    const int foam = static_cast<int>(at - file.channelNames.begin());
    // Every channel but the Foam layer's stays, in order: the heights (and Dx, Dy) as without foam.
    std::vector<int> kept;
    std::vector<std::string> keptNames;
    for (size_t c = 0; c < file.channelNames.size(); ++c) {
        const std::string& n = file.channelNames[c];
        if (n == "Foam" || n.rfind("Foam.", 0) == 0) continue;
        kept.push_back(static_cast<int>(c));
        keptNames.push_back(n);
    }
    std::vector<Image> coverage;
    for (Image& level : file.levels) {
        coverage.push_back(selectChannels(level, {foam}));
        level = selectChannels(level, kept);
    }
    frame.foam = storeFloats(coverage);
    file.channelNames = std::move(keptNames);
    file.stored.reset();  // its texels hold the Foam channels too
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
