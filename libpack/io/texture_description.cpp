// The one place a header's heightpack:* text becomes typed values, and the one place the channel names
// heightpack writes (R, G, B, A; Y; Dx.R ...; Foam) are mapped to roles.
#include "heightpack/io/texture_description.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <utility>

namespace heightpack {

namespace {

struct KindWord {
    const char* word;
    TextureKind kind;
    std::optional<Layout> layout;
};
// Every heightpack:layout word heightpack writes.
const std::array<KindWord, 9> kKindWords = {{
    {"neighbour4", TextureKind::Heights, Layout::Neighbour4},
    {"plain", TextureKind::Heights, Layout::Plain},
    {"normal", TextureKind::Normals, Layout::Rgb},
    {"normalXY", TextureKind::Normals, Layout::Xy},
    {attr::fresnelRamp, TextureKind::FresnelRamp, std::nullopt},
    {attr::synthesised, TextureKind::SynthesisedSea, std::nullopt},
    {attr::seamPreview, TextureKind::SeamPreview, std::nullopt},
    {attr::gridHeights, TextureKind::GridHeights, std::nullopt},
    {attr::screenshot, TextureKind::Screenshot, std::nullopt},
}};

Error damaged(const std::string& path, const char* key, const std::string& text, const std::string& expected) {
    return badInput(path, std::string("its ") + key + " metadata '" + text.substr(0, 64) + "' is not " + expected,
                    "remove or correct that metadata in the file");
}

// The whole text one finite number.
std::optional<double> finiteNumber(const std::string& text) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || std::abs(v) > 1e30) return std::nullopt;
    return v;
}

// Every number key of the schema the description does not read itself is still checked: a damaged one
// would otherwise be printed by info as if it were a value.
constexpr std::array<AttributeKey<float>, 23> kNumberKeys = {
    attr::texelCentre, attr::normalisedOffset, attr::normalisedScale, attr::maxLookupError, attr::ior,
    attr::fetch, attr::depth, attr::choppiness, attr::bandLow, attr::bandHigh, attr::foamThreshold,
    attr::foamDecay, attr::foamBuildUp, attr::significantWaveHeight, attr::spectrumWaveHeight, attr::peakPeriod,
    attr::peakWavelength, attr::steepness, attr::foldFraction, attr::maxShift, attr::shiftBound,
    attr::crossfadeWidth, attr::threshold};

template <class E>
Result<std::optional<E>> recordedEnum(const std::string& path, const Attributes& attributes, AttributeKey<E> key) {
    const std::string text = findAttribute(attributes, key);
    if (text.empty()) return std::optional<E>{};
    if (const auto value = enumFromAttribute<E>(text)) return value;
    std::string names;
    for (const EnumName<E>& e : NameTable<E>::entries) names += std::string(names.empty() ? "" : ", ") + attributeText(e.value);
    return damaged(path, key.name, text, "one of " + names);
}

// A companion's layout word: neighbour4 or plain.
Result<std::optional<Layout>> recordedCompanion(const std::string& path, const Attributes& attributes,
                                                AttributeKey<std::string> key) {
    const std::string text = findAttribute(attributes, key);
    if (text.empty()) return std::optional<Layout>{};
    const auto layout = enumFromAttribute<Layout>(text);
    if (!layout || !isHeightLayout(*layout))
        return damaged(path, key.name, text, std::string("neighbour4 or plain"));
    return layout;
}

int indexOf(const std::vector<std::string>& names, const std::string& name) {
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

// The channels called prefix + suffix for each suffix (all of them, or none: empty).
std::vector<int> named(const std::vector<std::string>& names, const std::string& prefix, std::vector<const char*> suffixes) {
    std::vector<int> found;
    for (const char* s : suffixes) {
        const int c = indexOf(names, prefix + s);
        if (c < 0) return {};
        found.push_back(c);
    }
    return found;
}

const std::vector<const char*> kPacked = {".R", ".G", ".B", ".A"};

// A companion's channels: its layer's four (packed) or its one channel (plain, or a synthesised map's).
std::vector<int> companion(const std::vector<std::string>& names, const char* layer, std::optional<Layout> layout) {
    return layout == Layout::Neighbour4 ? named(names, layer, kPacked) : named(names, layer, {""});
}

Status mapChannels(const std::string& path, const std::vector<std::string>& names, TextureDescription& d) {
    TextureChannels& c = d.channels;
    c.dx = companion(names, layerName::dx, d.shift);
    c.dy = companion(names, layerName::dy, d.shift);
    if (c.dx.empty() || c.dy.empty()) c.dx.clear(), c.dy.clear();
    c.foam = companion(names, layerName::foam, d.foam);
    if (d.shift && c.dx.empty())
        return badInput(path, std::string("its ") + attr::shift.name + " metadata says it holds Dx, Dy but it has no such channels",
                        "pack it again");
    if (d.foam && c.foam.empty())
        return badInput(path, std::string("its ") + attr::foam.name + " metadata says it holds foam but it has no such channel",
                        "pack it again");
    if (d.kind != TextureKind::Heights) {
        // A height with companions (a synthesised sea's Dx, Dy, Foam) names its channel Y; other files
        // name none (a reader picks one of a grey or colour image by its own rules).
        if (const int y = indexOf(names, "Y"); y >= 0) c.heights = {y};
        return Done{};
    }
    const bool companions = c.shift() || c.hasFoam();
    if (d.layout == Layout::Neighbour4) {
        // Without companions the heights are the first four channels, whatever their names.
        c.heights = companions ? named(names, "", {"R", "G", "B", "A"}) : std::vector<int>{0, 1, 2, 3};
        if (int(names.size()) < 4 || c.heights.empty())
            return badInput(path, "is marked neighbour4 but has no four height channels (R, G, B, A)", "pack it again");
    } else {
        const int y = indexOf(names, "Y");
        c.heights = {y >= 0 ? y : 0};
        if (companions && y < 0 && indexOf(names, "R") != 0)
            return badInput(path, "records its companions but lacks a height channel", "pack it again");
    }
    return Done{};
}

}  // namespace

