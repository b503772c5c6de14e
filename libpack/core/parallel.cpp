#include "heightpack/core/parallel.hpp"

#include <algorithm>
#include <thread>
#include <vector>

namespace heightpack {

int resolveThreadCount(int threads) {
    if (threads > 0) return threads;
    return std::max(1u, std::thread::hardware_concurrency());
}

void parallelFor(int count, int threads, const std::function<void(int, int)>& body) {
    if (count <= 0) return;
    const int workers = std::min(resolveThreadCount(threads), count);
    if (workers == 1) {
        body(0, count);
        return;
    }
    // Contiguous chunks: each thread streams through neighbouring rows, which keeps caches warm.
    std::vector<std::thread> pool;
    pool.reserve(workers - 1);
    auto chunkBegin = [&](int w) { return static_cast<int>(static_cast<long long>(count) * w / workers); };
    for (int w = 1; w < workers; ++w) pool.emplace_back(body, chunkBegin(w), chunkBegin(w + 1));
    body(0, chunkBegin(1));
    for (auto& t : pool) t.join();
}

}  // namespace heightpack
