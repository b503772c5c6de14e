#include "texture_options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "heightpack/io/texture_write.hpp"

#include "command.hpp"
#include "enum_option.hpp"

namespace heightpack::cli {

void addPixelTypeOption(CLI::App& cmd, PixelTypeRequest& pixelType, bool withAuto, std::string* tolerance,
                        const std::string& toleranceHelp, std::vector<PixelTypeRequest> offered) {
    if (offered.empty())
        offered = {PixelTypeRequest::Float,      PixelTypeRequest::Half,       PixelTypeRequest::Uint16,
                   PixelTypeRequest::Bc4,        PixelTypeRequest::Bc5,        PixelTypeRequest::Astc4x4,
                   PixelTypeRequest::Astc6x6,    PixelTypeRequest::Astc8x8,    PixelTypeRequest::AstcHdr4x4,
                   PixelTypeRequest::AstcHdr6x6, PixelTypeRequest::AstcHdr8x8};
    if (withAuto) offered.push_back(PixelTypeRequest::Auto);
    std::string help;
    for (const PixelTypeRequest r : offered) help += (help.empty() ? "" : "; ") + std::string(nameOf(r)) + ": " + describe(r);
    addEnumOption(cmd, "--pixel-type", pixelType, help, offered);
    if (withAuto && tolerance)
        cmd.add_option("--tolerance", *tolerance,
                       !toleranceHelp.empty() ? toleranceHelp
                                              : "with --pixel-type auto: the worst lookup error allowed over the chain; a "
                                                "length (1mm, 0.5cm) when --height is given, else a number in stored units");
}

void addBlockChoiceOption(CLI::App& cmd, bool& allow) {
    cmd.add_flag("--allow-block-compression", allow,
                 "with --pixel-type auto: weigh the block formats too (.ktx2: ASTC 8x8, 6x6, bc4, ASTC 4x4, bc5; "
                 ".dds: bc4, bc5), the fewest bytes within --tolerance");
}

std::string blockChoiceProblem(PixelTypeRequest pixelType, bool allow, Layout layout, const std::vector<std::string>& outputs) {
    if (!allow) return {};
    if (pixelType != PixelTypeRequest::Auto)
        return std::string("--allow-block-compression is for --pixel-type auto, which weighs the block formats with the "
                           "others; leave it out with --pixel-type ") + nameOf(pixelType);
    if (layout != Layout::Plain && layout != Layout::Xy)
        return std::string("--allow-block-compression: the ") + nameOf(layout) +
               " layout cannot be block-compressed (write --layout plain for heights, --layout xy for normals)";
    for (const std::string& path : outputs) {
        const auto c = containerForPath(path);
        if (!path.empty() && c != Container::Ktx2 && c != Container::Dds)
            return path + ": --allow-block-compression needs a .ktx2 or .dds output (an EXR has no block-compressed "
                          "texels)";
    }
    return {};
}

namespace {

std::optional<double> plainNumber(const std::string& text) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end == text.c_str() || *end != '\0' || !std::isfinite(v) || v <= 0) return std::nullopt;
    return v;
}

}  // namespace

std::string toleranceInStoredUnits(PixelTypeRequest pixelType, const std::string& text, double heightMetres,
                                   double& tolerance) {
    tolerance = 0.0;
    if (pixelType != PixelTypeRequest::Auto) {
        if (text.empty()) return {};
        return "--tolerance '" + text + "' is for --pixel-type auto (which picks the type); leave it out with --pixel-type " +
               nameOf(pixelType);
    }
    if (text.empty())
        return "--pixel-type auto needs --tolerance, the worst lookup error allowed: a length like 1mm with --height, "
               "or a number in stored units like 0.0005";
    if (heightMetres > 0.0) {
        const auto metres = parseLength(text);
        if (!metres) return "--tolerance '" + text + "' is not a positive length like 1mm, 0.5cm or 2e-3m";
        tolerance = *metres / heightMetres;
        return {};
    }
    if (const auto v = plainNumber(text)) {
        tolerance = *v;
        return {};
    }
    if (parseLength(text))
        return "--tolerance '" + text + "' is a length, but without --height there are no metres to convert it from: "
               "give --height, or a number in stored units";
    if (text.size() > 3 && text.compare(text.size() - 3, 3, "deg") == 0)
        return "--tolerance '" + text + "' is an angle, which only a normal map's error is measured in: give a length "
               "with --height, or a number in stored units";
    return "--tolerance '" + text + "' is not a positive number";
}

