// The loaders' behaviour behind every entry is cited in docs/formats.md, "Which engine loads what".
#include "heightpack/io/engine_support.hpp"

#include <string>
#include <string_view>
#include <utility>

#include "heightpack/io/info.hpp"
#include "heightpack/io/pixel_type.hpp"

namespace heightpack {

namespace {

// The texel formats heightpack writes to KTX2 and DDS, by what a loader tells apart.
// R16G16_SNORM: xy normals in uint16 as earlier versions wrote them (read, no longer written).
enum class Texel { Rgba32F, Rgba16F, Rgba16Unorm, R32F, R16F, R16Unorm, Rg32F, Rg16F, Rg16Unorm, Rg16Snorm, Other };

Texel texelOf(TexelFormat format) {
    switch (format) {
        case TexelFormat::Rgba32F: return Texel::Rgba32F;
        case TexelFormat::Rgba16F: return Texel::Rgba16F;
        case TexelFormat::Rgba16Unorm: return Texel::Rgba16Unorm;
        case TexelFormat::R32F: return Texel::R32F;
        case TexelFormat::R16F: return Texel::R16F;
        case TexelFormat::R16Unorm: return Texel::R16Unorm;
        case TexelFormat::Rg32F: return Texel::Rg32F;
        case TexelFormat::Rg16F: return Texel::Rg16F;
        case TexelFormat::Rg16Unorm: return Texel::Rg16Unorm;
        case TexelFormat::Rg16Snorm: return Texel::Rg16Snorm;
        case TexelFormat::Bc4Unorm:
        case TexelFormat::Bc5Unorm: return Texel::Other;
    }
    return Texel::Other;
}

bool isFloat(Texel t) {
    return t == Texel::Rgba32F || t == Texel::Rgba16F || t == Texel::R32F || t == Texel::R16F || t == Texel::Rg32F || t == Texel::Rg16F;
}

// The same channels in half floats, which every engine that reads KTX2 or DDS floats loads.
std::string halfOf(Texel t, const char* container) {
    const char* channels = t == Texel::Rgba16Unorm ? "RGBA" : t == Texel::R16Unorm ? "R" : "RG";
    return std::string(container) + " " + channels + " half or float";
}

EngineVerdict verdict(EngineSupport s, std::string why, std::string alternative = {}) {
    return {s, std::move(why), std::move(alternative)};
}

EngineVerdict threeJs(FileKind c, Texel t, bool mipmappedExr, bool png16) {
    switch (c) {
        case FileKind::Ktx2:
            if (isFloat(t)) return verdict(EngineSupport::Loads, "KTX2Loader uploads it as stored, mip levels and all");
            if (t == Texel::Rgba16Unorm)
                return verdict(EngineSupport::Partial, "KTX2Loader loads it only where the GPU has EXT_texture_norm16", halfOf(t, "KTX2"));
            return verdict(EngineSupport::Refuses, "KTX2Loader's only 16-bit normalised format is RGBA (R16G16B16A16_UNORM)",
                           halfOf(t, "KTX2"));
        case FileKind::Dds:
            return verdict(EngineSupport::Refuses, "DDSLoader reads block-compressed and 8-bit RGBA DDS only, no DX10 float or 16-bit format",
                           isFloat(t) ? "KTX2 of the same format" : halfOf(t, "KTX2"));
        case FileKind::Exr:
            if (mipmappedExr) return verdict(EngineSupport::Partial, "EXRLoader reads the top level only: the file's mip levels are lost", "KTX2 float or half");
            return verdict(EngineSupport::Loads, "EXRLoader reads scanline and tiled EXR, float or half");
        case FileKind::Png:
            if (png16) return verdict(EngineSupport::Partial, "the browser decodes a PNG to 8 bits per channel", "KTX2 R half or float");
            return verdict(EngineSupport::Loads, "an 8-bit image, as the browser decodes it");
        case FileKind::Other: break;
    }
    return verdict(EngineSupport::Unknown, "not a container heightpack knows three.js's loaders for");
}

EngineVerdict babylon(FileKind c, Texel t, bool tiledExr, bool png16) {
    switch (c) {
        case FileKind::Ktx2:
            return verdict(EngineSupport::Refuses, "its KTX2 decoder transcodes Basis (UASTC, ETC1S) files only", "DDS RGBA float or half");
        case FileKind::Dds:
            if (t == Texel::Rgba32F || t == Texel::Rgba16F)
                return verdict(EngineSupport::Partial,
                               "loads with the file's mip levels, but flips the rows (breaking the neighbour order) unless invertY is false");
            return verdict(EngineSupport::Refuses, "its DDS loader reads RGBA float and half only (an empty texture otherwise)", "DDS RGBA float or half");
        case FileKind::Exr:
            if (tiledExr) return verdict(EngineSupport::Refuses, "its EXR loader rejects tiled files", "DDS RGBA float or half");
            return verdict(EngineSupport::Loads, "its EXR loader reads scanline files (it makes its own mip levels)");
        case FileKind::Png:
            if (png16) return verdict(EngineSupport::Partial, "the browser decodes a PNG to 8 bits per channel", "DDS RGBA float or half");
            return verdict(EngineSupport::Loads, "an 8-bit image, as the browser decodes it");
        case FileKind::Other: break;
    }
    return verdict(EngineSupport::Unknown, "not a container heightpack knows Babylon.js's loaders for");
}

EngineVerdict unreal(FileKind c, Texel, bool mipmappedExr, bool png16) {
    switch (c) {
        case FileKind::Ktx2: return verdict(EngineSupport::Refuses, "Unreal imports no KTX2 file", "a scanline EXR");
        case FileKind::Dds: return verdict(EngineSupport::Unknown, "Unreal imports .dds, but which DXGI formats it keeps is not documented");
        case FileKind::Exr:
            if (mipmappedExr) return verdict(EngineSupport::Unknown, "Unreal imports EXR (HDR); whether it keeps the file's mip levels is not documented");
            return verdict(EngineSupport::Loads, "Unreal imports EXR as an HDR texture");
        case FileKind::Png:
            return png16 ? verdict(EngineSupport::Loads, "Unreal imports a 16-bit grey PNG as G16")
                         : verdict(EngineSupport::Loads, "an 8-bit image");
        case FileKind::Other: break;
    }
    return verdict(EngineSupport::Unknown, "not a container heightpack knows Unreal's importers for");
}

EngineVerdict unity(FileKind c, Texel, bool mipmappedExr, bool png16) {
    switch (c) {
        case FileKind::Ktx2:
            return verdict(EngineSupport::Refuses, "Unity reads KTX2 through the KtxUnity package, which reads supercompressed (Basis) files only", "a scanline EXR");
        case FileKind::Dds: return verdict(EngineSupport::Unknown, "Unity imports .dds raw, but which DXGI formats is not documented");
        case FileKind::Exr:
            if (mipmappedExr) return verdict(EngineSupport::Unknown, "Unity imports EXR; whether it keeps the file's mip levels is not documented");
            return verdict(EngineSupport::Loads, "Unity imports EXR as an HDR texture");
        case FileKind::Png:
            return png16 ? verdict(EngineSupport::Unknown, "whether Unity keeps a PNG's 16 bits is not documented")
                         : verdict(EngineSupport::Loads, "an 8-bit image");
        case FileKind::Other: break;
    }
    return verdict(EngineSupport::Unknown, "not a container heightpack knows Unity's importers for");
}

EngineVerdict godot(FileKind c, Texel t, bool mipmappedExr, bool png16) {
    switch (c) {
        case FileKind::Ktx2:
        case FileKind::Dds: {
            const char* name = c == FileKind::Ktx2 ? "KTX2" : "DDS";
            if (isFloat(t)) return verdict(EngineSupport::Loads, std::string("its ") + name + " loader keeps the format and the file's mip levels");
            if (t == Texel::Rgba16Unorm || t == Texel::R16Unorm || t == Texel::Rg16Unorm)
                return verdict(EngineSupport::Partial, std::string("only the newest Godot 4 releases read 16-bit integer ") + name, halfOf(t, name));
            return verdict(EngineSupport::Refuses, std::string("its ") + name + " loader has no two-channel signed 16-bit format", halfOf(t, name));
        }
        case FileKind::Exr:
            if (mipmappedExr)
                return verdict(EngineSupport::Partial, "its EXR loader reads the top level only; the importer makes its own mip levels", "KTX2 or DDS float or half");
            return verdict(EngineSupport::Loads, "its EXR loader reads scanline EXR, float or half");
        case FileKind::Png:
            if (png16) return verdict(EngineSupport::Partial, "Godot imports PNG at 8 bits per channel", "KTX2 R half or float");
            return verdict(EngineSupport::Loads, "an 8-bit image");
        case FileKind::Other: break;
    }
    return verdict(EngineSupport::Unknown, "not a container heightpack knows Godot's loaders for");
}

// An array texture (the heights, Dx, Dy, foam as layers of one texture) in a loader that takes its format.
EngineVerdict arrayOf(Engine engine, FileKind c, EngineVerdict single) {
    if (single.support == EngineSupport::Refuses || single.support == EngineSupport::Unknown) return single;
    switch (engine) {
        case Engine::ThreeJs:  // only KTX2 gets here
            return verdict(EngineSupport::Partial,
                           "KTX2Loader makes a 2D DataTexture of an uncompressed file whatever its layerCount (arrays only "
                           "for Basis files): layer 0, the heights, loads; the other layers stay unused in each level's data");
        case Engine::Babylon:  // only DDS RGBA float or half gets here
            return verdict(EngineSupport::Partial,
                           "its DDS loader reads no array size: layer 0, the heights, loads as a 2D texture (with invertY = false)");
        case Engine::Godot:
            if (c == FileKind::Ktx2)
                return verdict(EngineSupport::Refuses, "its KTX2 loader refuses array textures", "DDS of the same format");
            return verdict(single.support, "its DDS loader makes a Texture2DArray of a DX10 array, the file's mip levels and all" +
                                               (single.support == EngineSupport::Partial ? "; " + single.why : std::string()),
                           single.alternative);
        case Engine::Unreal:
        case Engine::Unity: break;
    }
    return single;
}

}  // namespace

EngineVerdict engineSupport(Engine engine, const TextureHeader& header, int levels) {
    const FileKind c = header.kind;
    const Texel texel = header.texelFormat ? texelOf(*header.texelFormat) : Texel::Other;
    if ((c == FileKind::Ktx2 || c == FileKind::Dds) && texel == Texel::Other)
        return verdict(EngineSupport::Unknown, "no entry for this texel format in heightpack's engines table");
    const bool mipmappedExr = c == FileKind::Exr && levels > 1;
    const bool png16 = c == FileKind::Png && header.description.componentBytes == 2;
    EngineVerdict single;
    switch (engine) {
        case Engine::ThreeJs: single = threeJs(c, texel, mipmappedExr, png16); break;
        case Engine::Babylon: single = babylon(c, texel, c == FileKind::Exr && header.storedInTiles, png16); break;
        case Engine::Unreal: single = unreal(c, texel, mipmappedExr, png16); break;
        case Engine::Unity: single = unity(c, texel, mipmappedExr, png16); break;
        case Engine::Godot: single = godot(c, texel, mipmappedExr, png16); break;
    }
    return header.layerNames.empty() ? single : arrayOf(engine, c, std::move(single));
}

}  // namespace heightpack