const char* layoutWord(TextureKind kind) {
    for (const KindWord& k : kKindWords)
        if (k.kind == kind && !k.layout) return k.word;
    return "";
}

const char* layoutWord(const LayoutWord& said) {
    return said.layout ? attributeText(*said.layout) : layoutWord(said.kind);
}

const char* layoutWord(const TextureDescription& texture) { return layoutWord(LayoutWord{texture.kind, texture.layout}); }

std::optional<LayoutWord> parseLayoutWord(std::string_view word) {
    for (const KindWord& k : kKindWords)
        if (word == k.word) return LayoutWord{k.kind, k.layout};
    return std::nullopt;
}

Result<TextureDescription> describeTexture(const std::string& path, const Attributes& attributes,
                                           const std::vector<std::string>& channelNames, std::string_view sampleType) {
    TextureDescription d;
    if (const std::string word = findAttribute(attributes, attr::layout); !word.empty()) {
        const std::optional<LayoutWord> said = parseLayoutWord(word);
        if (!said) {
            std::string words;
            for (const KindWord& w : kKindWords) words += std::string(words.empty() ? "" : ", ") + w.word;
            return damaged(path, attr::layout.name, word, "one of " + words);
        }
        d.kind = said->kind;
        d.layout = said->layout;
    }
    auto wrap = recordedEnum(path, attributes, attr::wrap);
    if (!wrap) return wrap.error();
    d.wrap = wrap->value_or(Wrap::Periodic);
    d.wrapRecorded = wrap->has_value();
    auto filter = recordedEnum(path, attributes, attr::filter);
    if (!filter) return filter.error();
    d.filter = *filter;
    auto convention = recordedEnum(path, attributes, attr::convention);
    if (!convention) return convention.error();
    d.convention = *convention;
    auto index = recordedEnum(path, attributes, attr::index);
    if (!index) return index.error();
    d.fresnelIndex = *index;
    // The enums read nowhere else are checked all the same.
    const auto check = [&](auto key) -> Status {
        auto value = recordedEnum(path, attributes, key);
        if (!value) return value.error();
        return Done{};
    };
    for (Status s : {check(attr::kernel), check(attr::alpha), check(attr::model), check(attr::spectrum), check(attr::spreading)})
        if (!s) return s.error();
    for (const AttributeKey<float>& key : kNumberKeys) {
        const std::string text = findAttribute(attributes, key);
        if (!text.empty() && !finiteNumber(text)) return damaged(path, key.name, text, "a finite number");
    }
    auto units = readMapUnits(attributes, path);
    if (!units) return units.error();
    d.units = *units;
    for (auto [key, to] : {std::pair{attr::heightScale, &d.heightScale}, std::pair{attr::heightOffset, &d.heightOffset}}) {
        const std::string text = findAttribute(attributes, key);
        if (text.empty()) continue;
        const auto v = finiteNumber(text);
        if (!v) return damaged(path, key.name, text, "a finite number");
        *to = *v;
    }
    // synth writes metres = heightOffset + heightScale * value (heightScale 1 in a float EXR, which a
    // manifest's synthesised frames leave out).
    if (!d.units.heightRange && d.kind == TextureKind::SynthesisedSea) d.units.heightRange = d.heightScale;
    auto shift = recordedCompanion(path, attributes, attr::shift);
    if (!shift) return shift.error();
    d.shift = *shift;
    auto foam = recordedCompanion(path, attributes, attr::foam);
    if (!foam) return foam.error();
    d.foam = *foam;
    if (const std::string layers = findAttribute(attributes, attr::layers); !layers.empty()) {
        for (size_t at = 0; at <= layers.size();) {
            const size_t comma = std::min(layers.find(',', at), layers.size());
            const std::string name = layers.substr(at, comma - at);
            if (name != layerName::heights && name != layerName::dx && name != layerName::dy && name != layerName::foam)
                return damaged(path, attr::layers.name, layers, "a list of heights, Dx, Dy, Foam");
            at = comma + 1;
        }
    }
    for (const auto& [key, list] : {std::pair{attr::lookupError.name, &d.lookupErrors}, std::pair{attr::rmsError.name, &d.rmsErrors},
                                    std::pair{attr::angleError.name, &d.angleErrors},
                                    std::pair{attr::rmsAngleError.name, &d.rmsAngleErrors}}) {
        const std::string errors = findAttribute(attributes, key);
        for (size_t at = 0; !errors.empty() && at <= errors.size();) {
            const size_t comma = std::min(errors.find(',', at), errors.size());
            const auto v = finiteNumber(errors.substr(at, comma - at));
            if (!v || *v < 0) return damaged(path, key, errors, "a list of numbers, one a level");
            list->push_back(*v);
            at = comma + 1;
        }
    }
    d.pixelType = parsePixelType(sampleType);
    d.componentBytes = sampleType == "uint8" || sampleType == "int8" ? 1
                       : sampleType == "half" || sampleType == "uint16" || sampleType == "int16" ? 2
                       : sampleType == "double" ? 8
                                                 : 4;
    if (Status s = mapChannels(path, channelNames, d); !s) return s.error();
    return d;
}

}  // namespace heightpack
