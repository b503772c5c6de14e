#include "heightpack/bake/pack_foam.hpp"

#include <cassert>

#include "heightpack/core/mip.hpp"

#include "job_steps.hpp"

namespace heightpack {

Result<std::vector<Image>> foamChain(Image foam, const SourceInfo& source, const PackOptions& options) {
    assert(foam.channels == 1);
    auto resized = detail::ensurePowerOfTwo(foam, source.path, options.resizeToPowerOfTwo, options.mip);
    if (!resized) return resized.error();
    return generateMipChain(foam, options.mip);
}

}  // namespace heightpack
