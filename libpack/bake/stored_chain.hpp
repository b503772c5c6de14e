// Internal: the pixel type a job stores its chain in and what that costs at the shader's lookups,
// measured for a type given, or chosen ("auto") as the fewest bytes within a tolerance. pack and normal
// share it, so both choose and record alike.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "heightpack/core/image.hpp"
#include "heightpack/core/result.hpp"
#include "heightpack/io/attributes.hpp"
#include "heightpack/io/texture_write.hpp"

namespace heightpack::detail {

struct StoredChain {
    PixelType pixelType = PixelType::Float;
    WritePlan plan;  // as decided for every output: hand it to writeTexture
    std::vector<double> lookupError;  // per level, level 0 first, in the chain's units
    // Block formats: per level, the RMS decoded error (chain's units) and for xy normals the worst and RMS
    // angle in degrees; empty otherwise.
    // Half and uint16 under a tolerance in degrees: angleError too (worstAngleErrorDegrees).
    std::vector<double> rmsError, angleError, rmsAngleError;
    double worst() const;
    double worstDegrees() const;
    // The worst error in the tolerance's measure: degrees when storage.toleranceInDegrees, else stored units.
    double worstIn(const TextureStorage& storage) const;
};

// chains are what content writes, level by level (ChainValues): the plain heights of a packed output (a
// packed texel holds copies of them, see worstLookupError), then each chain written beside them (Dx, Dy,
// foam: an EXR's further channels, a KTX2's or DDS's further layers); the plan's range is read from them,
// and each is measured once, on all threads. A level's error is the worst of every
// chain's, so a type is chosen only when it holds every layer. With options.storage.tolerance 0, measures
// options.storage.pixelType and fails as writeTexture would when it cannot be stored. With a tolerance > 0,
// chooses the type: the fewest bytes whose worst error over the whole chain (angle in degrees with
// options.storage.toleranceInDegrees: a normal map's chain) is within the tolerance; half
// and uint16 take the same bytes, so of the two that qualify the smaller error wins (half on a tie); float
// when neither does. With options.storage.allowBlockCompression, the block formats are measured first, fewest
// bytes a texel first (ASTC 8x8, 6x6, BC4, ASTC 4x4, BC5; those the layout or container cannot hold are passed
// over), and the first within the tolerance is chosen; of two that take as many bytes (ASTC 4x4, BC5), the one
// with the smaller error. A type the
// container lacks (uint16 in an EXR) or the values do not fit (a half beyond 65504) is passed over.
// outputs are every file the chain goes to (a packed output and its plain twin): a type must suit each
// one's container; content is what the first one holds.
Result<StoredChain> chooseStorage(const std::vector<TextureOutput>& outputs, const ChainToWrite& content,
                                  const ChainValues& chains, const TextureWriteOptions& options);

// The attributes that record stored's lookup errors (lookupError, maxLookupError); none for float,
// whose file is the float chain itself.
std::vector<ExrAttribute> lookupErrorAttributes(const StoredChain& stored);

}  // namespace heightpack::detail
