#include "work_queue.hpp"

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace heightpack::detail {

void forEachParallel(std::size_t count, int jobs, const std::function<void(std::size_t)>& body) {
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
        for (std::size_t i = next++; i < count; i = next++) body(i);
    };
    std::vector<std::thread> pool;
    const std::size_t extra =
        std::min<std::size_t>(count, static_cast<std::size_t>(std::max(1, jobs))) - (count > 0 ? 1 : 0);
    for (std::size_t k = 0; k < extra; ++k) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
}

}  // namespace heightpack::detail
