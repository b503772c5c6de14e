#include "command_line.hpp"

#include <cstdio>

#include "heightpack/io/format_module.hpp"

namespace heightpack::cli {

int printFormatReport() {
    const FormatModuleState before = formatModuleState();
    std::printf("decoded by heightpack itself: PNG, OpenEXR, KTX2, DDS (and TOML manifests)\n");
    std::printf("OpenImageIO module (TIFF, JPEG, TGA, BMP, PSD, HDR, PNM): %s, %s\n", before.path.c_str(),
                before.loaded ? "loaded" : "not loaded until a file needs it");
    const FormatModuleState after = loadFormatModule();
    if (!after.loaded) {
        std::fprintf(stderr, "heightpack: error: the OpenImageIO module does not load: %s (reinstall heightpack, or name "
                             "the module's file in %s)\n", after.failure.c_str(), kFormatModuleVariable);
        return static_cast<int>(ExitCode::Internal);
    }
    std::printf("  loading it now to check: %s\n", after.library.c_str());
    return 0;
}

}  // namespace heightpack::cli
