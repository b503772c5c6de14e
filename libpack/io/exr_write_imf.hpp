// Internal: what the two tiled EXR writers share, and the one on OpenEXR's C++ library (rle, piz), which
// implements those codecs; exr_write.cpp writes none, zip and zips itself on OpenEXRCore.
#pragma once

#include <cstddef>
#include <string>

#include "heightpack/io/exr_write.hpp"

namespace heightpack::detail {

// The last guard before bytes reach a file: an output never holds NaN or infinity. Whatever let one
// through (an option or input check missing) is a bug, reported as one.
Status requireFinite(const std::string& path, const float* values, size_t count, int level);

// Writes content as writeTiledExr describes, through Imf::TiledOutputFile, to path (the temporary file
// whose errors are reported under finalPath).
Status writeTiledWithImf(const std::string& finalPath, const std::string& path, const MipChainSource& content,
                         const ExrWriteOptions& options);

}  // namespace heightpack::detail
