#include "heightpack/bake/build/cache_key.hpp"

#include <cstdint>
#include <type_traits>

#include "heightpack/bake/build/build_state.hpp"

#include "build_common.hpp"

namespace heightpack {

namespace {

// One line of key text per field; the value spelt so that different values never read alike.
class Key {
public:
    Key(std::string& text, std::string_view prefix) : text_(text), prefix_(prefix) {}

    void put(std::string_view name, const std::string& s) { line(name, std::to_string(s.size()) + ":" + s); }
    void put(std::string_view name, double v) { line(name, detail::number(v)); }
    void put(std::string_view name, float v) { line(name, detail::number(v)); }
    void put(std::string_view name, bool v) { line(name, v ? "1" : "0"); }
    void put(std::string_view name, int v) { line(name, std::to_string(v)); }
    void put(std::string_view name, int64_t v) { line(name, std::to_string(v)); }
    template <class E>
        requires std::is_enum_v<E>
    void put(std::string_view name, E v) {
        line(name, std::to_string(static_cast<long long>(v)));
    }
    template <class Options>
        requires std::is_class_v<Options>
    void nested(std::string_view name, const Options& o) {
        appendKeyText(text_, std::string(prefix_).append(name).append("."), o);
    }

private:
    void line(std::string_view name, const std::string& value) {
        text_.append(prefix_).append(name).append("=").append(value).append("\n");
    }
    std::string& text_;
    std::string_view prefix_;
};

// The pixel type and supercompression (issue 14) put a line only when not the default, so every key made
// before they existed still matches and no build redoes its outputs for them.
// A tolerance ("auto") chooses the type itself, so it stands in for the pixel type. The storage's fields
// are lines of the job's own key (not a nested storage.*), as they were before they were one struct, so
// existing keys still match; the zstd level likewise only when not the default.
void putStorage(Key& k, const TextureStorage& s) {
    static_assert(fieldCount<TextureStorage>() == 7, "TextureStorage changed: put the new field in its key text");
    k.put("compression", s.exrCompression);
    if (s.tolerance > 0.0) k.put("tolerance", s.tolerance);
    if (s.tolerance > 0.0 && s.toleranceInDegrees) k.put("toleranceInDegrees", true);
    if (s.tolerance > 0.0 && s.allowBlockCompression) k.put("allowBlockCompression", true);
    else if (s.pixelType != PixelType::Float) k.put("pixelType", s.pixelType);
    if (s.supercompression != Supercompression::None) k.put("supercompression", s.supercompression);
    if (s.supercompression != Supercompression::None && s.zstdLevel != TextureStorage{}.zstdLevel)
        k.put("zstdLevel", s.zstdLevel);
}

}  // namespace

void appendKeyText(std::string& text, std::string_view prefix, const LoadOptions& o) {
    static_assert(fieldCount<LoadOptions>() == 6, "LoadOptions changed: put the new field in its key text");
    Key k(text, prefix);
    k.put("channel", o.channel);
    k.put("channelName", o.channelName);
    k.put("maxSide", o.maxSide);
    k.put("maxTexels", static_cast<int64_t>(o.maxTexels));
    // silenceDecoderMessages: where a decoder's messages go, not what is decoded
    // threads: the decoded heights do not depend on it
}

void appendKeyText(std::string& text, std::string_view prefix, const MipOptions& o) {
    static_assert(fieldCount<MipOptions>() == 3, "MipOptions changed: put the new field in its key text");
    Key k(text, prefix);
    k.put("filter", o.filter);
    k.put("wrap", o.wrap);
    // threads: the chain does not depend on it
}

void appendKeyText(std::string& text, std::string_view prefix, const NormalOptions& o) {
    static_assert(fieldCount<NormalOptions>() == 8, "NormalOptions changed: put the new field in its key text");
    Key k(text, prefix);
    k.put("tileWidth", o.tileWidth);
    k.put("tileHeight", o.tileHeight);
    k.put("heightRange", o.heightRange);
    k.put("kernel", o.kernel);
    k.put("wrap", o.wrap);
    k.put("convention", o.convention);
    k.put("alpha", o.alpha);
    // threads: the normals do not depend on it
}

void appendKeyText(std::string& text, std::string_view prefix, const FresnelOptions& o) {
    static_assert(fieldCount<FresnelOptions>() == 6, "FresnelOptions changed: put the new field in its key text");
    Key k(text, prefix);
    k.put("ior", o.ior);
    k.put("model", o.model);
    k.put("index", o.index);
    k.put("size", o.size);
    for (size_t c = 0; c < o.deep.size(); ++c) k.put("deep" + std::to_string(c), o.deep[c]);
    for (size_t c = 0; c < o.shallow.size(); ++c) k.put("shallow" + std::to_string(c), o.shallow[c]);
}

void appendKeyText(std::string& text, std::string_view prefix, const PackOptions& o) {
    static_assert(fieldCount<PackOptions>() == 13, "PackOptions changed: put the new field in its key text");
    Key k(text, prefix);
    k.nested("load", o.load);
    k.nested("mip", o.mip);
    k.put("scale", o.scale);
    k.put("offset", o.offset);
    k.put("resizeToPowerOfTwo", o.resizeToPowerOfTwo);
    putStorage(k, o.storage);
    k.put("plainOutput", o.plainOutput);
    // The layout's line is the one it replaced (packed or not), so every existing key still matches.
    k.put("packed", o.layout == Layout::Neighbour4);
    if (o.layout != Layout::Neighbour4 && o.layout != Layout::Plain) k.put("layout", o.layout);
    if (o.heightRange > 0.0) k.put("heightRange", o.heightRange);  // recorded in the file when known
    k.put("version", o.version);
    // Issue 15: a line only when on, so every key made before it existed still matches.
    if (o.shift) k.put("shift", o.shift);
    if (o.foam) k.put("foam", o.foam);
    // progress: reports, makes nothing
}

void appendKeyText(std::string& text, std::string_view prefix, const NormalJobOptions& o) {
    static_assert(fieldCount<NormalJobOptions>() == 10, "NormalJobOptions changed: put the new field in its key text");
    Key k(text, prefix);
    k.nested("load", o.load);
    k.nested("normal", o.normal);
    k.put("filter", o.filter);
    k.put("resizeToPowerOfTwo", o.resizeToPowerOfTwo);
    k.put("format", o.format);
    putStorage(k, o.storage);
    if (o.toleranceMetres > 0.0) k.put("toleranceMetres", o.toleranceMetres);  // a line only when set, as below
    if (o.layout != Layout::Rgb) k.put("layout", o.layout);  // a line only when not the default, as above
    k.put("version", o.version);
    // progress: reports, makes nothing
}

void appendKeyText(std::string& text, std::string_view prefix, const CheckOptions& o) {
    static_assert(fieldCount<CheckOptions>() == 7, "CheckOptions changed: put the new field in its key text");
    Key k(text, prefix);
    k.nested("load", o.load);
    k.nested("mip", o.mip);
    k.put("threshold", o.threshold);
    // The look's verdict: lines only when not the defaults, so keys made before it stay as they were.
    const LookThresholds defaults;
    if (o.look.frame != defaults.frame) k.put("lookFrame", o.look.frame);
    if (o.look.blobs != defaults.blobs) k.put("lookBlobs", o.look.blobs);
    if (o.look.echo != defaults.echo) k.put("lookEcho", o.look.echo);
    if (o.lookFails) k.put("lookFails", o.lookFails);
    k.put("previewPath", o.previewPath);
    // progress: reports, judges nothing
}

void appendKeyText(std::string& text, std::string_view prefix, const SwellOptions& o) {
    static_assert(fieldCount<SwellOptions>() == 5, "SwellOptions changed: put the new field in its key text");
    Key k(text, prefix);
    k.put("significantHeight", o.significantHeight);
    k.put("peakPeriod", o.peakPeriod);
    k.put("direction", o.direction);
    k.put("gamma", o.gamma);
    k.put("spreadingExponent", o.spreadingExponent);
}

void appendKeyText(std::string& text, std::string_view prefix, const SpectrumOptions& o) {
    static_assert(fieldCount<SpectrumOptions>() == 17, "SpectrumOptions changed: put the new field in its key text");
    Key k(text, prefix);
    k.put("model", o.model);
    k.put("windSpeed", o.windSpeed);
    k.put("windDirection", o.windDirection);
    k.put("fetch", o.fetch);
    k.put("gamma", o.gamma);
    k.put("phillipsAlpha", o.phillipsAlpha);
    k.put("smallWaveLength", o.smallWaveLength);
    k.put("spreading", o.spreading);
    k.put("spreadingExponent", o.spreadingExponent);
    k.put("depth", o.depth);
    k.nested("swell", o.swell);
    k.put("tileSize", o.tileSize);
    k.put("size", o.size);
    k.put("seed", std::to_string(o.seed));  // every bit of a 64-bit seed
    k.put("loopPeriod", o.loopPeriod);
    k.put("bandLow", o.bandLow);
    k.put("bandHigh", o.bandHigh);
}

void appendKeyText(std::string& text, std::string_view prefix, const FoamOptions& o) {
    static_assert(fieldCount<FoamOptions>() == 3, "FoamOptions changed: put the new field in its key text");
    Key k(text, prefix);
    k.put("threshold", o.threshold);
    k.put("decay", o.decay);
    k.put("buildUp", o.buildUp);
}

std::string cacheKey(std::string_view version, std::string_view text, std::string_view inputHash) {
    std::string all = "heightpack ";
    all.append(version).append("\n").append(text).append("input=").append(inputHash).append("\n");
    return hashText(all);
}

}  // namespace heightpack
