#include "heightpack/bake/material.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <sstream>

namespace heightpack {

namespace {

using Json = nlohmann::ordered_json;  // keys stay in the order written: the schema's order

Json textureJson(const MaterialTexture& t) {
    Json j = {{"file", t.file}, {"width", t.width}, {"height", t.height}, {"levels", t.levels}};
    if (t.frames > 1) j["frames"] = t.frames;
    if (t.pixelType) j["pixelType"] = nameOf(*t.pixelType);  // only where not float: older files keep their bytes
    return j;
}

Json pairJson(const std::array<double, 2>& v) { return Json::array({v[0], v[1]}); }

// Reading: every lookup names the key path it wanted, so a damaged file says where. Every value's type
// and range is checked before it is used: a number where a string belongs, or 1e20 where an int
// belongs (converting it would be undefined behaviour), is a damaged file like any other.
class Reader {
public:
    explicit Reader(std::string path) : path_(std::move(path)) {}

    // Numbers beyond this are refused: the viewer and engines hold them as floats, and converting a
    // double outside float's range is undefined behaviour.
    static constexpr double kLargest = 1e30;

    const Json& at(const Json& object, const char* key, const std::string& where) const {
        if (!object.is_object() || !object.contains(key)) throw missing(where + key);
        return object.at(key);
    }
    double number(const Json& object, const char* key, const std::string& where) const {
        return number(at(object, key, where), where + key);
    }
    double number(const Json& v, const std::string& name) const {
        const double d = v.is_number() ? v.get<double>() : NAN;
        if (!std::isfinite(d) || std::abs(d) > kLargest) throw missing(name + " (a number)");
        return d;
    }
    // A whole number in [lo, hi], checked as a double before it becomes an int.
    int integer(const Json& object, const char* key, const std::string& where, int lo, int hi) const {
        const Json& v = at(object, key, where);
        const double d = v.is_number() ? v.get<double>() : NAN;
        if (!(d >= lo && d <= hi) || d != std::floor(d))
            throw missing(where + key + " (a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) + ")");
        return static_cast<int>(d);
    }
    std::string text(const Json& object, const char* key, const std::string& where) const {
        const Json& v = at(object, key, where);
        if (!v.is_string()) throw missing(where + key + " (a string)");
        return v.get<std::string>();
    }
    // A string that may be left out.
    std::string optionalText(const Json& object, const char* key, const std::string& where) const {
        return object.contains(key) ? text(object, key, where) : std::string();
    }
    // A name from E's table.
    template <class E>
    E choice(const Json& object, const char* key, const std::string& where) const {
        const Json& v = at(object, key, where);
        const std::optional<E> e = v.is_string() ? parseName<E>(v.get<std::string>()) : std::nullopt;
        if (!e) throw missing(where + key + " (one of: " + joinedNames<E>() + ")");
        return *e;
    }
    std::array<double, 2> pair(const Json& object, const char* key, const std::string& where) const {
        const Json& v = at(object, key, where);
        if (!v.is_array() || v.size() != 2) throw missing(where + key + " (two numbers)");
        return {number(v[0], where + key + "[0]"), number(v[1], where + key + "[1]")};
    }
    MaterialTexture texture(const Json& object, const std::string& where) const {
        const Json& t = at(object, "texture", where);
        const std::string w = where + "texture.";
        MaterialTexture out;
        out.file = text(t, "file", w);
        if (out.file.empty()) throw missing(w + "file (a file name)");
        out.width = integer(t, "width", w, 1, kMaxSide);
        out.height = integer(t, "height", w, 1, kMaxSide);
        out.levels = integer(t, "levels", w, 1, 64);
        out.frames = t.contains("frames") ? integer(t, "frames", w, 1, kMaxFrames) : 1;
        if (t.contains("pixelType")) {
            out.pixelType = parseName<PixelType>(text(t, "pixelType", w));
            if (!out.pixelType) throw missing(w + "pixelType (one of: " + joinedNames<PixelType>() + ")");
        }
        return out;
    }
    Error missing(const std::string& key) const {
        return badInput(path_, "has no valid '" + key + "'", "build the material again with heightpack build");
    }

