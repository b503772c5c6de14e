#include "scene_foam.hpp"

#include <algorithm>

#include "heightpack/bake/pack_foam.hpp"
#include "heightpack/io/foam_read.hpp"

namespace heightpack::view {

Status takeFoam(const std::string& path, ViewerTexture& file, HeightFrame& frame) {
    const std::string stored = findAttribute(file.attributes, attr::foam);
    if (stored.empty()) return Done{};
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
    for (Image& level : file.levels) {
        Image coverage(level.width, level.height, 1), rest(level.width, level.height, static_cast<int>(kept.size()));
        for (size_t t = 0; t < level.texelCount(); ++t) {
            coverage.pixels[t] = level.pixels[t * level.channels + foam];
            for (size_t c = 0; c < kept.size(); ++c) rest.pixels[t * kept.size() + c] = level.pixels[t * level.channels + kept[c]];
        }
        frame.foam.push_back(std::move(coverage));
        level = std::move(rest);
    }
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
    frame.foam = std::move(*chain);
    return Done{};
}

}  // namespace heightpack::view
