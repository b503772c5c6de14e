// Internal: an OpenEXR file decoded by OpenEXR directly, presented as OpenImageIO presents it.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "image_source.hpp"

namespace heightpack::detail {

// A decoder over the bytes of an EXR (kept alive by the caller); null where OpenImageIO is to read the
// file instead (anything this does not present exactly as OpenImageIO would, or any file OpenEXR refuses).
std::unique_ptr<ImageSource> openExrDirectly(const unsigned char* bytes, size_t size, const std::string& path);

}  // namespace heightpack::detail
