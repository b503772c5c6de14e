#include "stored_chain.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <optional>

#include "heightpack/core/lookup_error.hpp"

namespace heightpack::detail {

double StoredChain::worst() const {
    return lookupError.empty() ? 0.0 : *std::max_element(lookupError.begin(), lookupError.end());
}

double StoredChain::worstDegrees() const {
    return angleError.empty() ? 0.0 : *std::max_element(angleError.begin(), angleError.end());
}

double StoredChain::worstIn(const TextureStorage& storage) const {
    if (!storage.toleranceInDegrees) return worst();
    // No angle measured (a chain that is no normal map): nothing shows it within a tolerance in degrees.
    return angleError.empty() ? std::numeric_limits<double>::infinity() : worstDegrees();
}

namespace {

Result<StoredChain> measure(const std::vector<TextureOutput>& outputs, const ChainToWrite& content,
                            const ChainValues& chains, TextureWriteOptions options, PixelType type) {
    options.storage.pixelType = type;
    StoredChain stored;
    stored.pixelType = type;
    if (type == PixelType::Float) {  // the float chain itself; every container holds it
        stored.lookupError.assign(chains.front()->size(), 0.0);
        if (options.storage.toleranceInDegrees) stored.angleError = stored.lookupError;
        return stored;
    }
    // The range from the plain chains themselves: the same values as content's, four times fewer than a
    // packed content's and nothing to pack.
    auto storage = planTexelStorage(outputs.front(), content, options, chains);
    if (!storage) return storage.error();
    stored.plan = storage->plan;
    // The same values, so only the container can object: no second scan.
    for (size_t i = 1; i < outputs.size(); ++i)
        if (Status s = containerTakes(outputs[i], options.storage); !s) return s.error();
    if (const BlockLevels* blocks = stored.plan.blocks.get()) {  // measured on what was encoded
        stored.lookupError = blocks->worst;
        stored.rmsError = blocks->rms;
        stored.angleError = blocks->worstDegrees;
        stored.rmsAngleError = blocks->rmsDegrees;
        return stored;
    }
    for (const std::vector<Image>* chain : chains) {
        const std::vector<double> errors = worstLookupError(*chain, storage->storeAndReadRow, options.threads);
        if (stored.lookupError.empty()) stored.lookupError = errors;
        for (size_t level = 0; level < errors.size(); ++level)
            stored.lookupError[level] = std::max(stored.lookupError[level], errors[level]);
    }
    if (options.storage.toleranceInDegrees)  // a normal map: one chain
        stored.angleError = worstAngleErrorDegrees(*chains.front(), storage->storeAndReadRow, options.threads);
    return stored;
}

}  // namespace

Result<StoredChain> chooseStorage(const std::vector<TextureOutput>& outputs, const ChainToWrite& content,
                                  const ChainValues& chains, const TextureWriteOptions& options) {
    const double tolerance = options.storage.tolerance;
    if (!(tolerance > 0.0)) return measure(outputs, content, chains, options, options.storage.pixelType);
    if (options.storage.allowBlockCompression) {
        // Fewest bytes a texel first; of those that take as many (ASTC 4x4 and BC5 for xy normals), the
        // smaller error wins (ASTC 4x4 on a tie). Not ASTC HDR: its worst error over a chain is above LDR's
        // of the same size on every map measured (docs/formats.md, "ASTC HDR"), so it would never be chosen.
        struct Candidate {
            PixelType type;
            double bytesPerTexel;
        };
        std::optional<StoredChain> within;
        double withinBytes = 0.0;
        for (const Candidate c : {Candidate{PixelType::Astc8x8, 16.0 / 64}, Candidate{PixelType::Astc6x6, 16.0 / 36},
                                  Candidate{PixelType::Bc4, 0.5}, Candidate{PixelType::Astc4x4, 1.0}, Candidate{PixelType::Bc5, 1.0}}) {
            if (within && c.bytesPerTexel > withinBytes) break;
            auto candidate = measure(outputs, content, chains, options, c.type);
            if (!candidate || candidate->worstIn(options.storage) > tolerance) continue;
            if (!within || candidate->worstIn(options.storage) < within->worstIn(options.storage)) within = std::move(*candidate);
            withinBytes = c.bytesPerTexel;
        }
        if (within) return *within;
    }
    std::optional<StoredChain> best;
    for (const PixelType type : {PixelType::Half, PixelType::Uint16}) {  // two bytes a component
        auto candidate = measure(outputs, content, chains, options, type);
        if (!candidate || candidate->worstIn(options.storage) > tolerance) continue;
        if (!best || candidate->worstIn(options.storage) < best->worstIn(options.storage)) best = std::move(*candidate);
    }
    if (best) return *best;
    return measure(outputs, content, chains, options, PixelType::Float);
}

namespace {

std::string levelList(const std::vector<double>& values) {
    std::string levels;
    for (const double e : values) {
        char text[32];
        std::snprintf(text, sizeof text, "%.9g", e);
        if (!levels.empty()) levels += ',';
        levels += text;
    }
    return levels;
}

}  // namespace

std::vector<ExrAttribute> lookupErrorAttributes(const StoredChain& stored) {
    if (stored.pixelType == PixelType::Float) return {};
    std::vector<ExrAttribute> out = {attribute(attr::lookupError, levelList(stored.lookupError)),
                                     attribute(attr::maxLookupError, static_cast<float>(stored.worst()))};
    if (!stored.rmsError.empty()) out.push_back(attribute(attr::rmsError, levelList(stored.rmsError)));
    if (!stored.angleError.empty()) out.push_back(attribute(attr::angleError, levelList(stored.angleError)));
    if (!stored.rmsAngleError.empty()) out.push_back(attribute(attr::rmsAngleError, levelList(stored.rmsAngleError)));
    return out;
}

}  // namespace heightpack::detail
