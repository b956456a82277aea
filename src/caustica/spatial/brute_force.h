// brute_force.h — the reference lookup: every query tests every point. O(n) per query, no
// build, no memory; the other structures are tested against it (tests/spatial/). Written out
// without BallQueries, so that the shared code of the others is not its own reference.
#pragma once

#include <cstddef>
#include <cstdint>

#include "caustica/spatial/point_set.h"

namespace caustica {

/// What kernels query: points in index order.
struct BruteForceView {
    PointSet points;

    /// f(i) for every point i with inBall(position i, center, radius), ascending i.
    template <class F>
    CA_HD void forEachPointWithin(Vec3f center, Float radius, F&& f) const {
        for (uint32_t i = 0; i < uint32_t(points.size()); ++i)
            if (inBall(points.positions[i], center, radius)) f(i);
    }
    /// f(i) for every point i whose sphere covers x: inBall(x, position i, radius i), ascending i.
    template <class F>
    CA_HD void forEachSphereCovering(Vec3f x, F&& f) const {
        for (uint32_t i = 0; i < uint32_t(points.size()); ++i)
            if (inBall(x, points.positions[i], points.radiusOf(i))) f(i);
    }
    /// f(i) for every point i whose sphere meets the segment o + t d, t in [0, tMax]:
    /// sphereMeetsSegment(position i, radius i, Segment(o, d, tMax)), ascending i.
    template <class F>
    CA_HD void forEachSphereOnSegment(Vec3f o, Vec3f d, Float tMax, F&& f) const {
        const Segment s(o, d, tMax);
        for (uint32_t i = 0; i < uint32_t(points.size()); ++i)
            if (sphereMeetsSegment(points.positions[i], points.radiusOf(i), s)) f(i);
    }
    /// The min(k, kMaxNeighbors) points nearest to center within maxRadius, ascending by
    /// (squared distance, index) (point_set.h: BallQueries::kNearest), every point offered.
    CA_HD void kNearest(Vec3f center, uint32_t k, Float maxRadius, uint32_t* indices,
                        uint32_t& count, Float* distancesSquared = nullptr) const {
        NearestHeap heap(k, maxRadius);
        for (uint32_t i = 0; i < uint32_t(points.size()) && heap.capacity() > 0; ++i)
            heap.consider(i, points.positions[i], center);
        heap.finish(indices, count, distancesSquared);
    }
};

/// The brute-force "structure" (see point_set.h for the interface): it only keeps the PointSet.
class BruteForce {
public:
    template <class Exec>
    static BruteForce build(Exec, const PointSet& points) {
        BruteForce b;
        b.view_.points = points;
        return b;
    }
    BruteForceView view() const { return view_; }
    size_t memoryBytes() const { return 0; }

private:
    BruteForceView view_;
};

}  // namespace caustica