    static constexpr int kMaxSide = 1 << 24;
    static constexpr int kMaxFrames = 100000;  // as many as expandSequence looks for

private:
    std::string path_;
};

}  // namespace

std::string materialJson(const MaterialDescription& m) {
    Json doc = {{"schema", kMaterialSchemaName}, {"version", kMaterialSchemaVersion}, {"name", m.name},
                {"generator", m.generator}, {"manifest", m.manifest}};
    Json layers = Json::array();
    for (const DisplacementLayer& d : m.displacement) {
        Json j = {{"name", d.name},         {"texture", textureJson(d.texture)}, {"layout", nameOf(d.layout)},
                  {"wrap", nameOf(d.wrap)}, {"filter", nameOf(d.filter)},                {"heightScale", d.heightScale},
                  {"heightOffset", d.heightOffset}, {"tileSize", d.tileSize},    {"scroll", pairJson(d.scroll)},
                  {"amplitude", d.amplitude}};
        if (d.loopPeriod > 0) j["loopPeriod"] = d.loopPeriod;
        // Only for a texture that holds Dx, Dy: every material.json written before them keeps its bytes.
        if (d.shift) {
            j["shift"] = true;
            j["choppiness"] = d.choppiness;
        }
        if (d.foam) j["foam"] = true;  // likewise only for a texture with a Foam layer
        layers.push_back(std::move(j));
    }
    doc["displacement"] = std::move(layers);
    if (m.normals) {
        const NormalLayer& n = *m.normals;
        Json octaves = Json::array();
        for (const NormalOctave& o : n.octaves)
            octaves.push_back({{"tileSize", o.tileSize}, {"scroll", pairJson(o.scroll)}, {"strength", o.strength}});
        Json j = {{"name", n.name}, {"texture", textureJson(n.texture)}};
        if (n.layout != Layout::Rgb) j["layout"] = nameOf(n.layout);  // only xy: older files keep their bytes
        j["convention"] = nameOf(n.convention);
        j["alpha"] = nameOf(n.alpha);
        j["tileSize"] = n.tileSize;
        j["heightRange"] = n.heightRange;
        j["octaves"] = std::move(octaves);
        doc["normals"] = std::move(j);
    }
    if (m.fresnel) {
        const FresnelLayer& f = *m.fresnel;
        doc["fresnel"] = {{"name", f.name}, {"texture", textureJson(f.texture)}, {"ior", f.ior}, {"model", nameOf(f.model)},
                          {"index", nameOf(f.index)}};
    }
    if (m.foam) {
        const FoamLayer& f = *m.foam;
        Json j = {{"name", f.name}};
        if (f.texture) j["texture"] = textureJson(*f.texture);
        j["h0"] = f.h0;
        j["hmax"] = f.hmax;
        j["tileSize"] = f.tileSize;
        doc["foam"] = std::move(j);
    }
    return doc.dump(2) + "\n";
}

Result<MaterialDescription> readMaterial(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return badInput(path, "cannot be opened", "check the path; heightpack build writes OUTPUT/material.json");
    std::stringstream text;
    text << in.rdbuf();
    Json doc = Json::parse(text.str(), nullptr, false);
    if (doc.is_discarded() || !doc.is_object())
        return badInput(path, "is not valid JSON", "build the material again with heightpack build");
    const Reader r(path);
    try {
        if (r.text(doc, "schema", "") != kMaterialSchemaName)
            return badInput(path, "is not a heightpack material (schema is not 'heightpack-material')",
                            "give the material.json that heightpack build wrote");
        const Json& version = r.at(doc, "version", "");
        if (!version.is_number()) throw r.missing("version (a number)");
        // Judged as a double: 1e20 must not be converted to an int.
        const double v = version.get<double>();
        if (!(v >= 1 && v <= kMaterialSchemaVersion) || v != std::floor(v))
            return badInput(path, "has material schema version " + version.dump() + ", this heightpack reads " +
                                      std::to_string(kMaterialSchemaVersion),
                            "use the heightpack that built it, or build it again with this one");
        MaterialDescription m;
        m.name = r.text(doc, "name", "");
        m.generator = r.optionalText(doc, "generator", "");
        m.manifest = r.optionalText(doc, "manifest", "");
        const Json& layers = r.at(doc, "displacement", "");
        if (!layers.is_array()) throw r.missing("displacement (an array)");
        for (size_t i = 0; i < layers.size(); ++i) {
            const std::string w = "displacement[" + std::to_string(i) + "].";
            const Json& j = layers[i];
            DisplacementLayer d;
            d.name = r.text(j, "name", w);
            d.texture = r.texture(j, w);
            // A height layout; neighbour4 where a hand-written file leaves it out.
            d.layout = j.contains("layout") ? r.choice<Layout>(j, "layout", w) : Layout::Neighbour4;
            if (!isHeightLayout(d.layout)) throw r.missing(w + "layout (neighbour4 or plain)");
            d.wrap = r.choice<Wrap>(j, "wrap", w);
            d.filter = r.choice<Filter>(j, "filter", w);
            d.heightScale = r.number(j, "heightScale", w);
            d.heightOffset = r.number(j, "heightOffset", w);
            d.tileSize = r.number(j, "tileSize", w);
            d.scroll = r.pair(j, "scroll", w);
            d.amplitude = r.number(j, "amplitude", w);
            d.loopPeriod = j.contains("loopPeriod") ? r.number(j, "loopPeriod", w) : 0.0;
            // Files written before the sideways motion was called shift name it horizontalDisplacement.
            for (const char* key : {"shift", "horizontalDisplacement"}) {
                if (!j.contains(key)) continue;
                const Json& h = j[key];
                if (!h.is_boolean()) throw r.missing(w + key + " (true or false)");
                d.shift = d.shift || h.get<bool>();
            }
            if (j.contains("choppiness")) d.choppiness = r.number(j, "choppiness", w);
            if (j.contains("foam")) {
                const Json& f = j["foam"];
                if (!f.is_boolean()) throw r.missing(w + "foam (true or false)");
                d.foam = f.get<bool>();
            }
            m.displacement.push_back(std::move(d));
        }
        if (doc.contains("normals")) {
            const Json& j = doc["normals"];
            NormalLayer n;
            n.name = r.text(j, "name", "normals.");
            n.texture = r.texture(j, "normals.");
            n.layout = j.contains("layout") ? r.choice<Layout>(j, "layout", "normals.") : Layout::Rgb;
            if (isHeightLayout(n.layout)) throw r.missing("normals.layout (rgb or xy)");
            n.convention = r.choice<NormalConvention>(j, "convention", "normals.");
            n.alpha = r.choice<NormalAlpha>(j, "alpha", "normals.");
            n.tileSize = r.number(j, "tileSize", "normals.");
            n.heightRange = r.number(j, "heightRange", "normals.");
            const Json& octaves = r.at(j, "octaves", "normals.");
            if (!octaves.is_array()) throw r.missing("normals.octaves (an array)");
            for (size_t i = 0; i < octaves.size(); ++i) {
                const std::string w = "normals.octaves[" + std::to_string(i) + "].";
                n.octaves.push_back({r.number(octaves[i], "tileSize", w), r.pair(octaves[i], "scroll", w),
                                     r.number(octaves[i], "strength", w)});
            }
            m.normals = std::move(n);
        }
        if (doc.contains("fresnel")) {
            const Json& j = doc["fresnel"];
            FresnelLayer f;
            f.name = r.text(j, "name", "fresnel.");
            f.texture = r.texture(j, "fresnel.");
            f.ior = r.number(j, "ior", "fresnel.");
            f.model = r.choice<FresnelModel>(j, "model", "fresnel.");
            f.index = r.choice<FresnelIndex>(j, "index", "fresnel.");
            m.fresnel = std::move(f);
        }
        if (doc.contains("foam")) {
            const Json& j = doc["foam"];
            FoamLayer f;
            f.name = r.text(j, "name", "foam.");
            if (j.contains("texture")) f.texture = r.texture(j, "foam.");
            f.h0 = r.number(j, "h0", "foam.");
            f.hmax = r.number(j, "hmax", "foam.");
            f.tileSize = r.number(j, "tileSize", "foam.");
            m.foam = std::move(f);
        }
        return m;
    } catch (const Error& e) {
        return e;
    }
}

}  // namespace heightpack
