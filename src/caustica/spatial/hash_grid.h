// hash_grid.h — a spatial hash grid: an unbounded grid of cells of width 2 x the largest radius,
// cell coordinates hashed into a table of next-power-of-two >= point count buckets, points
// grouped by bucket with a counting sort (cell_sort.h; SmallVCM's hash grid, built from
// parallel/ primitives). Memory does not grow with the scene's extent, only with the points.
// Segments walk the cells along them and k-nearest searches rings of cells (grid_walk.h).
#pragma once

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "caustica/spatial/cell_sort.h"
#include "caustica/spatial/grid_walk.h"
#include "caustica/spatial/point_extent.h"
#include "caustica/spatial/point_set.h"

namespace caustica {

/// The hash of a cell (hash grid and multi-level hash table): Teschner et al. 2003 ("Optimized
/// Spatial Hashing for Collision Detection of Deformable Objects"), x p1 xor y p2 xor z p3, then
/// MurmurHash3's finaliser, because tables are powers of two and the low bits of the products
/// alone are poorly mixed.
CA_HD_INLINE uint32_t hashCell(CellCoord c) {
    uint32_t h = uint32_t(c.x) * 73856093u ^ uint32_t(c.y) * 19349663u ^ uint32_t(c.z) * 83492791u;
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    h ^= h >> 16;
    return h;
}

/// What kernels query. Different cells may share a bucket (a hash collision): a point is
/// reported only from its own cell (its cell is recomputed and compared), so a collision costs
/// candidates, never a duplicate or a wrong result.
struct HashGridView : BallQueries<HashGridView> {
    PointSet points;
    CellLists cells;  // points grouped by bucket (cell_sort.h)
    Float cellSize = 1;
    Float invCellSize = 1;
    uint32_t bucketMask = 0;  // bucketCount - 1 (a power of two)
    Float maxRadius = 0;      // the largest radius of the points
    int32_t maxRing = 0;      // rings a k-nearest search visits before it tests every point

    /// Cell coordinates are clamped to [-kCellLimit, kCellLimit].
    static constexpr int32_t kCellLimit = 1 << 30;

    /// floor(v / cellSize), clamped to +-2^30 (NaN to 0) so that the integer is defined.
    CA_HD static int32_t axisCell(Float v, Float invCellSize) {
        const Float t = std::floor(v * invCellSize);
        constexpr Float kLimit = Float(1 << 30);
        if (!(t > -kLimit)) return t != t ? 0 : -(1 << 30);
        return t >= kLimit ? (1 << 30) : int32_t(t);
    }
    CA_HD CellCoord cellOf(Vec3f p) const {
        return {axisCell(p.x, invCellSize), axisCell(p.y, invCellSize), axisCell(p.z, invCellSize)};
    }
    CA_HD uint32_t bucketOf(CellCoord c) const { return hashCell(c) & bucketMask; }
    /// The bucket of position p (the key of the build's sort).
    CA_HD uint32_t keyOf(Vec3f p) const { return bucketOf(cellOf(p)); }

    /// Visits the cells overlapped by the box of half-width `reach` around `center`; when they
    /// outnumber the buckets, every point once instead (same result, bounded cost).
    template <bool kSpheres, class F>
    CA_HD void visit(Vec3f center, Float reach, Float radius, F& f) const {
        if (cells.order.empty()) return;
        const Float r = conservativeReach(reach);
        forEachInCellBox(
            *this, cellOf(center - Vec3f(r)), cellOf(center + Vec3f(r)), Float(bucketMask) + 1,
            [&](uint32_t i) { return acceptsPoint<kSpheres>(points, i, center, radius); }, f);
    }

