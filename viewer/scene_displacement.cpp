#include "scene_displacement.hpp"

#include <algorithm>

#include "heightpack/bake/pack_displacement.hpp"
#include "heightpack/core/pack.hpp"
#include "heightpack/io/attributes.hpp"
#include "heightpack/io/displacement_read.hpp"

namespace heightpack::view {

Status takeDisplacement(const std::string& path, ViewerTexture& file, Wrap wrap, HeightFrame& frame) {
    const std::string stored = findAttribute(file.attributes, attr::displacement);
    if (stored.empty()) return Done{};
    const bool packed = stored == "neighbour4";
    if (!file.layers.empty()) {  // an array texture: its layers Dx, Dy as stored
        const StoredChain *x = file.layer(layerName::dx), *y = file.layer(layerName::dy);
        if (!x || !y) return badInput(path, "records a displacement but has no layers Dx and Dy", "pack it again");
        frame.shiftX = packed ? *x : packStoredNeighbour4(*x, wrap);
        frame.shiftY = packed ? *y : packStoredNeighbour4(*y, wrap);
        return Done{};
    }
    const auto index = [&](const std::string& name) {
        const auto it = std::find(file.channelNames.begin(), file.channelNames.end(), name);
        return it == file.channelNames.end() ? -1 : static_cast<int>(it - file.channelNames.begin());
    };
    const std::vector<std::string> heights = packed ? std::vector<std::string>{"R", "G", "B", "A"} : std::vector<std::string>{"Y"};
    const std::vector<std::string> dx = packed ? std::vector<std::string>{"Dx.R", "Dx.G", "Dx.B", "Dx.A"} : std::vector<std::string>{"Dx"};
    const std::vector<std::string> dy = packed ? std::vector<std::string>{"Dy.R", "Dy.G", "Dy.B", "Dy.A"} : std::vector<std::string>{"Dy"};
    std::vector<int> h, x, y;
    for (auto [names, out] : {std::pair{&heights, &h}, std::pair{&dx, &x}, std::pair{&dy, &y}})
        for (const std::string& n : *names) {
            if (index(n) < 0)
                return badInput(path, "records a displacement but has no channel " + n, "pack it again");
            out->push_back(index(n));
        }
    std::vector<Image> shiftX, shiftY;
    for (Image& level : file.levels) {
        Image levelX = selectChannels(level, x), levelY = selectChannels(level, y);
        shiftX.push_back(packed ? std::move(levelX) : packNeighbour4(levelX, wrap));
        shiftY.push_back(packed ? std::move(levelY) : packNeighbour4(levelY, wrap));
        level = selectChannels(level, h);
    }
    frame.shiftX = storeFloats(shiftX);
    frame.shiftY = storeFloats(shiftY);
    file.stored.reset();  // its texels hold all twelve (or three) channels
    return Done{};
}

Status packDisplacementOf(const std::string& path, const LoadOptions& load, const SourceInfo& source,
                          const PackOptions& pack, HeightFrame& frame) {
    if (!hasDisplacement(path)) return Done{};
    auto d = loadDisplacement(path, load);
    if (!d) return d.error();
    auto maps = packDisplacement(std::move(*d), source, pack);
    if (!maps) return maps.error();
    frame.shiftX = storeFloats(maps->packedX);
    frame.shiftY = storeFloats(maps->packedY);
    return Done{};
}

}  // namespace heightpack::view