std::string normalTolerance(PixelTypeRequest pixelType, const std::string& text, TextureStorage& storage, double& metres) {
    metres = 0.0;
    storage.toleranceInDegrees = false;
    if (pixelType != PixelTypeRequest::Auto || text.empty() || plainNumber(text))
        return toleranceInStoredUnits(pixelType, text, 0.0, storage.tolerance);
    storage.tolerance = 0.0;
    for (const std::string_view unit : {"deg", "\u00b0"})  // 2deg, 2°
        if (text.size() > unit.size() && text.compare(text.size() - unit.size(), unit.size(), unit) == 0) {
            const auto degrees = plainNumber(text.substr(0, text.size() - unit.size()));
            if (!degrees || *degrees >= 180.0)
                return "--tolerance '" + text + "' is not an angle between 0 and 180 degrees, like 0.5deg";
            storage.tolerance = *degrees;
            storage.toleranceInDegrees = true;
            return {};
        }
    if (const auto length = parseLength(text)) {
        metres = *length;
        return {};
    }
    return "--tolerance '" + text + "' is neither a number (normal units), an angle like 0.5deg, nor a length like 1mm or 0.5cm";
}

PixelType requestedPixelType(PixelTypeRequest pixelType) {
    switch (pixelType) {
        case PixelTypeRequest::Half: return PixelType::Half;
        case PixelTypeRequest::Uint16: return PixelType::Uint16;
        case PixelTypeRequest::Bc4: return PixelType::Bc4;
        case PixelTypeRequest::Bc5: return PixelType::Bc5;
        case PixelTypeRequest::Astc4x4: return PixelType::Astc4x4;
        case PixelTypeRequest::Astc6x6: return PixelType::Astc6x6;
        case PixelTypeRequest::Astc8x8: return PixelType::Astc8x8;
        case PixelTypeRequest::AstcHdr4x4: return PixelType::AstcHdr4x4;
        case PixelTypeRequest::AstcHdr6x6: return PixelType::AstcHdr6x6;
        case PixelTypeRequest::AstcHdr8x8: return PixelType::AstcHdr8x8;
        case PixelTypeRequest::Float:
        case PixelTypeRequest::Auto: break;  // auto: judged as float, which every container holds, until the job chooses
    }
    return PixelType::Float;
}

nlohmann::json storedChainJson(const std::vector<std::pair<int, int>>& levelSizes, int channels, PixelType type,
                               const std::vector<double>& lookupError, double metresPerUnit, const char* units,
                               int layers) {
    const double toUnits = metresPerUnit > 0.0 ? metresPerUnit : 1.0;
    nlohmann::json levels = nlohmann::json::array();
    size_t total = 0;
    double worst = 0.0;
    for (size_t i = 0; i < levelSizes.size(); ++i) {
        const size_t bytes = gpuBytes(levelSizes[i].first, levelSizes[i].second, channels, type) * size_t(layers);
        const double error = i < lookupError.size() ? lookupError[i] * toUnits : 0.0;
        total += bytes;
        worst = std::max(worst, error);
        levels.push_back({{"level", i}, {"width", levelSizes[i].first}, {"height", levelSizes[i].second},
                          {"gpuBytes", bytes}, {"lookupError", error}});
    }
    return {{"pixelType", pixelTypeName(type)},
            {"gpuBytes", total},
            {"lookupError", {{"units", metresPerUnit > 0.0 ? "m" : units}, {"worst", worst}}},
            {"levels", levels}};
}

