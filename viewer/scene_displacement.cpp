#include "scene_displacement.hpp"

#include <algorithm>

#include "heightpack/bake/pack_displacement.hpp"
#include "heightpack/core/pack.hpp"
#include "heightpack/io/displacement_read.hpp"

namespace heightpack::view {

Status takeDisplacement(const std::string& path, ViewerTexture& file, Wrap wrap, HeightFrame& frame) {
    const std::string stored = findAttribute(file.attributes, attr::displacement);
    if (stored.empty()) return Done{};
    const bool packed = stored == "neighbour4";
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
    for (Image& level : file.levels) {
        Image shiftX = selectChannels(level, x), shiftY = selectChannels(level, y);
        frame.shiftX.push_back(packed ? std::move(shiftX) : packNeighbour4(shiftX, wrap));
        frame.shiftY.push_back(packed ? std::move(shiftY) : packNeighbour4(shiftY, wrap));
        level = selectChannels(level, h);
    }
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
    frame.shiftX = std::move(maps->packedX);
    frame.shiftY = std::move(maps->packedY);
    return Done{};
}

}  // namespace heightpack::view
