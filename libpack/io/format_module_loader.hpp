// Internal: the OpenImageIO module, loaded on first need (format_module.cpp).
#pragma once

#include <string>

#include "heightpack/core/result.hpp"

#include "image_source.hpp"

namespace heightpack::detail {

// The module, loaded now if it was not; an Internal error naming path (the file that needed it), whose
// text starts with `failed` ("cannot be read"), when it is missing or broken.
Result<ImageModule*> formatModule(const std::string& path, const char* failed);

// OpenImageIO's thread count: applied now if the module is loaded, else when it loads.
void setFormatModuleThreads(int threads);

// The thread count setLibraryThreads gave (0 = all cores, as when it was not called), for heightpack's own
// decoders where they stand in for OpenImageIO's.
int libraryThreads();

}  // namespace heightpack::detail