std::string storedChainText(PixelType type, const std::vector<double>& lookupError, double metresPerUnit) {
    double worst = 0.0;
    for (const double e : lookupError) worst = std::max(worst, e);
    char text[96];
    std::snprintf(text, sizeof text, "%s, worst lookup error %.3g%s", pixelTypeName(type),
                  worst * (metresPerUnit > 0.0 ? metresPerUnit : 1.0), metresPerUnit > 0.0 ? " m" : "");
    return text;
}

// KTX2's supercompression, the one --compression word that names no EXR codec.
constexpr const char* kZstdWord = "zstd";

std::vector<std::string> compressionNames() {
    std::vector<std::string> names;
    for (const auto& name : allNames<Compression>()) names.emplace_back(name);
    names.emplace_back(kZstdWord);
    return names;
}

CompressionChoice readCompression(const std::string& word) {
    return word == kZstdWord ? CompressionChoice{} : CompressionChoice{parseName<Compression>(word).value_or(Compression::Zip)};
}

std::string checkContainerChoice(const std::vector<std::string>& outputs, PixelType pixelType,
                                 std::optional<CompressionChoice> given, Supercompression& supercompression) {
    const bool none = given && given->exr == Compression::None, zstd = given && given->zstd();
    supercompression = Supercompression::None;
    for (const std::string& path : outputs) {
        if (path.empty()) continue;
        const auto c = containerForPath(path);
        if (c == Container::Ktx2) {
            if (given && !none && !zstd) return path + ": a KTX2 takes --compression none or zstd";
            if (zstd) supercompression = Supercompression::Zstd;
        } else if (c == Container::Dds) {
            if (isAstcType(pixelType))
                return path + ": --pixel-type " + pixelTypeName(pixelType) +
                       " needs a .ktx2 output (DDS and Direct3D have no ASTC format; for a .dds write --pixel-type bc4 "
                       "for heights or bc5 for xy normals)";
            if (given && !none) return path + ": a DDS is stored uncompressed: leave out --compression";
        } else {
            if (pixelType == PixelType::Uint16)
                return path + ": --pixel-type uint16 needs a .ktx2 or .dds output (an EXR has no 16-bit normalised "
                              "channels)";
            if (isAstcType(pixelType))
                return path + ": --pixel-type " + pixelTypeName(pixelType) +
                       " needs a .ktx2 output (an EXR has no block-compressed texels; store float or half in an EXR)";
            if (isBlockType(pixelType))
                return path + ": --pixel-type " + pixelTypeName(pixelType) +
                       " needs a .ktx2 or .dds output (an EXR has no block-compressed texels; store float or half in "
                       "an EXR)";
            if (zstd) return path + ": --compression zstd is for .ktx2 outputs";
        }
    }
    return {};
}

std::string blockLayoutProblem(PixelType type, Layout layout) {
    if (!isBlockType(type)) return {};
    const std::string name = pixelTypeName(type);
    if (layout == Layout::Neighbour4)
        return "--pixel-type " + name + " cannot hold the neighbour4 layout: each copy of a shared height would "
               "decode differently and the lookup would show seams (write --layout plain and filter in hardware, or "
               "view it with --lookup gather)";
    if (isAstcHdrType(type) && layout != Layout::Plain)
        return "--pixel-type " + name + " stores plain heights (--layout plain): HDR blocks hold one channel (for xy "
               "normals write --pixel-type astc-" + name.substr(9) + ")";
    if (isAstcType(type) && layout != Layout::Plain && layout != Layout::Xy)
        return "--pixel-type " + name + " stores plain heights (--layout plain) or xy normals (--layout xy)";
    if (type == PixelType::Bc4 && layout != Layout::Plain)
        return "--pixel-type bc4 holds one channel: it stores plain heights (for normals write --layout xy "
               "--pixel-type bc5)";
    if (type == PixelType::Bc5 && layout != Layout::Xy)
        return "--pixel-type bc5 holds two channels: it stores xy normals (write --layout xy, or for heights "
               "--layout plain --pixel-type bc4)";
    return {};
}

}  // namespace heightpack::cli
