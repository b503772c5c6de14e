// What a texture file is, read once from its header (EXR attributes, KTX2 key/values, a DDS record, PNG
// text) into enums and numbers: its kind, layout, wrap, filter, height scale and offset, pixel type, units
// and timing, and which of its channels hold the heights, Dx, Dy and foam. Every reader (info, check, pack's
// input, the viewer, the material sampler) asks this value; none compares an attribute's text or types a
// channel's name. A damaged value is bad input where the header is parsed, naming the file and the key.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "heightpack/core/fresnel.hpp"
#include "heightpack/core/layout.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/normal.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/attributes.hpp"
#include "heightpack/io/map_units.hpp"
#include "heightpack/io/pixel_type.hpp"

namespace heightpack {

// What a file holds, from its heightpack:layout word: an image from elsewhere has none.
enum class TextureKind { Image, Heights, Normals, FresnelRamp, SynthesisedSea, SeamPreview, GridHeights, Screenshot };
template <>
struct NameTable<TextureKind> {
    static constexpr EnumName<TextureKind> entries[] = {
        {TextureKind::Image, "image", "an image heightpack did not describe (a painted map, a photo)"},
        {TextureKind::Heights, "heights", "packed (neighbour4) or plain heights from pack"},
        {TextureKind::Normals, "normals", "a normal map from normal (rgb or xy)"},
        {TextureKind::FresnelRamp, "fresnel", "a Fresnel ramp from fresnel"},
        {TextureKind::SynthesisedSea, "synthesised", "a sea from synth: heights in metres, maybe Dx, Dy, Foam"},
        {TextureKind::SeamPreview, "seamPreview", "check's seam preview"},
        {TextureKind::GridHeights, "gridHeights", "heightpack-view's grid heights"},
        {TextureKind::Screenshot, "screenshot", "heightpack-view's screenshot"},
    };
};

// Channel indices (into the file's channels, an array texture's layers in turn) of level 0 for each role.
// Heights: R, G, B, A of a packed file; the one plain channel; Y of any other file that names it. Dx, Dy and Foam: their layer's four
// (packed) or their one channel (plain, synthesised); empty where the file holds none.
struct TextureChannels {
    std::vector<int> heights, dx, dy, foam;
    bool shift() const { return !dx.empty(); }
    bool hasFoam() const { return !foam.empty(); }
};

struct TextureDescription {
    TextureKind kind = TextureKind::Image;
    // Heights: Neighbour4 or Plain; normals: Rgb or Xy; nullopt for other kinds.
    std::optional<Layout> layout;
    Wrap wrap = Wrap::Periodic;       // heightpack:wrap; periodic where the file does not say
    bool wrapRecorded = false;        // whether it says
    std::optional<Filter> filter;     // the mip filter, where recorded
    // stored = heightOffset + heightScale * value (1 and 0 where not recorded).
    double heightScale = 1.0, heightOffset = 0.0;
    // The stored texels' type, where heightpack writes it (float, half, uint16); nullopt for other
    // sample types (8-bit, 32-bit integers), whose width componentBytes gives.
    std::optional<PixelType> pixelType;
    int componentBytes = 4;
    // Tile size, height range, and a sequence's loop period (positive) and time.
    MapUnits units;
    // How the companions beside the heights are laid out (heightpack:displacement, heightpack:foam).
    std::optional<Layout> shift, foam;
    TextureChannels channels;
    // Half, uint16 and block textures: the worst lookup error of each level, level 0 first
    // (heightpack:lookupError); block textures also the RMS error (rmsError) and, for xy normals, the worst
    // and RMS angle in degrees (angleError, rmsAngleError). Empty where the file records none.
    std::vector<double> lookupErrors, rmsErrors, angleErrors, rmsAngleErrors;
    std::optional<NormalConvention> convention;  // normal maps
    std::optional<FresnelIndex> fresnelIndex;    // Fresnel ramps
    bool isHeights() const { return kind == TextureKind::Heights; }
};

// What the header of the file at path says: its heightpack:* attributes as text, its channels' names (an
// array's layers named as readGpuTextureFile names them) and the decoder's word for its sample type
// ("float", "half", "uint16", "uint8", ...). Fails with BadInput naming path and the key for a value the
// schema does not allow: a layout, wrap, filter or other enum word it does not list, a number that is not
// finite (a length or loop period that is not positive), a companion recorded without its channels.
Result<TextureDescription> describeTexture(const std::string& path, const Attributes& attributes,
                                           const std::vector<std::string>& channelNames, std::string_view sampleType);

// What a heightpack:layout word says: the kind of file, and for heights and normals their Layout.
struct LayoutWord {
    TextureKind kind = TextureKind::Image;
    std::optional<Layout> layout;
    bool operator==(const LayoutWord&) const = default;
};
// The one reading of a layout word (neighbour4, normal, fresnel, grid heights, ...); nullopt for a word
// heightpack does not write.
std::optional<LayoutWord> parseLayoutWord(std::string_view word);
// The layout word heightpack writes for a kind that has no Layout (fresnel, synthesised, ...).
const char* layoutWord(TextureKind kind);
// The word for what parseLayoutWord read.
const char* layoutWord(const LayoutWord& said);
// The heightpack:layout word of a described file (neighbour4, normal, fresnel, ...); "" for an Image.
const char* layoutWord(const TextureDescription& texture);

}  // namespace heightpack
