// Whether a texture file loads in a game or web engine as it is: the container and texel format against
// what each engine's loader reads, from the loaders' own source or documentation (docs/formats.md, "Which engine
// loads what", gives the source of every entry). heightpack's outputs are data, not colour: a loader that
// converts them (to 8 bits, dropping the file's mip levels) does not load them faithfully.
#pragma once

#include <string>

#include "heightpack/core/names.hpp"
#include "heightpack/io/info.hpp"

namespace heightpack {

enum class Engine { ThreeJs, Babylon, Unreal, Unity, Godot };

template <>
struct NameTable<Engine> {
    static constexpr EnumName<Engine> entries[] = {
        {Engine::ThreeJs, "three", "three.js (KTX2Loader, DDSLoader, EXRLoader)"},
        {Engine::Babylon, "babylon", "Babylon.js (its KTX2 decoder, DDS and EXR loaders)"},
        {Engine::Unreal, "unreal", "Unreal Engine 5's texture import"},
        {Engine::Unity, "unity", "Unity's texture importers (KTX2 through the KtxUnity package)"},
        {Engine::Godot, "godot", "Godot 4's image loaders"},
    };
};

enum class EngineSupport {
    Loads,    // as stored: every texel and the file's mip levels
    Partial,  // loads with a loss or a condition, said in `why`
    Refuses,  // the loader fails or gives an empty texture
    Unknown,  // no documentation or source says
};

template <>
struct NameTable<EngineSupport> {
    static constexpr EnumName<EngineSupport> entries[] = {
        {EngineSupport::Loads, "loads", "loads as stored"},
        {EngineSupport::Partial, "partial", "loads with a loss or a condition"},
        {EngineSupport::Refuses, "refuses", "does not load"},
        {EngineSupport::Unknown, "unknown", "no source says"},
    };
};

struct EngineVerdict {
    EngineSupport support = EngineSupport::Unknown;
    std::string why;          // the loader's behaviour, in a phrase
    std::string alternative;  // a container and format the engine does load, where one exists; else empty
};

// The verdict for a file whose header is `header` (as readTextureLevels or readFileInfo give it: its
// format names the container and, for KTX2 and DDS, the texel format; its layerNames an array texture)
// with `levels` mip levels.
EngineVerdict engineSupport(Engine engine, const TextureHeader& header, int levels);

}  // namespace heightpack
