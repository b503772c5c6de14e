// Metadata written into texture headers, and the typed schema of the heightpack:* keys: one constant per
// key, carrying the type of its value, used by every writer and reader instead of string literals.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "heightpack/core/fresnel.hpp"
#include "heightpack/core/image.hpp"
#include "heightpack/core/layout.hpp"
#include "heightpack/core/mip.hpp"
#include "heightpack/core/names.hpp"
#include "heightpack/core/normal.hpp"
#include "heightpack/core/sea/spectrum.hpp"

namespace heightpack {

// A header attribute: a string or a float.
struct ExrAttribute {
    std::string name;
    std::variant<std::string, float> value;
};

// A heightpack:* key and the type of its value: std::string, float, or an enum with a NameTable (written
// as its name).
template <class T>
struct AttributeKey {
    const char* name;
};

namespace attr {
inline constexpr const char* kPrefix = "heightpack:";  // every key below starts with it
// Every file heightpack writes.
// neighbour4, plain, normal, normalXY (see attributeText(Layout)), fresnel, synthesised, ...
inline constexpr AttributeKey<std::string> layout{"heightpack:layout"};
// The layout word of synth's seas: heights in metres = heightOffset + heightScale * value.
inline constexpr const char* synthesised = "synthesised";
// The layout words of the other files heightpack writes: Fresnel ramps, check's seam previews, and
// heightpack-view's captures (its grid's heights, a screenshot).
inline constexpr const char* fresnelRamp = "fresnel";
inline constexpr const char* seamPreview = "seamPreview";
inline constexpr const char* gridHeights = "grid heights";
inline constexpr const char* screenshot = "screenshot";
inline constexpr AttributeKey<std::string> version{"heightpack:version"};
inline constexpr AttributeKey<float> texelCentre{"heightpack:texelCentre"};
inline constexpr AttributeKey<std::string> source{"heightpack:source"};  // the input's file name
inline constexpr AttributeKey<std::string> sourceHash{"heightpack:sourceHash"};
// Height textures (packed, plain) and synthesised maps: stored = offset + scale * value.
inline constexpr AttributeKey<Wrap> wrap{"heightpack:wrap"};
inline constexpr AttributeKey<Filter> filter{"heightpack:filter"};
inline constexpr AttributeKey<float> heightScale{"heightpack:heightScale"};
inline constexpr AttributeKey<float> heightOffset{"heightpack:heightOffset"};
// Shift stored beside the heights (pack --shift; the key is named as design.md names it): "neighbour4" when layers Dx and
// Dy hold Dx, Dy packed as the heights are (Dx.R = Dx(i,j), Dx.G = Dx(i+1,j), ...), "plain" when channels
// Dx, Dy hold them unpacked. Absent: the file holds heights alone.
inline constexpr AttributeKey<std::string> shift{"heightpack:displacement"};
// Foam coverage (synth --foam, 0..1) stored beside the heights (pack --foam): "neighbour4" when layer Foam
// holds it packed as the heights are (Foam.R = F(i,j), Foam.G = F(i+1,j), ...), "plain" when channel Foam
// holds it unpacked. Absent: the file holds no foam.
inline constexpr AttributeKey<std::string> foam{"heightpack:foam"};
// Array textures (KTX2 layerCount, DDS arraySize): the layers' names in order, comma-separated, e.g.
// "heights,Dx,Dy,Foam" (names in layerName below). Each layer is a whole texture of the file's format,
// laid out as the file's layout (heights), shift (Dx, Dy) and foam (Foam) attributes say. A KTX2
// records it as a key/value; a DDS in its header's record (see dds.cpp); readers report it either way.
inline constexpr AttributeKey<std::string> layers{"heightpack:layers"};
// 16-bit normalised textures (KTX2, DDS): value = normalisedOffset + normalisedScale * u / 65535.
inline constexpr AttributeKey<float> normalisedOffset{"heightpack:normalisedOffset"};
inline constexpr AttributeKey<float> normalisedScale{"heightpack:normalisedScale"};
// Half and uint16 textures: the worst difference between a bilinear lookup from the stored texels and
// from the float chain they were made from (core/lookup_error.hpp), in the chain's units (stored heights,
// normal components), measured when written since the float chain is not in the file. lookupError lists
// it per level, level 0 first, comma-separated; maxLookupError is the worst of them.
inline constexpr AttributeKey<std::string> lookupError{"heightpack:lookupError"};
inline constexpr AttributeKey<float> maxLookupError{"heightpack:maxLookupError"};
// Block-compressed textures (bc4, bc5): their levels decoded by the format's rules against the float
// chain, per level as lookupError lists it. lookupError is then the worst texel's error (a bilinear lookup
// errs no more than its worst texel); rmsError the root mean square in the same units; for xy normals
// angleError and rmsAngleError the angle between decoded and float normals, in degrees.
inline constexpr AttributeKey<std::string> rmsError{"heightpack:rmsError"};
inline constexpr AttributeKey<std::string> angleError{"heightpack:angleError"};
inline constexpr AttributeKey<std::string> rmsAngleError{"heightpack:rmsAngleError"};
// Sequences: a float in an EXR, text in a PNG.
inline constexpr AttributeKey<float> loopPeriod{"heightpack:loopPeriod"};
inline constexpr AttributeKey<float> time{"heightpack:time"};
inline constexpr AttributeKey<std::string> frame{"heightpack:frame"};  // "F/FRAMES"
// Normal maps.
inline constexpr AttributeKey<SlopeKernel> kernel{"heightpack:kernel"};
inline constexpr AttributeKey<NormalConvention> convention{"heightpack:convention"};
inline constexpr AttributeKey<NormalAlpha> alpha{"heightpack:alpha"};
inline constexpr AttributeKey<float> tileWidth{"heightpack:tileWidth"};  // metres; synth: the tile's size
inline constexpr AttributeKey<float> tileHeight{"heightpack:tileHeight"};
// Metres between a stored 0.0 and 1.0: normal maps always, packed and plain heights when it was given.
inline constexpr AttributeKey<float> heightRange{"heightpack:heightRange"};
// Fresnel ramps.
inline constexpr AttributeKey<float> ior{"heightpack:ior"};
inline constexpr AttributeKey<FresnelModel> model{"heightpack:model"};
inline constexpr AttributeKey<FresnelIndex> index{"heightpack:index"};
inline constexpr AttributeKey<std::string> deep{"heightpack:deep"};  // "r,g,b"
inline constexpr AttributeKey<std::string> shallow{"heightpack:shallow"};
// Synthesised seas.
inline constexpr AttributeKey<SpectrumModel> spectrum{"heightpack:spectrum"};
inline constexpr AttributeKey<std::string> wind{"heightpack:wind"};
inline constexpr AttributeKey<std::string> seed{"heightpack:seed"};
inline constexpr AttributeKey<float> fetch{"heightpack:fetch"};
inline constexpr AttributeKey<float> depth{"heightpack:depth"};  // m; absent in deep water
inline constexpr AttributeKey<Spreading> spreading{"heightpack:spreading"};
inline constexpr AttributeKey<std::string> swell{"heightpack:swell"};  // "Hs m, Tp s, direction deg"
inline constexpr AttributeKey<float> choppiness{"heightpack:choppiness"};  // the lambda foam and folds assume
inline constexpr AttributeKey<std::string> cascade{"heightpack:cascade"};  // "C/COUNT"
inline constexpr AttributeKey<float> bandLow{"heightpack:bandLow"};        // rad/m, a cascade's band
inline constexpr AttributeKey<float> bandHigh{"heightpack:bandHigh"};
inline constexpr AttributeKey<float> foamThreshold{"heightpack:foamThreshold"};
inline constexpr AttributeKey<float> foamDecay{"heightpack:foamDecay"};    // s
inline constexpr AttributeKey<float> foamBuildUp{"heightpack:foamBuildUp"};  // 1/s
// The sea-state report (the whole sequence's numbers, in every frame).
inline constexpr AttributeKey<float> significantWaveHeight{"heightpack:significantWaveHeight"};  // m, 4 std
inline constexpr AttributeKey<float> spectrumWaveHeight{"heightpack:spectrumWaveHeight"};        // m, 4 sqrt(m0)
inline constexpr AttributeKey<float> peakPeriod{"heightpack:peakPeriod"};                        // s
inline constexpr AttributeKey<float> peakWavelength{"heightpack:peakWavelength"};                // m
inline constexpr AttributeKey<float> steepness{"heightpack:steepness"};                          // Hs / Lp
inline constexpr AttributeKey<float> foldFraction{"heightpack:foldFraction"};                    // J < 0
inline constexpr AttributeKey<float> maxShift{"heightpack:maxDisplacement"};  // m, the largest shift (key as design.md)
inline constexpr AttributeKey<float> shiftBound{"heightpack:displacementBound"};  // m, its bound
// Tiled maps.
inline constexpr AttributeKey<std::string> tileMethod{"heightpack:tileMethod"};
inline constexpr AttributeKey<std::string> seamsBefore{"heightpack:seamsBefore"};
inline constexpr AttributeKey<std::string> seamsAfter{"heightpack:seamsAfter"};
inline constexpr AttributeKey<float> crossfadeWidth{"heightpack:crossfadeWidth"};
inline constexpr AttributeKey<std::string> tileBand{"heightpack:tileBand"};  // "BXxBY": texels re-synthesised
inline constexpr AttributeKey<std::string> tileMatch{"heightpack:tileMatch"};  // quilt: 1 the best source, 2 the next
// Seam previews.
inline constexpr AttributeKey<float> threshold{"heightpack:threshold"};
}  // namespace attr

// The layers heightpack writes into an array texture, in this order when present: the heights, the
// shift's Dx and Dy, the foam coverage (the companions keep their EXR layers' names).
namespace layerName {
inline constexpr const char* heights = "heights";
inline constexpr const char* dx = "Dx";
inline constexpr const char* dy = "Dy";
inline constexpr const char* foam = "Foam";
}  // namespace layerName

// The word a header holds for an enum value: its table name, except that a variance normal map has
// always said "slopeVariance" in its header (the manifest and material.json say "variance").
template <class E>
const char* attributeText(E value) {
    return nameOf(value);
}
inline const char* attributeText(NormalAlpha alpha) {
    return alpha == NormalAlpha::SlopeVariance ? "slopeVariance" : nameOf(alpha);
}

// A layout's word in a header: its table name for heights; a normal map's header has always said
// "normal" (rgb), and says "normalXY" for two channels, so a reader tells normals from heights by the
// word alone.
inline const char* attributeText(Layout layout) {
    switch (layout) {
        case Layout::Rgb: return "normal";
        case Layout::Xy: return "normalXY";
        default: return nameOf(layout);
    }
}

// A header's attributes as text, in the order the file lists them (a float as %g).
using Attributes = std::vector<std::pair<std::string, std::string>>;

// The value of the attribute called name, or empty.
std::string findAttribute(const Attributes& attributes, const std::string& name);
// The text of a schema key, or empty.
template <class T>
std::string findAttribute(const Attributes& attributes, AttributeKey<T> key) {
    return findAttribute(attributes, key.name);
}

// The enum value a header's word names (attributeText's inverse); nullopt for any other word.
template <class E>
std::optional<E> enumFromAttribute(std::string_view text) {
    for (const EnumName<E>& e : NameTable<E>::entries)
        if (text == attributeText(e.value)) return e.value;
    return std::nullopt;
}

// One attribute of the schema with its value.
inline ExrAttribute attribute(AttributeKey<std::string> key, std::string value) { return {key.name, std::move(value)}; }
inline ExrAttribute attribute(AttributeKey<float> key, float value) { return {key.name, value}; }
template <class E>
ExrAttribute attribute(AttributeKey<E> key, E value) {
    return {key.name, std::string(attributeText(value))};
}

}  // namespace heightpack
