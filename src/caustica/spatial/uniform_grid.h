// uniform_grid.h — a uniform grid over the bounding box of the points (seed 003, Lysek 2015,
// sec. 4 "spatial grid": box of the points, cell = floor((x - box.min) / cellWidth) per axis),
// points grouped by cell with a counting sort (cell_sort.h). The cell width comes from the
// radius: by default 2 x the largest radius, so a ball of that radius overlaps 2 x 2 x 2 cells (3
// along an axis only within the rounding margin of conservativeReach); a build may ask for
// narrower cells (SPPM's photon grid: 1 x, 2-3 cells along an axis but 0.56x the box's area
// around a surface). The points' positions are also kept in cell order, so that a ball query's
// distance test reads them in sequence. Segments walk the rows of cells along them and k-nearest
// searches rings of cells outward (grid_walk.h).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "caustica/spatial/ball_range.h"
#include "caustica/spatial/cell_sort.h"
#include "caustica/spatial/grid_walk.h"
#include "caustica/spatial/point_extent.h"
#include "caustica/spatial/point_set.h"

namespace caustica {

/// What kernels query: cells indexed x fastest, then y, then z. Cell coordinates are clamped to
/// the grid, so every point (and every query) maps to a cell inside it.
struct UniformGridView : BallQueries<UniformGridView> {
    PointSet points;
    CellLists cells;  // points grouped by cell (cell_sort.h)
    Span<const Vec3f> cellPositions;  // cellPositions[k] = points.positions[cells.order[k]]
    Vec3f origin;     // the points' bounding box minimum
    Vec3f upper;      // and maximum (queries beyond it return at once)
    Float cellSize = 1;
    Float invCellSize = 1;
    CellCoord resolution{1, 1, 1};  // cells per axis
    Float maxRadius = 0;            // the largest radius of the points

    /// The cell of p along one axis: floor((v - origin) / cellSize) clamped to [0, res - 1].
    CA_HD int32_t axisCell(Float v, Float o, int32_t res) const {
        const Float t = std::floor((v - o) * invCellSize);
        if (!(t >= 0)) return 0;  // also NaN
        return t >= Float(res - 1) ? res - 1 : int32_t(t);
    }
    CA_HD CellCoord cellOf(Vec3f p) const {
        return {axisCell(p.x, origin.x, resolution.x), axisCell(p.y, origin.y, resolution.y),
                axisCell(p.z, origin.z, resolution.z)};
    }
    CA_HD uint32_t cellIndex(CellCoord c) const {
        return (uint32_t(c.z) * uint32_t(resolution.y) + uint32_t(c.y)) * uint32_t(resolution.x) +
               uint32_t(c.x);
    }
    /// The cell index of position p (the key of the build's sort).
    CA_HD uint32_t keyOf(Vec3f p) const { return cellIndex(cellOf(p)); }

    /// Visits the cells overlapped by the box of half-width `reach` around `center`; points of
    /// one grid row (x from lo to hi) are contiguous in `order`, so each row is one range.
    template <bool kSpheres, class F>
    CA_HD void visit(Vec3f center, Float reach, Float radius, F& f) const {
        if (cells.order.empty()) return;
        const Float r = conservativeReach(reach);
        if (center.x + r < origin.x || center.y + r < origin.y || center.z + r < origin.z ||
            center.x - r > upper.x || center.y - r > upper.y || center.z - r > upper.z)
            return;
        const CellCoord lo = cellOf(center - Vec3f(r)), hi = cellOf(center + Vec3f(r));
        if constexpr (!kSpheres) {
            // acceptsPoint<false> is inBall(position, center, radius): tested on the copy of the
            // positions in cell order, one contiguous range per row.
            const auto report = [&](uint32_t k) { f(cells.order[k]); };
            for (int32_t z = lo.z; z <= hi.z; ++z)
                for (int32_t y = lo.y; y <= hi.y; ++y) {
                    const uint32_t row = cellIndex({lo.x, y, z});
                    const uint32_t end = cells.cellStart[row + uint32_t(hi.x - lo.x) + 1];
                    forEachInBallRange(cellPositions.data(), cells.cellStart[row], end, center, radius, report);
                }
        } else {
            forEachInCellBox(
                *this, lo, hi, kUnbounded,
                [&](uint32_t i) { return acceptsPoint<kSpheres>(points, i, center, radius); }, f);
        }
    }

    /// The grid as grid_walk.h sees it: cells along one axis, clamped to the grid.
    CA_HD int32_t cellOnAxis(int a, Float v) const { return axisCell(v, origin[a], resolution[a]); }
    CA_HD int32_t firstCell(int) const { return 0; }
    CA_HD int32_t lastCell(int a) const { return resolution[a] - 1; }
    CA_HD Float cellLower(int a, int32_t c) const {
        return c <= 0 ? -kUnbounded : origin[a] + Float(c) * cellSize;
    }
    CA_HD Float cellUpper(int a, int32_t c) const {
        return c >= resolution[a] - 1 ? kUnbounded : origin[a] + Float(c + 1) * cellSize;
    }
    /// report(i) for the points i of cells x0..x1 of row (y, z) with test(i): one contiguous
    /// range of `order` (none when x1 < x0).
    /// report(i) for every point i with test(i), once each, in index order.
    template <class Test, class Report>
    CA_HD void forEachPoint(Test&& test, Report&& report) const {
        for (uint32_t i = 0; i < uint32_t(cells.order.size()); ++i)
            if (test(i)) report(i);
    }
    template <class Test, class Report>
    CA_HD void forEachInRow(int32_t x0, int32_t x1, int32_t y, int32_t z, Test&& test,
                            Report&& report) const {
        if (x1 < x0) return;
        const uint32_t row = cellIndex({x0, y, z});
        const uint32_t end = cells.cellStart[row + uint32_t(x1 - x0) + 1];
        for (uint32_t k = cells.cellStart[row]; k < end; ++k)
            if (test(cells.order[k])) report(cells.order[k]);
    }
    /// The magnitude of the grid's coordinates (for the slack of segment and ring walks).
    CA_HD Float coordinateScale() const { return max(maxAbs(origin), maxAbs(upper)) + cellSize; }

