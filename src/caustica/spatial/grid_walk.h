// grid_walk.h — the cell walks every grid (uniform_grid.h, hash_grid.h, a leaf of
// multi_hash.h) shares: the cells of a box, the cells along a segment widened by a reach (a 3D
// DDA by nested clipping) and the rings of cells around a point, outward, for k nearest
// neighbours. Written once over a Grid that provides
//   cellOnAxis(axis, v)       the cell of coordinate v (monotone in v; clamped to the grid),
//   firstCell(axis), lastCell(axis)   the clamping range,
//   cellLower(axis, c), cellUpper(axis, c)   the nominal bounds of cell c (-inf / +inf for the
//                             first / last cell, which take everything beyond),
//   forEachInRow(x0, x1, y, z, test, report)   report(i) for each point i of cells x0..x1 of
//                             row (y, z) with test(i), once (the hashed grids check each point's
//                             own cell, after the cheaper test),
//   forEachPoint(test, report)   the same for every point of the grid (the fallbacks).
#pragma once

#include <cmath>
#include <cstdint>

#include "caustica/spatial/k_nearest.h"
#include "caustica/spatial/point_set.h"

namespace caustica {

namespace spatial_detail {

/// First and last cell along `axis` of the part t in [t0, t1] of segment s, widened by reach.
template <class Grid>
CA_HD void segmentCells(const Grid& g, const Segment& s, int axis, Float t0, Float t1, Float reach,
                        int32_t& first, int32_t& last) {
    const Float a = s.origin[axis] + s.dir[axis] * t0, b = s.origin[axis] + s.dir[axis] * t1;
    first = g.cellOnAxis(axis, min(a, b) - reach);
    last = g.cellOnAxis(axis, max(a, b) + reach);
}

}  // namespace spatial_detail

/// Cells in the box lo..hi (inclusive), as a Float: no overflow for any box.
CA_HD_INLINE Float cellBoxCount(CellCoord lo, CellCoord hi) {
    return (Float(hi.x) - Float(lo.x) + 1) * (Float(hi.y) - Float(lo.y) + 1) * (Float(hi.z) - Float(lo.z) + 1);
}

/// report(i) for every point i with test(i) in the cells lo..hi of grid g (row by row), or, when
/// the box has more than maxCells cells, in g.forEachPoint (every point once: the same result
/// at a cost bounded by the points; the hashed grids pass their bucket count, the uniform grid
/// +inf).
template <class Grid, class Test, class Report>
CA_HD void forEachInCellBox(const Grid& g, CellCoord lo, CellCoord hi, Float maxCells, Test&& test,
                            Report&& report) {
    if (cellBoxCount(lo, hi) > maxCells) {
        g.forEachPoint(test, report);
        return;
    }
    for (int32_t z = lo.z; z <= hi.z; ++z)
        for (int32_t y = lo.y; y <= hi.y; ++y) g.forEachInRow(lo.x, hi.x, y, z, test, report);
}

/// row(x0, x1, y, z) for every row of cells (x0..x1, y, z) that segment s widened by `reach`
/// may touch, inside the box [lo, hi] widened by reach (a point beyond it cannot be in any
/// cell). For each layer z the segment is clipped to the layer's slab (widened), for each row y
/// of it to the row's slab, and the row's x range is what is left: every cell within reach of
/// the segment, plus a few along the corners of the widened tube. Stops early, returning false,
/// when row returns false. Segments of length zero and along an axis need no special case
/// (Segment::clip). The rounding of the clipping is covered by segmentReach's slack.
template <class Grid, class Row>
CA_HD bool walkSegmentCells(const Grid& g, const Segment& s, Float reach, Vec3f lo, Vec3f hi,
                            Row&& row) {
    using spatial_detail::segmentCells;
    Float t0 = 0, t1 = s.tEnd;
    for (int a = 0; a < 3; ++a)
        if (!s.clip(a, lo[a] - reach, hi[a] + reach, t0, t1)) return true;
    int32_t z0, z1;
    segmentCells(g, s, 2, t0, t1, reach, z0, z1);
    for (int32_t z = z0; z <= z1; ++z) {
        Float a0 = t0, a1 = t1;
        if (!s.clip(2, g.cellLower(2, z) - reach, g.cellUpper(2, z) + reach, a0, a1)) continue;
        int32_t y0, y1;
        segmentCells(g, s, 1, a0, a1, reach, y0, y1);
        for (int32_t y = y0; y <= y1; ++y) {
            Float b0 = a0, b1 = a1;
            if (!s.clip(1, g.cellLower(1, y) - reach, g.cellUpper(1, y) + reach, b0, b1)) continue;
            int32_t x0, x1;
            segmentCells(g, s, 0, b0, b1, reach, x0, x1);
            if (!row(x0, x1, y, z)) return false;
        }
    }
    return true;
}

/// The sphere of point i meets segment s (the predicate of every grid's segment query).
template <class Grid>
CA_HD bool gridSphereMeetsSegment(const Grid& g, uint32_t i, const Segment& s) {
    return sphereMeetsSegment(g.points.positions[i], g.points.radiusOf(i), s);
}

/// f(i) for every point of the cells along s (widened by `reach`, within [lo, hi]) whose sphere
/// meets s: the walk both grids' visitSegment make.
template <class Grid, class F>
CA_HD void forEachSphereAlongWalk(const Grid& g, const Segment& s, Float reach, Vec3f lo, Vec3f hi, F& f) {
    auto meets = [&](uint32_t i) { return gridSphereMeetsSegment(g, i, s); };
    walkSegmentCells(g, s, reach, lo, hi, [&](int32_t x0, int32_t x1, int32_t y, int32_t z) {
        g.forEachInRow(x0, x1, y, z, meets, f);
        return true;
    });
}

/// The segment query of a hashed grid (hash grid, a leaf of the multi-level hash table): the
/// walk of forEachSphereAlongWalk, unless it would visit more than maxCells cells (counted
/// first, when the segment's box of cells has more); then g.forEachPoint(test, report) tests
/// every point of the grid once instead: the same result at a cost bounded by the points.
template <class Grid, class F>
CA_HD void forEachSphereAlongWalkOrScan(const Grid& g, const Segment& s, Float reach, Vec3f lo, Vec3f hi,
                                        Float maxCells, F& f) {
    Float boxCells = 1;
    for (int a = 0; a < 3; ++a) {
        int32_t first, last;
        spatial_detail::segmentCells(g, s, a, 0, s.tEnd, reach, first, last);
        boxCells *= Float(last) - Float(first) + 1;
    }
    Float walked = 0;  // cells of the walk so far, while counting
    auto count = [&](int32_t x0, int32_t x1, int32_t, int32_t) {
        walked += Float(x1) - Float(x0) + 1;
        return walked <= maxCells;
    };
    if (boxCells > maxCells && !walkSegmentCells(g, s, reach, lo, hi, count)) {
        g.forEachPoint([&](uint32_t i) { return gridSphereMeetsSegment(g, i, s); }, f);
        return;
    }
    forEachSphereAlongWalk(g, s, reach, lo, hi, f);
}

/// Relative slack of the rings' distance bound: 1e-3 of the bound (the rounding of the squared
/// distances) and kSegmentSlack of the coordinates involved (the rounding of cell assignment).
inline constexpr Float kRingSlack = 1e-3f;

/// The k-nearest search of a grid (seed 003's cells, searched outward): ring m is the cells at
/// Chebyshev distance m from center's cell, clipped to the cells that the box of maxRadius
/// around center overlaps (as visit() does: no other cell can hold an accepted point). After
/// ring m every point not yet offered lies outside the cube of rings 0..m, so at least `bound`
/// from center (the nearest face of the cube that has candidate cells beyond it). The search
/// stops when that bound, made conservative, exceeds maxRadius or the k-th candidate's distance
/// (strictly: a tie may still enter by index), or when the cube covers every candidate cell
/// (the grid, or maxRadius's box). Returns false when it gives up after ring maxRing (the
/// caller then clears the heap and offers every point). `scale`: the magnitude of the grid's
/// own coordinates (its origin), for the slack.
template <class Grid>
CA_HD bool searchRings(const Grid& g, Vec3f center, int32_t maxRing, Float cellSize, Float scale,
                       NearestHeap& heap) {
    const CellCoord c{g.cellOnAxis(0, center.x), g.cellOnAxis(1, center.y),
                      g.cellOnAxis(2, center.z)};
    // Only cells within the heap's limit (maxRadius until it is full; widened as visit() widens)
    // can hold a point the heap keeps.
    const Float reach = conservativeReach(std::sqrt(heap.limit()));
    const CellCoord first{max(g.firstCell(0), g.cellOnAxis(0, center.x - reach)),
                          max(g.firstCell(1), g.cellOnAxis(1, center.y - reach)),
                          max(g.firstCell(2), g.cellOnAxis(2, center.z - reach))};
    const CellCoord last{min(g.lastCell(0), g.cellOnAxis(0, center.x + reach)),
                         min(g.lastCell(1), g.cellOnAxis(1, center.y + reach)),
                         min(g.lastCell(2), g.cellOnAxis(2, center.z + reach))};
    // Candidates farther than the heap's limit are dropped before the hash grid's cell check.
    auto closeEnough = [&](uint32_t i) {
        return !(distanceSquaredUnfused(g.points.positions[i], center) > heap.limit());
    };
    auto offer = [&](uint32_t i) { heap.consider(i, g.points.positions[i], center); };
    for (int32_t m = 0; m <= maxRing; ++m) {
        // Ring m: whole rows on the faces z = c.z +- m and y = c.y +- m, two cells elsewhere.
        for (int32_t z = max(c.z - m, first.z); z <= min(c.z + m, last.z); ++z) {
            for (int32_t y = max(c.y - m, first.y); y <= min(c.y + m, last.y); ++y) {
                if (z == c.z - m || z == c.z + m || y == c.y - m || y == c.y + m) {
                    g.forEachInRow(max(c.x - m, first.x), min(c.x + m, last.x), y, z, closeEnough,
                                   offer);
                } else {
                    if (c.x - m >= first.x)
                        g.forEachInRow(c.x - m, c.x - m, y, z, closeEnough, offer);
                    if (m > 0 && c.x + m <= last.x)
                        g.forEachInRow(c.x + m, c.x + m, y, z, closeEnough, offer);
                }
            }
        }
        // The distance beyond which the points not yet offered lie.
        bool covered = true;
        Float bound = kUnbounded;
        for (int a = 0; a < 3; ++a) {
            if (c[a] - m > first[a]) {
                covered = false;
                bound = min(bound, center[a] - g.cellLower(a, c[a] - m));
            }
            if (c[a] + m < last[a]) {
                covered = false;
                bound = min(bound, g.cellUpper(a, c[a] + m) - center[a]);
            }
        }
        if (covered) return true;
        const Float slack = kSegmentSlack * (maxAbs(center) + Float(m + 1) * cellSize + scale);
        const Float b = bound * (1 - kRingSlack) - slack;
        if (b > 0) {
            const Float b2 = b * b;
            if (b2 > heap.maxDistanceSquared()) return true;
            if (heap.full() && heap.limit() < b2) return true;
        }
    }
    return false;
}

}  // namespace caustica
