#include "ordered_writes.hpp"

#include <condition_variable>
#include <mutex>
#include <vector>

#include "heightpack/core/parallel.hpp"

namespace heightpack::detail {

Status makeAndWriteInOrder(size_t count, int workers, size_t slots, EarlyWriteback& writeback,
                           const std::function<Status(size_t piece, size_t slot, int worker)>& make,
                           const std::function<Result<size_t>(size_t piece, size_t slot)>& write) {
    if (count == 0) return Done{};
    struct Made {
        Status status = Done{};
        bool ready = false;
    };
    std::vector<Made> made(slots);
    std::mutex lock;
    std::condition_variable changed;
    size_t taken = 0, written = 0;
    bool stop = false;
    Status outcome = Done{};
    // Writes the pieces made, in order from `written` on; called with the lock held. Returns the bytes.
    auto writeReady = [&] {
        size_t bytes = 0;
        for (; written < count && made[written % slots].ready && !stop; ++written) {
            Made& m = made[written % slots];
            m.ready = false;
            if (!m.status) {
                outcome = m.status, stop = true;
                break;
            }
            Result<size_t> wrote = write(written, written % slots);
            if (!wrote) {
                outcome = wrote.error(), stop = true;
                break;
            }
            bytes += *wrote;
        }
        return bytes;
    };
    parallelFor(workers, workers, [&](int first, int last) {
        for (int worker = first; worker < last; ++worker)
            for (;;) {
                size_t piece = 0;
                {
                    std::unique_lock<std::mutex> held(lock);
                    changed.wait(held, [&] { return stop || taken == count || taken < written + slots; });
                    if (stop || taken == count) break;
                    piece = taken++;
                }
                // The slot is free: the piece `slots` before this one has been written.
                Status status = make(piece, piece % slots, worker);
                size_t bytes = 0;
                {
                    std::lock_guard<std::mutex> held(lock);
                    made[piece % slots] = {std::move(status), true};
                    bytes = writeReady();
                    changed.notify_all();
                }
                writeback.wrote(bytes);  // the disk writes start here, outside the lock
            }
    });
    return outcome;
}

}  // namespace heightpack::detail