    /// Walks the rows of cells along the segment widened by the largest radius (grid_walk.h).
    template <class F>
    CA_HD void visitSegment(const Segment& s, F& f) const {
        if (cells.order.empty()) return;
        const Float reach = segmentReach(s, maxRadius, coordinateScale());
        forEachSphereAlongWalk(*this, s, reach, origin, upper, f);
    }
    /// Rings of cells outward from center's cell until the k-th distance (or maxRadius) is
    /// below the next ring's distance, or the rings cover the candidate cells (grid_walk.h).
    CA_HD void searchNearest(Vec3f center, NearestHeap& heap) const {
        if (cells.order.empty()) return;
        const int32_t rings = max(resolution.x, max(resolution.y, resolution.z));
        searchRings(*this, center, rings, cellSize, coordinateScale(), heap);
    }
};

/// Layout of a uniform grid: chosen on the host from the points' box and largest radius.
struct UniformGridLayout {
    Vec3f origin;
    Float cellSize = 1;
    CellCoord resolution{1, 1, 1};
    uint32_t cellCount() const {
        return uint32_t(resolution.x) * uint32_t(resolution.y) * uint32_t(resolution.z);
    }

    /// Cell width cellRadii x maxRadius; doubled until the grid has at most max(4 n, 4096) cells
    /// (and 2^26), so that a tiny radius over a large box cannot exhaust memory. A zero radius
    /// starts from the box's longest side / 1024 (1 for a box of one point).
    static UniformGridLayout choose(const Bounds3f& box, Float maxRadius, size_t n, Float cellRadii = 2) {
        UniformGridLayout g;
        if (box.empty()) return g;
        g.origin = box.lo;
        const Vec3f extent = box.diagonal();
        const double longest = double(maxComponent(extent));
        const double maxCells = std::fmin(std::fmax(4.0 * double(n), 4096.0), double(1 << 26));
        double cell = double(cellRadii) * double(maxRadius);
        if (!(cell > 0)) cell = longest > 0 ? longest / 1024 : 1;
        cell = std::fmax(cell, longest / 4096);  // at most 4096 cells per axis
        for (;;) {
            const double rx = std::fmax(1, std::ceil(double(extent.x) / cell));
            const double ry = std::fmax(1, std::ceil(double(extent.y) / cell));
            const double rz = std::fmax(1, std::ceil(double(extent.z) / cell));
            if (rx * ry * rz <= maxCells) {
                g.resolution = {int32_t(rx), int32_t(ry), int32_t(rz)};
                break;
            }
            cell *= 2;
        }
        g.cellSize = Float(cell);
        return g;
    }
};

/// A uniform grid over a PointSet (see point_set.h for the interface). Build: bounding box,
/// layout, sort of (cell, index) pairs, cell starts, positions in cell order. Memory: 16 bytes
/// per point + 4 per cell. `cellRadii`: the cell width in largest radii (> 0).
class UniformGrid : public CellGrid<UniformGridView> {
public:
    template <class Exec>
    static UniformGrid build(Exec exec, const PointSet& points, Float cellRadii = 2) {
        UniformGrid g;
        const Bounds3f box = pointBounds(exec, points.positions);
        const Float largest = maxRadius(exec, points);
        const UniformGridLayout layout = UniformGridLayout::choose(box, largest, points.size(), cellRadii);
        g.view_.points = points;
        g.view_.origin = layout.origin;
        g.view_.upper = box.empty() ? layout.origin : box.hi;
        g.view_.cellSize = layout.cellSize;
        g.view_.invCellSize = 1 / layout.cellSize;
        g.view_.resolution = layout.resolution;
        g.view_.maxRadius = largest;
        g.cellSize_ = layout.cellSize;
        g.groupPoints(exec, layout.cellCount());
        g.cellPositions_ = Buffer<Vec3f>(Exec::device(), points.size());
        const Vec3f* from = points.positions.data();
        const uint32_t* order = g.view_.cells.order.data();
        Vec3f* to = g.cellPositions_.data();
        launch(exec, "spatial.cell_positions", points.size(), [=] CA_HD(size_t k) { to[k] = from[order[k]]; }, 256);
        g.view_.cellPositions = g.cellPositions_.constSpan();
        return g;
    }

    CellCoord resolution() const { return view_.resolution; }
    size_t memoryBytes() const { return CellGrid<UniformGridView>::memoryBytes() + cellPositions_.size() * sizeof(Vec3f); }

private:
    Buffer<Vec3f> cellPositions_;
};

}  // namespace caustica