    /// The grid as grid_walk.h sees it: unbounded but for the clamping of cell coordinates.
    CA_HD int32_t cellOnAxis(int, Float v) const { return axisCell(v, invCellSize); }
    CA_HD int32_t firstCell(int) const { return -kCellLimit; }
    CA_HD int32_t lastCell(int) const { return kCellLimit; }
    CA_HD Float cellLower(int, int32_t c) const {
        return c <= -kCellLimit ? -kUnbounded : Float(c) * cellSize;
    }
    CA_HD Float cellUpper(int, int32_t c) const {
        return c >= kCellLimit ? kUnbounded : Float(c + 1) * cellSize;
    }
    /// report(i) for the points i of cells x0..x1 of row (y, z) with test(i): each cell's
    /// bucket, test first, then the point's own cell (a collision must not report it twice).
    template <class Test, class Report>
    CA_HD void forEachInRow(int32_t x0, int32_t x1, int32_t y, int32_t z, Test&& test,
                            Report&& report) const {
        for (int32_t x = x0; x <= x1; ++x) {
            const CellCoord cell{x, y, z};
            const uint32_t b = bucketOf(cell);
            for (uint32_t k = cells.cellStart[b]; k < cells.cellStart[b + 1]; ++k) {
                const uint32_t i = cells.order[k];
                if (test(i) && cellOf(points.positions[i]) == cell) report(i);
            }
        }
    }

    /// report(i) for every point i with test(i), once each, in index order (the fallbacks).
    template <class Test, class Report>
    CA_HD void forEachPoint(Test&& test, Report&& report) const {
        for (uint32_t i = 0; i < uint32_t(cells.order.size()); ++i)
            if (test(i)) report(i);
    }

    /// Walks the cells along the segment widened by the largest radius (grid_walk.h), or tests
    /// every point once when the walk would visit more cells than there are buckets.
    template <class F>
    CA_HD void visitSegment(const Segment& s, F& f) const {
        if (cells.order.empty()) return;
        const Float reach = segmentReach(s, maxRadius, cellSize);
        forEachSphereAlongWalkOrScan(*this, s, reach, Vec3f(-kUnbounded), Vec3f(kUnbounded),
                                     Float(bucketMask) + 1, f);
    }
    /// Rings of cells outward (grid_walk.h); after maxRing rings ((2 maxRing + 1)^3 <= 2 x the
    /// buckets) it starts again testing every point: cost bounded by O(n).
    CA_HD void searchNearest(Vec3f center, NearestHeap& heap) const {
        if (cells.order.empty()) return;
        if (searchRings(*this, center, maxRing, cellSize, 0, heap)) return;
        heap.clear();
        for (uint32_t i = 0; i < uint32_t(cells.order.size()); ++i)
            heap.consider(i, points.positions[i], center);
    }
};

/// A spatial hash grid over a PointSet (see point_set.h for the interface). Build: largest
/// radius, sort of (bucket, index) pairs, bucket starts. Memory: 4 bytes per point + 4 per
/// bucket (at most 2 per point), i.e. at most 12 bytes per point.
class HashGrid : public CellGrid<HashGridView> {
public:
    template <class Exec>
    static HashGrid build(Exec exec, const PointSet& points) {
        if (points.size() > (size_t(1) << 31))
            throw Error("spatial: a hash grid holds at most 2^31 points");
        HashGrid g;
        const Float largest = maxRadius(exec, points);
        g.cellSize_ = largest > 0 ? 2 * largest : Float(1);
        const uint32_t buckets = uint32_t(std::bit_ceil(points.size() > 0 ? points.size() : 1));
        g.view_.points = points;
        g.view_.cellSize = g.cellSize_;
        g.view_.invCellSize = 1 / g.cellSize_;
        g.view_.bucketMask = buckets - 1;
        g.view_.maxRadius = largest;
        while (std::pow(2.0 * (g.view_.maxRing + 1) + 1, 3.0) <= 2.0 * double(buckets))
            ++g.view_.maxRing;
        g.groupPoints(exec, buckets);
        return g;
    }

    uint32_t bucketCount() const { return view_.bucketMask + 1; }
};

}  // namespace caustica
