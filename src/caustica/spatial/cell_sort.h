// cell_sort.h — the build step shared by the grids: points grouped by cell with a counting sort
// made of parallel/ primitives (SmallVCM's hash grid and seed 003's uniform grid both count per
// cell, prefix-sum and scatter). Here the counting is a stable radix sort of (cell key, point
// index) and the cell starts come from the boundaries of the sorted keys: no atomics, and the
// order of the points in a cell (ascending index) does not depend on the thread count.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>

#include "caustica/parallel/buffer.h"
#include "caustica/parallel/launch.h"
#include "caustica/parallel/primitives.h"
#include "caustica/util/error.h"

namespace caustica {

/// Points grouped by cell, as kernels see them: order[cellStart[c] .. cellStart[c + 1]) are the
/// indices of the points in cell c, ascending. cellStart has cellCount + 1 entries, the last
/// one the point count.
struct CellLists {
    Span<const uint32_t> order;
    Span<const uint32_t> cellStart;
};

/// The arrays of CellLists, owned (memory of the device they were built on).
struct CellTable {
    Buffer<uint32_t> order;
    Buffer<uint32_t> cellStart;

    CellLists lists() const { return {order.constSpan(), cellStart.constSpan()}; }
    size_t memoryBytes() const { return (order.size() + cellStart.size()) * sizeof(uint32_t); }
};

namespace spatial_detail {

/// Key bits a radix sort needs for keys in [0, count): at least 1.
inline int keyBitsFor(uint64_t count) {
    return count <= 2 ? 1 : int(std::bit_width(count - 1));
}

/// keys[i] = cellKey(i), order[i] = i for i in [0, n).
template <class Exec, class CellKey>
void writeCellKeys(Exec exec, size_t n, CellKey cellKey, uint32_t* keys, uint32_t* order) {
    launch(
        exec, "spatial.cell_keys", n,
        [=] CA_HD(size_t i) {
            keys[i] = cellKey(i);
            order[i] = uint32_t(i);
        },
        256);
}

/// cellStart[c] = the first i with keys[i] >= c (n when none), for c in [0, cellCount], from
/// keys sorted ascending. Work item i in [0, n] writes the cells in (keys[i - 1], keys[i]],
/// reading keys[-1] as -1 and keys[n] as cellCount: every entry is written exactly once.
template <class Exec>
void findCellStarts(Exec exec, const uint32_t* keys, size_t n, uint32_t cellCount,
                    uint32_t* cellStart) {
    launch(
        exec, "spatial.cell_starts", n + 1,
        [=] CA_HD(size_t i) {
            const int64_t first = i == 0 ? 0 : int64_t(keys[i - 1]) + 1;
            const int64_t last = i == n ? int64_t(cellCount) : int64_t(keys[i]);
            for (int64_t c = first; c <= last; ++c) cellStart[c] = uint32_t(i);
        },
        256);
}

}  // namespace spatial_detail

/// Groups points [0, n) by cellKey(i) in [0, cellCount) (a CA_HD functor, copied into the
/// kernel), on Exec's device.
template <class Exec, class CellKey>
CellTable sortIntoCells(Exec exec, size_t n, uint32_t cellCount, CellKey cellKey) {
    using namespace spatial_detail;
    if (n >= (uint64_t(1) << 32) || cellCount == UINT32_MAX)
        throw Error("spatial: at most 2^32 - 1 points and cells are supported");
    const Device device = Exec::device();
    CellTable table{Buffer<uint32_t>(device, n), Buffer<uint32_t>(device, size_t(cellCount) + 1)};
    Buffer<uint32_t> keys(device, n);
    if (n > 0) {
        writeCellKeys(exec, n, cellKey, keys.data(), table.order.data());
        radixSortPairs(device, keys.span(), table.order.span(), keyBitsFor(cellCount));
    }
    findCellStarts(exec, keys.data(), n, cellCount, table.cellStart.data());
    return table;
}

/// The cell key of point i for sortIntoCells: View::keyOf(position i).
template <class View>
struct PointCellKey {
    View view;
    CA_HD uint32_t operator()(size_t i) const { return view.keyOf(view.points.positions[i]); }
};

/// What the grids share: their view (kernels copy it), the cell table it points into, the cell
/// width. A derived grid's build() fills view_ and calls groupPoints().
template <class View>
class CellGrid {
public:
    View view() const { return view_; }
    /// Device memory held: 4 bytes per point and 4 per cell (the PointSet not counted).
    size_t memoryBytes() const { return cells_.memoryBytes(); }
    Float cellSize() const { return cellSize_; }

protected:
    /// Groups view_.points into `cellCount` cells by view_.keyOf and points the view at them.
    template <class Exec>
    void groupPoints(Exec exec, uint32_t cellCount) {
        cells_ = sortIntoCells(exec, view_.points.size(), cellCount, PointCellKey<View>{view_});
        view_.cells = cells_.lists();
    }

    View view_;
    CellTable cells_;
    Float cellSize_ = 1;
};

}  // namespace caustica
