// Internal: the steps the file-to-file jobs (pack, normal) share, so they load, check sizes and label
// their outputs the same way.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "heightpack/core/mip.hpp"
#include "heightpack/io/attributes.hpp"
#include "heightpack/io/read.hpp"

namespace heightpack::detail {

struct LoadedInput {
    Image heights;
    SourceInfo source;
    std::string hash;  // of the decoded pixels, before any scaling or resizing
};

// Loads input with options (threads as given), hashing what was decoded.
Result<LoadedInput> loadInput(const std::string& input, LoadOptions options, int threads);

// Makes heights' sides powers of two: resamples them up to the next ones with mip's filter and wrap when
// resize is set (returns true), else fails with BadInput and Fix::ResizeToPowerOfTwo (the size it would
// get in fixArgs), or Fix::ResizeOrLevelZeroOnly when levelZeroAlone says that writing level 0 alone is
// another way out. Returns false when nothing needed doing.
Result<bool> ensurePowerOfTwo(Image& heights, const std::string& input, bool resize, const MipOptions& mip,
                              bool levelZeroAlone = false);

// The attributes every heightpack texture carries: layout, wrap (and OpenImageIO's wrapmodes), filter,
// texel centre, source file name, source hash, version.
std::vector<ExrAttribute> commonAttributes(std::string_view layout, Wrap wrap, Filter filter, const SourceInfo& source,
                                           const std::string& hash, const std::string& version);

}  // namespace heightpack::detail
