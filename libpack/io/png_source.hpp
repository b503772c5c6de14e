// Internal: a grey PNG decoded by heightpack's own decoder, presented as OpenImageIO presents it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "image_source.hpp"

namespace heightpack::detail {

// A decoder over a PNG's bytes (whose buffer the caller keeps alive); null where OpenImageIO is to read the
// file instead.
std::unique_ptr<ImageSource> openPngDirectly(const std::vector<unsigned char>& bytes, const std::string& path);

}  // namespace heightpack::detail
