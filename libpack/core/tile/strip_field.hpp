// Internal: the part of a field near its wrap lines that the band re-synthesis (tile/resynthesis.cpp)
// reads and writes. A 4096^2 field of doubles is 134 MB; the strips of its bands are about a tenth of it,
// and every value elsewhere would be computed, stored and paged in only to be left as it was.
#pragma once

#include <algorithm>
#include <vector>

#include "buffer.hpp"

namespace heightpack::detail {

// The texels of a w x h field within reachX columns of the left/right wrap line (columns x < reachX and
// x >= w - reachX, every row) and within reachY rows of the top/bottom one (every column). A texel in both
// is held once, in its row. Nothing is set until written: a writer fills what it keeps with setRow.
class StripField {
public:
    StripField(int width, int height, int reachX, int reachY)
        : w(width), h(height), columnSlot_(size_t(width), -1), rowSlot_(size_t(height), -1) {
        for (int x = 0; x < w; ++x)
            if (x < reachX || x >= w - reachX) {
                columnSlot_[x] = int(kept_.size());
                kept_.push_back(x);
            }
        int rows = 0;
        for (int y = 0; y < h; ++y)
            if (y < reachY || y >= h - reachY) rowSlot_[y] = rows++;
        columnValues_.resize(size_t(h) * kept_.size());
        rowValues_.resize(size_t(rows) * w);
    }
    const int w, h;

    // The kept columns, in increasing x.
    const std::vector<int>& columns() const { return kept_; }
    bool keeps(int x, int y) const { return rowSlot_[y] >= 0 || columnSlot_[x] >= 0; }
    double at(int x, int y) const { return const_cast<StripField*>(this)->at(x, y); }
    double& at(int x, int y) {
        const int row = rowSlot_[y];
        return row >= 0 ? rowValues_[size_t(row) * w + x] : columnValues_[size_t(y) * kept_.size() + columnSlot_[x]];
    }
    // Row y of the whole field (w values): what of it is kept. Each row once, from any thread.
    template <class T>
    void setRow(int y, const T* row) {
        if (const int slot = rowSlot_[y]; slot >= 0) {
            std::copy(row, row + w, rowValues_.begin() + ptrdiff_t(slot) * w);
            return;
        }
        double* to = &columnValues_[size_t(y) * kept_.size()];
        for (int x : kept_) *to++ = row[x];
    }

private:
    std::vector<int> kept_, columnSlot_, rowSlot_;
    Buffer<double> columnValues_, rowValues_;
};

}  // namespace heightpack::detail
