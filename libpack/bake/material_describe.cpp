#include "heightpack/bake/material_describe.hpp"

#include <filesystem>

#include "heightpack/io/files.hpp"
#include "heightpack/io/info.hpp"

namespace heightpack {

namespace fs = std::filesystem;

namespace {

// A texture's description from its file's header.
Result<MaterialTexture> describeTexture(const std::string& folder, const std::string& output, int frames, double* loopPeriod,
                                        bool* shift = nullptr, bool* foam = nullptr) {
    const std::string first = (fs::path(folder) / frameFileName(output, 0, frames)).string();
    auto layout = readTextureLevels(first, true);
    if (!layout) return layout.error();
    MaterialTexture t;
    t.file = output;
    t.width = layout->levelSizes[0].first;
    t.height = layout->levelSizes[0].second;
    t.levels = static_cast<int>(layout->levelSizes.size());
    t.frames = frames;
    const TextureDescription& described = layout->description;
    if (described.pixelType != PixelType::Float) t.pixelType = described.pixelType;
    if (loopPeriod) *loopPeriod = described.units.loopPeriod.value_or(0.0);
    // Dx, Dy and foam are laid out as the heights are: packed beside packed heights, plain beside plain.
    if (shift) *shift = described.shift.has_value();
    if (foam) *foam = described.foam.has_value();
    return t;
}

}  // namespace

Result<MaterialDescription> describeMaterial(const Manifest& m, const std::string& folder, const std::string& version) {
    MaterialDescription d;
    d.name = m.name;
    d.generator = "heightpack " + version;
    d.manifest = fs::path(m.path).filename().string();
    for (const DisplacementAsset& a : m.displacement) {
        DisplacementLayer layer = a.layer;
        auto t = describeTexture(folder, a.output, static_cast<int>(a.frames.size()), &layer.loopPeriod,
                                 &layer.shift, &layer.foam);
        if (!t) return t.error();
        layer.texture = *t;
        d.displacement.push_back(std::move(layer));
    }
    if (m.normals) {
        NormalLayer layer = m.normals->layer;
        auto t = describeTexture(folder, m.normals->output, static_cast<int>(m.normals->frames.size()), nullptr);
        if (!t) return t.error();
        layer.texture = *t;
        d.normals = std::move(layer);
    }
    if (m.fresnel) {
        FresnelLayer layer = m.fresnel->layer;
        auto t = describeTexture(folder, m.fresnel->output, 1, nullptr);
        if (!t) return t.error();
        layer.texture = *t;
        d.fresnel = std::move(layer);
    }
    if (m.foam) {
        FoamLayer layer = m.foam->layer;
        if (m.foam->texture) {
            auto t = describeTexture(folder, m.foam->texture->output, 1, nullptr);
            if (!t) return t.error();
            layer.texture = *t;
        }
        d.foam = std::move(layer);
    }
    return d;
}

}  // namespace heightpack
