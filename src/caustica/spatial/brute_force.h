// brute_force.h — the reference lookup: every query tests every point. O(n) per query, no
// build, no memory; the grids are tested against it (tests/spatial/).
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
