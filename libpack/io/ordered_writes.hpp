// Internal: the loop of a writer whose pieces (rows of tiles, blocks of scanlines) are made on several
// threads but must reach the file in order.
#pragma once

#include <cstddef>
#include <functional>

#include "heightpack/core/result.hpp"
#include "heightpack/io/files.hpp"

namespace heightpack::detail {

// Pieces 0 .. count - 1 made by `workers` threads (the caller's among them) and written in order. A worker
// takes the next piece while it is fewer than `slots` ahead of the next to write, makes it with make(piece,
// slot, worker) outside the lock (slot = piece % slots: the caller's buffers for it, reused; worker: which
// thread, 0 .. workers - 1, for its own buffers), then writes every piece made, in order from the next to
// write, with write(piece, slot) under the lock (returning the bytes it wrote, told to writeback outside
// the lock). No thread waits at a batch's end for its slowest piece, and writing overlaps making. The
// first failure in piece order, of make or of write, stops the work and is returned; the pieces before it
// have been written, none after it. The bytes do not depend on `workers`.
Status makeAndWriteInOrder(size_t count, int workers, size_t slots, EarlyWriteback& writeback,
                           const std::function<Status(size_t piece, size_t slot, int worker)>& make,
                           const std::function<Result<size_t>(size_t piece, size_t slot)>& write);

}  // namespace heightpack::detail
