// The loaders' behaviour behind every entry is cited in docs/formats.md, "Which engine loads what".
#include "heightpack/io/engine_support.hpp"

#include <string>
#include <utility>

namespace heightpack {

namespace {

bool isFloat(TexelFormat t) {
    const ComponentKind k = texelFormatInfo(t).kind;
    return k == ComponentKind::Float32 || k == ComponentKind::Float16;
}
bool isUnorm16(TexelFormat t) { return texelFormatInfo(t).kind == ComponentKind::Unorm16; }
bool isRgtc(TexelFormat t) { return t == TexelFormat::Bc4Unorm || t == TexelFormat::Bc5Unorm; }
bool isAstc(TexelFormat t) { return isAstcType(pixelTypeOf(t)); }
bool isAstcHdr(TexelFormat t) { return isAstcHdrType(pixelTypeOf(t)); }

// The same channels in half floats, which every engine that reads KTX2 or DDS floats loads.
std::string halfOf(TexelFormat t, const char* container) {
    const int channels = texelFormatInfo(t).channels;
    const char* names = channels == 1 ? "R" : channels == 2 ? "RG" : "RGBA";
    return std::string(container) + " " + names + " half or float";
}

EngineVerdict verdict(EngineSupport s, std::string why, std::string alternative = {}) {
    return {s, std::move(why), std::move(alternative)};
}

EngineVerdict threeJs(FileContainer c, TexelFormat t, bool mipmappedExr, bool png16) {
    switch (c) {
        case FileContainer::Ktx2:
            if (isFloat(t)) return verdict(EngineSupport::Loads, "KTX2Loader uploads it as stored, mip levels and all");
            if (t == TexelFormat::Rgba16Unorm)
                return verdict(EngineSupport::Partial, "KTX2Loader loads it only where the GPU has EXT_texture_norm16", halfOf(t, "KTX2"));
            if (isRgtc(t))
                return verdict(EngineSupport::Partial,
                               "KTX2Loader uploads the blocks as stored, mip levels and all, where the WebGL context has "
                               "EXT_texture_compression_rgtc (desktop GPUs; few phones)",
                               halfOf(t, "KTX2"));
            if (pixelTypeOf(t) == PixelType::Astc8x8 || pixelTypeOf(t) == PixelType::AstcHdr8x8)
                return verdict(EngineSupport::Refuses, "KTX2Loader's format map has ASTC 4x4 and 6x6 only", "KTX2 ASTC 6x6 or 4x4");
            if (isAstcHdr(t))
                return verdict(EngineSupport::Partial,
                               "KTX2Loader uploads the SFLOAT blocks as stored (half-float type), decoded as HDR only where "
                               "WEBGL_compressed_texture_astc lists the hdr profile (an LDR-only decoder shows its error colour)",
                               "KTX2 ASTC 4x4 or 6x6 (LDR)");
            if (isAstc(t))
                return verdict(EngineSupport::Partial,
                               "KTX2Loader uploads the blocks as stored, mip levels and all, where the WebGL context has "
                               "WEBGL_compressed_texture_astc (phones, Apple GPUs; few desktop GPUs)",
                               halfOf(t, "KTX2"));
            return verdict(EngineSupport::Refuses, "KTX2Loader's only 16-bit normalised format is RGBA (R16G16B16A16_UNORM)",
                           halfOf(t, "KTX2"));
        case FileContainer::Dds:
            return verdict(EngineSupport::Refuses,
                           "DDSLoader reads DXT1/3/5, ETC1 and 8-bit RGBA DDS, and of the DX10 formats BC6H only",
                           isFloat(t) || isRgtc(t) ? "KTX2 of the same format" : halfOf(t, "KTX2"));
        case FileContainer::Exr:
            if (mipmappedExr) return verdict(EngineSupport::Partial, "EXRLoader reads the top level only: the file's mip levels are lost", "KTX2 float or half");
            return verdict(EngineSupport::Loads, "EXRLoader reads scanline and tiled EXR, float or half");
        case FileContainer::Png:
            if (png16) return verdict(EngineSupport::Partial, "the browser decodes a PNG to 8 bits per channel", "KTX2 R half or float");
            return verdict(EngineSupport::Loads, "an 8-bit image, as the browser decodes it");
        case FileContainer::OtherImage: break;
    }
    return verdict(EngineSupport::Unknown, "not a container heightpack knows three.js's loaders for");
}

EngineVerdict babylon(FileContainer c, TexelFormat t, bool tiledExr, bool png16) {
    switch (c) {
        case FileContainer::Ktx2:
            return verdict(EngineSupport::Refuses, "its KTX2 decoder transcodes Basis (UASTC, ETC1S) files only", "DDS RGBA float or half");
        case FileContainer::Dds:
            if (t == TexelFormat::Rgba32F || t == TexelFormat::Rgba16F)
                return verdict(EngineSupport::Partial,
                               "loads with the file's mip levels, but flips the rows (breaking the neighbour order) unless invertY is false");
            return verdict(EngineSupport::Refuses,
                           "its DDS loader reads DXT1/3/5 blocks and, of the DX10 formats, RGBA float and half only (an empty texture otherwise)",
                           "DDS RGBA float or half");
        case FileContainer::Exr:
            if (tiledExr) return verdict(EngineSupport::Refuses, "its EXR loader rejects tiled files", "DDS RGBA float or half");
            return verdict(EngineSupport::Loads, "its EXR loader reads scanline files (it makes its own mip levels)");
        case FileContainer::Png:
            if (png16) return verdict(EngineSupport::Partial, "the browser decodes a PNG to 8 bits per channel", "DDS RGBA float or half");
            return verdict(EngineSupport::Loads, "an 8-bit image, as the browser decodes it");
        case FileContainer::OtherImage: break;
    }
    return verdict(EngineSupport::Unknown, "not a container heightpack knows Babylon.js's loaders for");
}

EngineVerdict unreal(FileContainer c, TexelFormat, bool mipmappedExr, bool png16) {
    switch (c) {
        case FileContainer::Ktx2: return verdict(EngineSupport::Refuses, "Unreal imports no KTX2 file", "a scanline EXR");
        case FileContainer::Dds:
            return verdict(EngineSupport::Unknown,
                           "Unreal imports .dds, but which DXGI formats it keeps as stored, and whether it compresses blocks again when cooking, is not documented");
        case FileContainer::Exr:
            if (mipmappedExr) return verdict(EngineSupport::Unknown, "Unreal imports EXR (HDR); whether it keeps the file's mip levels is not documented");
            return verdict(EngineSupport::Loads, "Unreal imports EXR as an HDR texture");
        case FileContainer::Png:
            return png16 ? verdict(EngineSupport::Loads, "Unreal imports a 16-bit grey PNG as G16")
                         : verdict(EngineSupport::Loads, "an 8-bit image");
        case FileContainer::OtherImage: break;
    }
    return verdict(EngineSupport::Unknown, "not a container heightpack knows Unreal's importers for");
}

EngineVerdict unity(FileContainer c, TexelFormat t, bool mipmappedExr, bool png16) {
    switch (c) {
        case FileContainer::Ktx2:
            return verdict(EngineSupport::Refuses, "Unity reads KTX2 through the KtxUnity package, which reads supercompressed (Basis) files only", "a scanline EXR");
        case FileContainer::Dds:
            if (isRgtc(t))
                return verdict(EngineSupport::Loads,
                               "IHVImageFormatImporter imports a .dds's compressed blocks as they are, bypassing Unity's texture importer");
            return verdict(EngineSupport::Unknown, "Unity imports .dds raw, but which DXGI formats is not documented");
        case FileContainer::Exr:
            if (mipmappedExr) return verdict(EngineSupport::Unknown, "Unity imports EXR; whether it keeps the file's mip levels is not documented");
            return verdict(EngineSupport::Loads, "Unity imports EXR as an HDR texture");
        case FileContainer::Png:
            return png16 ? verdict(EngineSupport::Unknown, "whether Unity keeps a PNG's 16 bits is not documented")
                         : verdict(EngineSupport::Loads, "an 8-bit image");
        case FileContainer::OtherImage: break;
    }
    return verdict(EngineSupport::Unknown, "not a container heightpack knows Unity's importers for");
}

EngineVerdict godot(FileContainer c, TexelFormat t, bool mipmappedExr, bool png16) {
    switch (c) {
        case FileContainer::Ktx2:
        case FileContainer::Dds: {
            const char* name = c == FileContainer::Ktx2 ? "KTX2" : "DDS";
            if (isFloat(t)) return verdict(EngineSupport::Loads, std::string("its ") + name + " loader keeps the format and the file's mip levels");
            if (isRgtc(t))
                return verdict(EngineSupport::Loads, std::string("its ") + name + " loader keeps the BC4/BC5 (RGTC) blocks and the file's mip levels");
            if (isAstcHdr(t))
                return verdict(EngineSupport::Refuses, "its KTX2 loader reads UNORM ASTC (4x4, 8x8) only, no SFLOAT (HDR) format",
                               "KTX2 ASTC 4x4 or 8x8 (LDR)");
            if (pixelTypeOf(t) == PixelType::Astc6x6)
                return verdict(EngineSupport::Refuses, "its KTX2 loader reads ASTC 4x4 and 8x8 only", "KTX2 ASTC 4x4 or 8x8");
            if (isAstc(t))
                return verdict(EngineSupport::Loads, "its KTX2 loader keeps the ASTC blocks and the file's mip levels");
            if (isUnorm16(t))
                return verdict(EngineSupport::Partial, std::string("only the newest Godot 4 releases read 16-bit integer ") + name, halfOf(t, name));
            return verdict(EngineSupport::Refuses, std::string("its ") + name + " loader has no two-channel signed 16-bit format", halfOf(t, name));
        }
        case FileContainer::Exr:
            if (mipmappedExr)
                return verdict(EngineSupport::Partial, "its EXR loader reads the top level only; the importer makes its own mip levels", "KTX2 or DDS float or half");
            return verdict(EngineSupport::Loads, "its EXR loader reads scanline EXR, float or half");
        case FileContainer::Png:
            if (png16) return verdict(EngineSupport::Partial, "Godot imports PNG at 8 bits per channel", "KTX2 R half or float");
            return verdict(EngineSupport::Loads, "an 8-bit image");
        case FileContainer::OtherImage: break;
    }
    return verdict(EngineSupport::Unknown, "not a container heightpack knows Godot's loaders for");
}

// An array texture (the heights, Dx, Dy, foam as layers of one texture) in a loader that takes its format.
EngineVerdict arrayOf(Engine engine, FileContainer c, EngineVerdict single) {
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
            if (c == FileContainer::Ktx2)
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
    const FileContainer c = header.container;
    const bool gpuContainer = c == FileContainer::Ktx2 || c == FileContainer::Dds;
    if (gpuContainer && !header.texelFormat)
        return verdict(EngineSupport::Unknown, "no entry for this texel format in heightpack's engines table");
    // EXR and PNG have no texel format; the loaders below ask for one only of KTX2 and DDS.
    const TexelFormat t = header.texelFormat.value_or(TexelFormat::Rgba32F);
    const bool mipmappedExr = c == FileContainer::Exr && levels > 1;
    const bool png16 = c == FileContainer::Png && header.description.componentBytes == 2;
    EngineVerdict single;
    switch (engine) {
        case Engine::ThreeJs: single = threeJs(c, t, mipmappedExr, png16); break;
        case Engine::Babylon: single = babylon(c, t, c == FileContainer::Exr && header.storedInTiles, png16); break;
        case Engine::Unreal: single = unreal(c, t, mipmappedExr, png16); break;
        case Engine::Unity: single = unity(c, t, mipmappedExr, png16); break;
        case Engine::Godot: single = godot(c, t, mipmappedExr, png16); break;
    }
    return header.layerNames.empty() ? single : arrayOf(engine, c, std::move(single));
}

}  // namespace heightpack
