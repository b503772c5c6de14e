// Splitting row loops over threads. Every output element is computed by exactly one thread with the
// same arithmetic in the same order, so results are identical whatever the thread count.
#pragma once

#include <functional>

namespace heightpack {

// The number of threads that `threads` asks for: itself when positive, else the hardware's count.
int resolveThreadCount(int threads);

// Calls body(begin, end) on contiguous, disjoint chunks that together cover [0, count), using up to
// `threads` threads (0 = all cores). Returns when every chunk is done.
void parallelFor(int count, int threads, const std::function<void(int begin, int end)>& body);

}  // namespace heightpack
