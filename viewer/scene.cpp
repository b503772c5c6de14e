#include "scene.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "heightpack/bake/pack_job.hpp"
#include "heightpack/io/files.hpp"
#include "heightpack/io/height_sequence.hpp"
#include "heightpack/io/pixel_type.hpp"
#include "heightpack/io/read.hpp"
#include "scene_shift.hpp"
#include "scene_foam.hpp"
#include "texture_reader.hpp"

namespace heightpack::view {

namespace {

double srgbToLinear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

// Level 0's range and the 1x1 level's value of channel 0, in the file's values.
void measure(const std::vector<Image>& levels, HeightFrame& frame) {
    const Image& top = levels.front();
    frame.minStored = frame.maxStored = top.pixels[0];
    for (size_t i = 0; i < top.pixels.size(); i += size_t(top.channels)) {
        frame.minStored = std::min(frame.minStored, top.pixels[i]);
        frame.maxStored = std::max(frame.maxStored, top.pixels[i]);
    }
    frame.meanStored = levels.back().pixels[0];
}

// One file's chain into frame; fills the layer's wrap and units from the first file.
Status loadFrame(const std::string& path, const std::string& channelChoice, HeightLayer& layer, HeightFrame& frame,
                 bool first) {
    auto file = readViewerTexture(path);
    if (!file) return file.error();
    const TextureDescription& texture = file->description;
    if (first) layer.units = texture.units;  // the file's own values: a texture goes up as stored
    if (texture.isHeights()) {
        if (first) {
            layer.wrap = texture.wrap;
            layer.source = texture.layout == Layout::Neighbour4 ? "packed texture" : "plain texture, packed in memory";
        }
        // An EXR's companions share its texels: split off, its levels keep the heights alone (R, G, B, A
        // or Y), which then go up as floats (a half EXR's stored texels hold every channel; floats hold
        // every half).
        HeightChains split;
        if (file->layers.empty() && (texture.channels.shift() || texture.channels.hasFoam())) {
            split = splitHeightChains(file->levels, texture.channels);
            file->levels = split.heights;
            file->stored.reset();
        }
        if (Status s = takeFoam(path, *file, split, frame); !s) return s;
        if (Status s = takeShift(path, *file, split, layer.wrap, frame); !s) return s;
        UploadChain stored = file->stored ? std::move(*file->stored) : storeFloats(file->levels);
        if (texture.layout == Layout::Neighbour4) {
            if (stored.channels != 4) return badInput(path, "is marked neighbour4 but has no 4 channels", "pack it again");
            frame.plain = firstChannel(stored);
            frame.packed = std::move(stored);
        } else if (stored.isBlock()) {
            // BC4 goes up as its blocks (the reference lookup filters them in hardware); the packing reads
            // texel by texel, so it takes the decoded values, in the same unit values and decode.
            const UploadChain units = firstChannel(unitFloats(file->levels, stored.decode));
            frame.plain = stored.channels == 1 ? std::move(stored) : units;
            frame.packed = packStoredNeighbour4(units, layer.wrap);
        } else {
            frame.plain = firstChannel(stored);
            frame.packed = packStoredNeighbour4(frame.plain, layer.wrap);
        }
        measure(file->levels, frame);
        return Done{};
    }
    // KTX2 and DDS hold what heightpack wrote; only heights are drawn as water.
    if (const auto container = containerForPath(path); container && *container != Container::Exr)
        return badInput(path, std::string("holds ") + describe(texture.kind) + ", not heights",
                        "give a texture heightpack pack wrote");
    // A painted map: the same load, mip and pack as `heightpack pack` (periodic, kaiser).
    LoadOptions load;
    load.silenceDecoderMessages = true;
    if (const auto select = parseChannelSelect(channelChoice)) {
        load.channel = *select;
    } else if (!channelChoice.empty()) {
        load.channel = ChannelSelect::Named;
        load.channelName = channelChoice;
    }
    auto loaded = loadHeightMap(path, load);
    if (!loaded) return loaded.error();
    PackOptions pack;
    pack.resizeToPowerOfTwo = true;  // a viewer shows any size; pack would ask for --resize pow2
    pack.mip.wrap = layer.wrap;      // periodic, unless the sequence's first frame said otherwise
    auto maps = packHeights(std::move(loaded->heights), loaded->source, pack);
    if (!maps) return maps.error();
    measure(maps->plain, frame);
    frame.plain = storeFloats(maps->plain);
    frame.packed = storeFloats(maps->packed);
    if (Status s = packShiftOf(path, load, loaded->source, pack, frame); !s) return s;
    if (Status s = foamChainOf(path, load, loaded->source, pack, frame); !s) return s;
    if (first) {
        layer.source = "painted map, packed in memory";
        layer.units = loaded->source.units;  // per unit of the values loaded (a heightpack texture's mapped back)
    }
    return Done{};
}

}  // namespace

Result<HeightLayer> loadHeightLayer(const std::string& path, const std::string& channel) {
    HeightLayer layer;
    layer.path = path;
    auto readFrame = [&](const std::string& file, size_t index) -> Result<SequenceFrame> {
        HeightFrame frame;
        if (Status s = loadFrame(file, channel, layer, frame, index == 0); !s) return s.error();
        SequenceFrame shape;
        shape.width = frame.packed.width;
        shape.height = frame.packed.height;
        shape.levels = frame.packed.levels.size();
        // The frames share one array texture on the GPU: one texel type for each chain.
        for (const UploadChain* chain : {&frame.packed, &frame.plain, &frame.shiftX, &frame.foam})
            shape.texelType = shape.texelType * 4 + static_cast<int>(chain->kind);
        shape.shift = !frame.shiftX.levels.empty();
        shape.foam = !frame.foam.levels.empty();
        shape.loopPeriod = index == 0 ? layer.units.loopPeriod : std::nullopt;
        layer.frames.push_back(std::move(frame));
        return shape;
    };
    auto sequence = readHeightSequence(path, readFrame);
    if (!sequence) return sequence.error();
    layer.loopPeriod = sequence->loopPeriod;
    if (sequence->files.size() > 1) layer.source += ", " + std::to_string(sequence->files.size()) + " frames";
    layer.minStored = layer.frames[0].minStored;
    layer.maxStored = layer.frames[0].maxStored;
    for (const HeightFrame& frame : layer.frames) {
        layer.minStored = std::min(layer.minStored, frame.minStored);
        layer.maxStored = std::max(layer.maxStored, frame.maxStored);
    }
    layer.horizontal = !layer.frames[0].shiftX.levels.empty();
    layer.foam = !layer.frames[0].foam.levels.empty();
    // Waves move about the map's mean: the 1x1 level of the first frame, whatever the map's units.
    layer.midStored = layer.frames[0].meanStored;
    return layer;
}

std::string astcPath(const Scene& scene) {
    for (const HeightLayer& layer : scene.layers)
        for (const HeightFrame& frame : layer.frames)
            if (frame.plain.isAstc()) return layer.path;
    if (scene.normals && scene.normals->levels.isAstc()) return scene.normals->path;
    return {};
}

std::string astcHdrPath(const Scene& scene) {
    for (const HeightLayer& layer : scene.layers)
        for (const HeightFrame& frame : layer.frames)
            if (frame.plain.isAstcHdr()) return layer.path;
    return {};  // normals are never HDR
}

Result<NormalMap> loadNormalMap(const std::string& path) {
    auto file = readViewerTexture(path);
    if (!file) return file.error();
    NormalMap map;
    map.path = path;
    const int channels = file->levels[0].channels;
    // Two channels: x and y of a unit normal (heightpack normal --layout xy); the shading needs no more.
    if (channels < 2) return badInput(path, "is not a normal map (fewer than 2 channels)", "make one with heightpack normal");
    // 8/16-bit images store 0.5 + 0.5 n.
    if (file->unitIntegers)
        for (Image& level : file->levels)
            for (float& v : level.pixels) v = 2.0f * v - 1.0f;
    // Each level of a file from heightpack normal holds the normals of that level's heights, better than
    // averaged normals: keep them all. A single level gets its chain from glGenerateMipmap, which needs a
    // colour-renderable format (16-bit snorm is not required to be, blocks are not): such a level goes up as
    // floats.
    const bool keepStored = file->stored && !(file->levels.size() == 1 && (file->stored->kind == ComponentKind::Snorm16 ||
                                                                          file->stored->isBlock()));
    map.levels = keepStored ? std::move(*file->stored) : storeFloats(file->levels);
    const bool directx = file->description.convention == NormalConvention::DirectX;
    map.greenSign = directx ? 1.0f : -1.0f;
    return map;
}

Result<FresnelRamp> loadFresnelRamp(const std::string& path) {
    auto file = readViewerTexture(path);
    if (!file) return file.error();
    FresnelRamp ramp;
    ramp.path = path;
    if (file->levels[0].channels != 4) return badInput(path, "is not a Fresnel ramp (needs RGBA)", "make one with heightpack fresnel");
    if (file->stored) {
        file->stored->levels.resize(1);  // the ramp is read at level 0 only
        ramp.ramp = std::move(*file->stored);
    } else {
        Image& level = file->levels[0];
        if (file->unitIntegers)  // a PNG ramp's colours are sRGB-encoded
            for (size_t i = 0; i < level.pixels.size(); ++i)
                if (i % 4 != 3) level.pixels[i] = static_cast<float>(srgbToLinear(level.pixels[i]));
        ramp.ramp = storeFloats({level});
    }
    ramp.indexScale = file->description.fresnelIndex == FresnelIndex::TwoNdotV ? 2.0f : 1.0f;
    return ramp;
}

Result<Scene> loadScene(const SceneFiles& files) {
    Scene scene;
    for (const std::string& path : files.heights) {
        auto layer = loadHeightLayer(path, files.channel);
        if (!layer) return layer.error();
        scene.layers.push_back(std::move(*layer));
    }
    if (!files.normals.empty()) {
        auto n = loadNormalMap(files.normals);
        if (!n) return n.error();
        scene.normals = std::move(*n);
    }
    if (!files.fresnel.empty()) {
        auto f = loadFresnelRamp(files.fresnel);
        if (!f) return f.error();
        scene.fresnel = std::move(*f);
    }
    if (!files.foam.empty()) {
        LoadOptions load;
        load.silenceDecoderMessages = true;
        auto foam = loadHeightMap(files.foam, load);
        if (!foam) return foam.error();
        scene.foam = std::move(foam->heights);
    }
    return scene;
}

std::vector<std::filesystem::file_time_type> fileTimes(const SceneFiles& files) {
    std::vector<std::filesystem::file_time_type> times;
    auto add = [&](const std::string& path) {
        std::error_code ec;
        times.push_back(path.empty() ? std::filesystem::file_time_type{} : std::filesystem::last_write_time(path, ec));
    };
    for (const auto& p : files.heights)
        for (const auto& frame : expandSequence(p)) add(frame);
    add(files.normals);
    add(files.fresnel);
    add(files.foam);
    return times;
}

}  // namespace heightpack::view
