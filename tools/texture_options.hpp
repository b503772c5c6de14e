// The options every texture-writing command shares for KTX2 and DDS: --pixel-type, and --compression's
// meaning per container (EXR's codecs, KTX2's zstd, DDS none).
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "heightpack/core/layout.hpp"
#include "heightpack/core/names.hpp"
#include "heightpack/io/exr_write.hpp"
#include "heightpack/io/gpu_texture.hpp"

namespace heightpack {

namespace cli {
// What --pixel-type asks for: one of the pixel types, or auto (pack and normal choose within --tolerance).
enum class PixelTypeRequest { Float, Half, Uint16, Bc4, Bc5, Astc4x4, Astc6x6, Astc8x8, AstcHdr4x4, AstcHdr6x6, AstcHdr8x8, Auto };
}  // namespace cli

template <>
struct NameTable<cli::PixelTypeRequest> {
    using R = cli::PixelTypeRequest;
    static constexpr EnumName<R> entries[] = {
        {R::Float, "float", "32-bit float"},
        {R::Half, "half", "16-bit float, rounded to nearest"},
        {R::Uint16, "uint16", "16-bit normalised to the chain's range, scale and offset recorded; .ktx2 and .dds only"},
        {R::Bc4, "bc4", "block-compressed plain heights (--layout plain), 0.5 byte a texel; .ktx2 and .dds only"},
        {R::Bc5, "bc5", "block-compressed xy normals (--layout xy), 1 byte a texel; .ktx2 and .dds only"},
        {R::Astc4x4, "astc-4x4", "ASTC 4x4 blocks: plain heights (--layout plain) or xy normals (--layout xy), 1 byte a texel; .ktx2 only"},
        {R::Astc6x6, "astc-6x6", "ASTC 6x6 blocks, as astc-4x4 at 0.44 byte a texel; .ktx2 only"},
        {R::Astc8x8, "astc-8x8", "ASTC 8x8 blocks, as astc-4x4 at 0.25 byte a texel; .ktx2 only"},
        {R::AstcHdr4x4, "astc-hdr-4x4", "ASTC HDR 4x4 blocks (decoded as half floats): plain heights (--layout plain), 1 byte a texel; .ktx2 only"},
        {R::AstcHdr6x6, "astc-hdr-6x6", "ASTC HDR 6x6 blocks, as astc-hdr-4x4 at 0.44 byte a texel; .ktx2 only"},
        {R::AstcHdr8x8, "astc-hdr-8x8", "ASTC HDR 8x8 blocks, as astc-hdr-4x4 at 0.25 byte a texel; .ktx2 only"},
        {R::Auto, "auto", "the fewest bytes whose worst lookup error is within --tolerance"},
    };
};

namespace cli {

// Adds --pixel-type to cmd, bound to pixelType: the pixel types (those of `offered`, default all); with
// withAuto also auto and --tolerance (into tolerance), described as toleranceHelp says (default: pack's,
// a length with --height or a number in stored units).
void addPixelTypeOption(CLI::App& cmd, PixelTypeRequest& pixelType, bool withAuto = false, std::string* tolerance = nullptr,
                        const std::string& toleranceHelp = "", std::vector<PixelTypeRequest> offered = {});

// The tolerance --pixel-type auto chooses within, in stored units (0 for a pixel type given), from
// --tolerance's text: a length (1mm, 0.5cm, 2e-3m) divided by heightMetres when that is known (> 0),
// else a plain number (stored units; normal units for normal maps). Returns what is wrong, for usage(),
// or empty.
std::string toleranceInStoredUnits(PixelTypeRequest pixelType, const std::string& text, double heightMetres,
                                   double& tolerance);

// --tolerance for a normal map, whose --height is always given: a plain number is in normal units (into
// storage.tolerance); an angle (2deg) the worst angle between a stored normal and its own, in degrees (into
// storage.tolerance, storage.toleranceInDegrees set); a length with a unit (1mm, 0.5cm) is a height error
// in metres (into metres: the job turns it into normal units, the tilt it makes across one texel). Returns
// what is wrong, for usage(), or empty.
std::string normalTolerance(PixelTypeRequest pixelType, const std::string& text, TextureStorage& storage, double& metres);

// Adds --allow-block-compression, bound to allow: with --pixel-type auto, the block formats are weighed too.
void addBlockChoiceOption(CLI::App& cmd, bool& allow);

// What is wrong with --allow-block-compression as given (allow), for usage(), or empty: it needs
// --pixel-type auto, a layout a block format holds (plain heights, xy normals), and .ktx2 or .dds outputs.
std::string blockChoiceProblem(PixelTypeRequest pixelType, bool allow, Layout layout, const std::vector<std::string>& outputs);

// The pixel type to judge the containers by: auto chooses among those each container holds.
PixelType requestedPixelType(PixelTypeRequest pixelType);

// --json's account of a chain as stored: per level its GPU bytes and worst lookup error (in metres when
// metresPerUnit > 0, else in `units`: "stored", or "normal" for normal maps), and the totals. channels
// as the texture stores them, in each of `layers` layers (the heights, Dx, Dy, foam: an array's layers,
// or an EXR's, each uploaded as its own texture).
nlohmann::json storedChainJson(const std::vector<std::pair<int, int>>& levelSizes, int channels, PixelType type,
                               const std::vector<double>& lookupError, double metresPerUnit,
                               const char* units = "stored", int layers = 1);
// "half, worst lookup error 1.2e-05 m" for a summary line.
std::string storedChainText(PixelType type, const std::vector<double>& lookupError, double metresPerUnit);

// The EXR compressions and the KTX2 one, for --compression's check.
std::vector<std::string> compressionNames();

// --compression's word, read once: an EXR codec (Compression's table), or nullopt for zstd, KTX2's
// supercompression.
struct CompressionChoice {
    std::optional<Compression> exr;
    bool zstd() const { return !exr; }
};
// One of compressionNames() (CLI11 checked it) into its choice.
CompressionChoice readCompression(const std::string& word);

// Checks the pixel type and the compression given (nullopt: none given) against the container of every
// output (by extension); sets supercompression. Returns what is wrong, for usage(), or empty.
std::string checkContainerChoice(const std::vector<std::string>& outputs, PixelType pixelType,
                                 std::optional<CompressionChoice> given, Supercompression& supercompression);

// What is wrong with storing `layout` in a block pixel type (bc4: plain heights only; bc5: xy normals
// only; ASTC: either; never the neighbour4 layout), for usage(), or empty (also for any other pixel type).
std::string blockLayoutProblem(PixelType type, Layout layout);

}  // namespace cli

}  // namespace heightpack
