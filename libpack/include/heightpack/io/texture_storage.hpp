// How a texture's texels are stored: the one choice a command line or a manifest makes and every job
// (pack, normal) and every writer (writeTexture, writeKtx2, writeDds) takes as it is, so it is never
// copied field by field from one struct into another.
#pragma once

#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/pixel_type.hpp"

namespace heightpack {

enum class Supercompression { None, Zstd };

struct TextureStorage {
    PixelType pixelType = PixelType::Float;
    // > 0: "auto": a job chooses pixelType, the fewest bytes whose worst lookup error over the chain is
    // within this many stored units (normal units for normal maps; see chooseStorage in stored_chain.hpp);
    // 0: pixelType as given. The choice is the job's: writers store pixelType and ignore this.
    double tolerance = 0.0;
    // Normal maps: the tolerance is the worst angle, in degrees, between a texel's stored normal and its
    // given one (worstAngleErrorDegrees; a block format's decoded texels), rather than stored units.
    bool toleranceInDegrees = false;
    // With a tolerance: the block formats are weighed too, before half and uint16, fewest bytes first (ASTC
    // 8x8, 6x6, bc4, ASTC 4x4, bc5; one the layout or the container cannot hold is passed over); the first
    // within the tolerance wins (of ASTC 4x4 and bc5, which take as many bytes, the more accurate).
    bool allowBlockCompression = false;
    Compression exrCompression = Compression::Zip;               // EXR outputs
    Supercompression supercompression = Supercompression::None;  // KTX2 outputs; DDS has none
    int zstdLevel = 9;                                           // with Supercompression::Zstd
};

}  // namespace heightpack
