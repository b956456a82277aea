// hash_grid.h — a spatial hash grid: an unbounded grid of cells of width 2 x the largest radius,
// cell coordinates hashed into a table of next-power-of-two >= point count buckets, points
// grouped by bucket with a counting sort (cell_sort.h; SmallVCM's hash grid, built from
// parallel/ primitives). Memory does not grow with the scene's extent, only with the points.
#pragma once

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "caustica/spatial/cell_sort.h"
#include "caustica/spatial/point_extent.h"
#include "caustica/spatial/point_set.h"

namespace caustica {

/// What kernels query. Different cells may share a bucket (a hash collision): a point is
/// reported only from its own cell (its cell is recomputed and compared), so a collision costs
/// candidates, never a duplicate or a wrong result.
struct HashGridView : BallQueries<HashGridView> {
    PointSet points;
    CellLists cells;  // points grouped by bucket (cell_sort.h)
    Float invCellSize = 1;
    uint32_t bucketMask = 0;  // bucketCount - 1 (a power of two)
    Float maxRadius = 0;      // the largest radius of the points

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
    /// Teschner et al. 2003 ("Optimized Spatial Hashing for Collision Detection of Deformable
    /// Objects"): x p1 xor y p2 xor z p3, then MurmurHash3's finaliser, because the table is a
    /// power of two and the low bits of the products alone are poorly mixed.
    CA_HD uint32_t bucketOf(CellCoord c) const {
        uint32_t h =
            uint32_t(c.x) * 73856093u ^ uint32_t(c.y) * 19349663u ^ uint32_t(c.z) * 83492791u;
        h ^= h >> 16;
        h *= 0x85ebca6bu;
        h ^= h >> 13;
        h *= 0xc2b2ae35u;
        h ^= h >> 16;
        return h & bucketMask;
    }
    /// The bucket of position p (the key of the build's sort).
    CA_HD uint32_t keyOf(Vec3f p) const { return bucketOf(cellOf(p)); }

    /// Visits the cells overlapped by the box of half-width `reach` around `center`; when they
    /// outnumber the buckets, every point once instead (same result, bounded cost).
    template <bool kSpheres, class F>
    CA_HD void visit(Vec3f center, Float reach, Float radius, F& f) const {
        if (cells.order.empty()) return;
        const Float r = conservativeReach(reach);
        const CellCoord lo = cellOf(center - Vec3f(r)), hi = cellOf(center + Vec3f(r));
        const Float cellCount = (Float(hi.x) - Float(lo.x) + 1) * (Float(hi.y) - Float(lo.y) + 1) *
                                (Float(hi.z) - Float(lo.z) + 1);
        if (cellCount > Float(bucketMask) + 1) {
            for (uint32_t i = 0; i < uint32_t(cells.order.size()); ++i)
                if (acceptsPoint<kSpheres>(points, i, center, radius)) f(i);
            return;
        }
        for (int32_t z = lo.z; z <= hi.z; ++z) {
            for (int32_t y = lo.y; y <= hi.y; ++y) {
                for (int32_t x = lo.x; x <= hi.x; ++x) {
                    const CellCoord cell{x, y, z};
                    const uint32_t b = bucketOf(cell);
                    for (uint32_t k = cells.cellStart[b]; k < cells.cellStart[b + 1]; ++k) {
                        const uint32_t i = cells.order[k];
                        if (acceptsPoint<kSpheres>(points, i, center, radius) &&
                            cellOf(points.positions[i]) == cell)
                            f(i);
                    }
                }
            }
        }
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
        g.view_.invCellSize = 1 / g.cellSize_;
        g.view_.bucketMask = buckets - 1;
        g.view_.maxRadius = largest;
        g.groupPoints(exec, buckets);
        return g;
    }

    uint32_t bucketCount() const { return view_.bucketMask + 1; }
};

}  // namespace caustica
