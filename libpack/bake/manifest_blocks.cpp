// A map's layout key and whether its pixel type suits it: block formats (BC4, BC5, ASTC) hold plain
// heights or xy normals in a KTX2 or DDS, and a manifest that asks for another pair is told at parse time,
// as heightpack pack and normal tell their command lines.
#include "heightpack/io/pixel_type.hpp"

#include "manifest_parser.hpp"

namespace heightpack::detail {

Layout ManifestParser::layout(Section& s, bool heights) {
    const Layout fallback = heights ? Layout::Neighbour4 : Layout::Rgb;
    const std::optional<std::string> text = s.text("layout");
    if (!text) return fallback;
    const std::optional<Layout> parsed = parseName<Layout>(*text);
    if (!parsed || isHeightLayout(*parsed) != heights)
        throw s.error("layout", "is '" + shorten(*text) + "', but must be one of: " + (heights ? "neighbour4, plain" : "rgb, xy"));
    return *parsed;
}

namespace {

// What to write instead of a block format type in a map of this layout: the layout that holds it, or
// the type that fits this one.
std::string layoutFix(PixelType type, Layout layout) {
    if (layout == Layout::Neighbour4)
        return "set layout = \"plain\" beside it, which the viewer filters in hardware; or pixel_type = \"half\" or "
               "\"uint16\" to keep the packed layout";
    if (layout == Layout::Rgb) return "set layout = \"xy\" beside it; the shader rebuilds z";
    if (type == PixelType::Bc4 || isAstcHdrType(type)) return "for xy normals set pixel_type = \"bc5\" or an LDR \"astc-NxN\"";
    return "for plain heights set pixel_type = \"bc4\"";
}

// Why a map of this layout cannot be stored as type; empty when it can.
std::string layoutProblem(PixelType type, Layout layout) {
    if (layout == Layout::Neighbour4)
        return "each copy of a shared height in the neighbour4 layout would decode differently, and the lookup "
               "would show seams";
    if (layout == Layout::Rgb) return "a block format holds xy normals (two channels), not rgb";
    if (type == PixelType::Bc4 && layout != Layout::Plain) return "bc4 holds one channel: plain heights";
    if (type == PixelType::Bc5 && layout != Layout::Xy) return "bc5 holds two channels: xy normals";
    if (isAstcHdrType(type) && layout != Layout::Plain) return "ASTC HDR holds one channel: plain heights";
    return {};
}

}  // namespace

void ManifestParser::blockFits(Section& s, const MapSettings& settings, Layout layout) {
    const TextureStorage& storage = settings.storage;
    const Container container = settings.container.value_or(Container::Exr);
    const std::string layoutWords = std::string("its layout is ") + nameOf(layout);
    // An error at key, or at the table's line when the value comes from [defaults].
    const auto refuse = [&](const char* key, const std::string& what, const std::string& fix) {
        if (s.find(key)) return s.error(key, what, fix);
        return s.error(s.line(), "[" + s.prefix() + "] takes " + key + " from [defaults], which " + what, fix);
    };
    if (storage.tolerance > 0.0) {
        if (!storage.allowBlockCompression) return;
        const char* key = "allow_block_compression";
        if (layout == Layout::Neighbour4 || layout == Layout::Rgb)
            throw refuse(key, "weighs the block formats, but " + layoutWords + ", which none can hold",
                         std::string("set layout = \"") + (layout == Layout::Rgb ? "xy" : "plain") + "\", or remove it");
        if (container == Container::Exr)
            throw refuse(key, "weighs the block formats, but the output is an EXR, which holds none",
                         "set container = \"ktx2\" or \"dds\", or remove it");
        return;
    }
    const PixelType type = storage.pixelType;
    if (!isBlockType(type)) return;
    const std::string is = std::string("is \"") + pixelTypeName(type) + "\"";
    if (const std::string problem = layoutProblem(type, layout); !problem.empty())
        throw refuse("pixel_type", is + ", but " + layoutWords + ": " + problem, layoutFix(type, layout));
    if (container == Container::Exr)
        throw refuse("pixel_type", is + ", but the output is an EXR, which has no block-compressed texels",
                     "set container = \"ktx2\" or \"dds\"");
    if (container == Container::Dds && isAstcType(type))
        throw refuse("pixel_type", is + ", but the output is a DDS, which has no ASTC format",
                     std::string("set container = \"ktx2\", or pixel_type = \"") + (layout == Layout::Xy ? "bc5" : "bc4") + "\"");
}

}  // namespace heightpack::detail
