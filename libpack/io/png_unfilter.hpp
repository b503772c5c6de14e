// Internal: undoing PNG's row filters (specification section 9) on all threads, for the fast decoder.
#pragma once

#include <cstddef>

namespace heightpack::detail {

// Undoes the filters in place. rows holds, per row, a filter byte and rowBytes bytes (a whole number of
// pixels of bpp bytes: 1, 2 or 4). The row above the first is all zeros. False, with nothing changed,
// when a filter byte is not 0 to 4 or bpp is none of those. The bytes are the same for any thread count.
bool unfilter(unsigned char* rows, int height, size_t rowBytes, int bpp, int threads);

}  // namespace heightpack::detail
