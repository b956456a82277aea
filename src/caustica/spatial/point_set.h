// point_set.h — the input of every lookup structure in spatial/: points in device memory, each
// with an optional radius (photons: points; SPPM visible points: spheres), and the one distance
// test that every structure and the brute-force reference share, so that their result sets are
// identical to the last bit.
#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>

#include "caustica/util/math.h"
#include "caustica/util/span.h"

namespace caustica {

/// Points in the memory of the device a structure is built on (Buffer<T>::constSpan()). The
/// structures keep these spans: the arrays must outlive the structure and stay unchanged.
///   positions  point i's position (world units); at most 2^32 - 1 points
///   radii      point i's sphere radius (>= 0); empty: every point has radius `radius`
///   radius     the common radius when `radii` is empty (photons: the gather radius)
/// The radius sizes the cells of the grids and is what forEachSphereCovering tests against.
struct PointSet {
    Span<const Vec3f> positions;
    Span<const Float> radii;
    Float radius = 0;

    CA_HD size_t size() const { return positions.size(); }
    CA_HD Float radiusOf(size_t i) const { return radii.empty() ? radius : radii[i]; }
};

/// True when p lies in the closed ball of radius r around c: |p - c|^2 <= r^2 in float. The one
/// predicate of every query, so that structures and brute force agree exactly.
CA_HD_INLINE bool inBall(Vec3f p, Vec3f c, Float r) {
    return lengthSquared(p - c) <= r * r;
}

/// How far beyond `r` a structure widens the box of cells it visits: the rounding of inBall can
/// accept a point a few ulps outside the exact ball, and a cell is never skipped for that. Extra
/// cells cost candidates that inBall rejects, never a wrong result.
CA_HD_INLINE Float conservativeReach(Float r) {
    return r * 1.001f;
}

/// The test both queries make of point i: "i lies within `radius` of center" (kSpheres false)
/// or "i's sphere covers center" (kSpheres true).
template <bool kSpheres>
CA_HD_INLINE bool acceptsPoint(const PointSet& points, uint32_t i, Vec3f center, Float radius) {
    const Vec3f p = points.positions[i];
    return kSpheres ? inBall(center, p, points.radiusOf(i)) : inBall(p, center, radius);
}

/// The two queries of a grid's view, written once (CRTP, no virtual call). View provides
///   points, maxRadius and visit<kSpheres>(center, reach, radius, f): f(i) once for each point
///   i of the cells overlapped by the box of half-width `reach` around center that passes
///   acceptsPoint<kSpheres>(points, i, center, radius).
template <class View>
struct BallQueries {
    /// f(i) for every point i with inBall(position i, center, radius).
    template <class F>
    CA_HD void forEachPointWithin(Vec3f center, Float radius, F&& f) const {
        static_cast<const View&>(*this).template visit<false>(center, radius, radius, f);
    }
    /// f(i) for every point i whose sphere (radius i) covers x: inBall(x, position i, radius i).
    template <class F>
    CA_HD void forEachSphereCovering(Vec3f x, F&& f) const {
        const View& view = static_cast<const View&>(*this);
        view.template visit<true>(x, view.maxRadius, 0, f);
    }
};

/// Integer cell coordinates (grids and hash grids).
struct CellCoord {
    int32_t x = 0, y = 0, z = 0;
    CA_HD bool operator==(const CellCoord& o) const { return x == o.x && y == o.y && z == o.z; }
};

/// The shape every lookup structure has (brute_force.h, uniform_grid.h, hash_grid.h):
///   S::build(exec, points)  builds on Exec's device (CpuExec now; GpuExec under nvcc) from a
///                           PointSet in that device's memory;
///   s.view()                a plain struct for kernels (copy it into a lambda by value) with
///                           CA_HD forEachPointWithin(center, radius, f) and
///                           forEachSphereCovering(x, f), calling f(uint32_t pointIndex) once per
///                           point found, in an order fixed by the build (not by thread count);
///   s.memoryBytes()         device memory the structure holds (not counting the PointSet).
template <class S, class Exec>
concept PointLookup = requires(Exec exec, const PointSet& points, const S& s) {
    { S::build(exec, points) } -> std::same_as<S>;
    {s.view()};
    { s.memoryBytes() } -> std::convertible_to<size_t>;
};

}  // namespace caustica
