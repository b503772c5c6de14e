// The module that decodes and writes the formats heightpack has no code of its own for (TIFF, JPEG, TGA,
// BMP, PSD, HDR, PNM, ...) through OpenImageIO. It is loaded the first time a file needs it, so a process
// that touches only PNG, EXR, KTX2, DDS and TOML never maps OpenImageIO and its ~260 libraries.
#pragma once

#include <string>

namespace heightpack {

// Where the module is and whether this process has loaded it.
struct FormatModuleState {
    bool loaded = false;
    std::string path;     // the file loaded, or (not yet loaded) the one that would be
    std::string library;  // "OpenImageIO 2.4.7" once loaded
    std::string failure;  // why loading failed, when it did
};

// The state now; never loads the module.
FormatModuleState formatModuleState();

// Loads the module if this process has not; its state afterwards.
FormatModuleState loadFormatModule();

// The environment variable that names the module's file, for an install that moved it.
inline constexpr const char* kFormatModuleVariable = "HEIGHTPACK_FORMAT_MODULE";

}  // namespace heightpack
