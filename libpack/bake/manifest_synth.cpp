#include "manifest_synth.hpp"

#include <limits>

#include "heightpack/core/sea/cascades.hpp"

namespace heightpack::detail {

namespace {

bool powerOfTwo(int v) { return v > 0 && (v & (v - 1)) == 0; }

}  // namespace

SynthSource parseSynthSource(Section& t, double tileSize) {
    SynthSource out;
    SpectrumOptions& o = out.spectrum;
    o.model = t.choice("spectrum", o.model);
    // The wind has no sensible default: a sea is mostly its wind, as --wind is required on the command line.
    o.windSpeed = t.number("wind", std::nullopt, 0.0, 100.0, true);
    o.windDirection = t.number("direction", o.windDirection, -360.0, 360.0);
    // fetch and gamma shape JONSWAP only: given with another spectrum they would change the key but
    // not the sea, so they are refused rather than ignored.
    for (const char* jonswapOnly : {"fetch", "gamma"})
        if (t.find(jonswapOnly) && o.model != SpectrumModel::Jonswap)
            throw t.error(jonswapOnly, std::string("shapes the jonswap spectrum only, but spectrum is \"") +
                                           nameOf(o.model) + "\"",
                          "remove it, or set spectrum = \"jonswap\"");
    o.fetch = t.number("fetch", o.fetch, 0.0, 1e7, true);
    o.gamma = t.number("gamma", o.gamma, 1.0, 10.0);
    o.spreading = t.choice("spreading", o.spreading);
    if (t.find("spreading_s") && o.spreading != Spreading::Cos2s)
        throw t.error("spreading_s", "sets the cos-2s exponent, but spreading is not \"cos2s\"",
                      "set spreading = \"cos2s\" beside it, or remove it");
    o.spreadingExponent = t.number("spreading_s", o.spreadingExponent, 0.1, 1000.0);
    o.depth = t.number("depth", 0.0, 0.0, 1e4, true);
    if (t.find("swell")) {
        const std::vector<double> v = t.numbers("swell", {}, 3, -360.0, 360.0);
        if (!(v[0] > 0.0 && v[0] <= 30.0) || v[1] < 1.0 || v[1] > 30.0)
            throw t.error("swell", "is [" + Section::formatNumber(v[0]) + ", " + Section::formatNumber(v[1]) + ", " +
                                       Section::formatNumber(v[2]) + "], but must be [height m, period s, direction deg]",
                          "height greater than 0 and at most 30, period 1 to 30, direction -360 to 360");
        o.swell.significantHeight = v[0];
        o.swell.peakPeriod = v[1];
        o.swell.direction = v[2];
    }
    o.tileSize = tileSize;
    o.size = t.integer("size", o.size, 4, 8192);
    if (!powerOfTwo(o.size)) throw t.error("size", "is " + std::to_string(o.size) + ", but must be a power of two");
    o.seed = static_cast<uint64_t>(t.integer("seed", 1, 0, std::numeric_limits<int>::max()));
    o.loopPeriod = t.number("loop", 0.0, 0.0, 1e6, true);
    out.frames = t.integer("frames", 1, 1, 10000);
    if (out.frames > 1 && o.loopPeriod == 0.0)
        throw t.error("frames", "is " + std::to_string(out.frames) + ", but there is no loop for the frames to cover",
                      "add loop = the period in seconds, such as 8");
    // What is baked beside the heights, and into how many tiles: `synth`'s shift and cascades. Manifests
    // written before the sideways motion was called shift say shift = true.
    if (t.find("shift") && t.find("displacement"))
        throw t.error("displacement", "is the old name of shift, which is given too", "remove displacement");
    out.shift = t.boolean(t.find("displacement") ? "displacement" : "shift").value_or(false);
    // Foam, as synth's --foam and its --foam-* flags; the tuning without foam would change the key, not the sea.
    out.foam = t.boolean("foam").value_or(false);
    for (const char* foamOnly : {"foam_threshold", "foam_decay", "foam_build_up"})
        if (t.find(foamOnly) && !out.foam)
            throw t.error(foamOnly, "tunes the foam, but foam is not true", "set foam = true beside it, or remove it");
    FoamOptions& f = out.foamOptions;
    f.threshold = t.number("foam_threshold", f.threshold, -2.0, 2.0);
    f.decay = t.number("foam_decay", f.decay, 0.0, 1e4, true);
    f.buildUp = t.number("foam_build_up", f.buildUp, 0.0, 1000.0);
    out.cascades = t.integer("cascades", 1, 1, kMaxCascades);
    if (out.cascades > 1 && o.size < kCascadeMinSize)
        throw t.error("cascades", "is " + std::to_string(out.cascades) + ", but size is " + std::to_string(o.size) +
                                      ": each cascade's band needs rings of waves",
                      "give size = " + std::to_string(kCascadeMinSize) + " or more, or remove cascades");
    t.finish();
    return out;
}

}  // namespace heightpack::detail
