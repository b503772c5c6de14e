// Internal: the build's own work queue.
#pragma once

#include <cstddef>
#include <functional>

namespace heightpack::detail {

// Runs body(i) for every i in [0, count) on up to jobs threads, in order of i as each thread frees up.
// Not parallelFor: that splits [0, count) into fixed contiguous chunks, and assets differ too much in
// cost for that (one 4096^2 map beside a 256-texel ramp); here a free thread takes the next asset.
void forEachParallel(std::size_t count, int jobs, const std::function<void(std::size_t)>& body);

}  // namespace heightpack::detail
