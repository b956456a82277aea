// point_set.h — the input of every lookup structure in spatial/: points in device memory, each
// with an optional radius (photons: points; SPPM visible points: spheres), and the one distance
// test that every structure and the brute-force reference share, so that their result sets are
// identical to the last bit.
#pragma once

#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "caustica/spatial/k_nearest.h"
#include "caustica/util/math.h"
#include "caustica/util/span.h"
#include "caustica/util/unfused.h"

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

/// True when p lies in the closed ball of radius r around c: |p - c|^2 <= r^2 in float, without
/// fused multiply-adds (unfused.h). The one predicate of every query, so that structures and
/// brute force agree exactly, on the GPU too.
CA_HD_INLINE bool inBall(Vec3f p, Vec3f c, Float r) {
    return distanceSquaredUnfused(p, c) <= mulUnfused(r, r);
}

/// How far beyond `r` a structure widens the box of cells it visits: the rounding of inBall can
/// accept a point a few ulps outside the exact ball, and a cell is never skipped for that. Extra
/// cells cost candidates that inBall rejects, never a wrong result. (|r|: inBall squares r.)
CA_HD_INLINE Float conservativeReach(Float r) {
    return std::fabs(r) * 1.001f;
}

/// +infinity (kInfinity is FLT_MAX): the bound of a grid's outer cells, of an unbounded side.
inline constexpr Float kUnbounded = std::numeric_limits<Float>::infinity();

/// The segment o + t d, t in [0, tEnd], in the one form every structure and the predicate use.
/// tMax <= 0 or NaN gives tEnd = 0 (an infinite one FLT_MAX); a direction whose squared length is
/// 0, NaN or infinite is replaced by 0: the segment is then the point o (length zero).
struct Segment {
    Vec3f origin;
    Vec3f dir;
    Float tEnd = 0;
    Float dirLengthSquared = 0;  // dot(dir, dir), > 0 unless the segment is a point

    Segment() = default;
    CA_HD Segment(Vec3f o, Vec3f d, Float tMax)
        : origin(o), dir(d), tEnd(tMax > 0 ? min(tMax, kInfinity) : Float(0)) {
        dirLengthSquared = dotUnfused(d, d);
        if (!(dirLengthSquared > 0 && dirLengthSquared <= kInfinity)) {
            dir = Vec3f(0);
            dirLengthSquared = 0;
        }
    }
    /// The far end, o + d tEnd (as computed: it only sizes rounding margins).
    CA_HD Vec3f end() const { return origin + dir * tEnd; }
    /// Shrinks [t0, t1] to the t whose coordinate along `axis` lies in [lo, hi]; false when none
    /// is left. Exact for a direction without that component (then all or nothing).
    CA_HD bool clip(int axis, Float lo, Float hi, Float& t0, Float& t1) const {
        const Float o = origin[axis], d = dir[axis];
        if (d == 0) return lo <= o && o <= hi && t0 <= t1;
        Float a = (lo - o) / d, b = (hi - o) / d;
        if (d < 0) {
            const Float swap = a;
            a = b;
            b = swap;
        }
        t0 = max(t0, a);
        t1 = min(t1, b);
        return t0 <= t1;
    }
};

/// The squared distance from p to the closest point of segment s, in float: the parameter of
/// the projection, dot(p - o, d) / dot(d, d), clamped to [0, tEnd] (NaN to 0), then
/// |(p - o) - d t|^2, without fused multiply-adds (unfused.h). The closest point is always on the segment, so rounding only moves it
/// along the segment. The one predicate of forEachSphereOnSegment (as inBall is of the others).
CA_HD_INLINE Float segmentDistanceSquared(Vec3f p, const Segment& s) {
    const Vec3f op = p - s.origin;
    Float t = s.dirLengthSquared > 0 ? dotUnfused(op, s.dir) / s.dirLengthSquared : Float(0);
    t = t > 0 ? (t < s.tEnd ? t : s.tEnd) : Float(0);
    const Vec3f along(mulUnfused(s.dir.x, t), mulUnfused(s.dir.y, t), mulUnfused(s.dir.z, t));
    return distanceSquaredUnfused(op, along);
}

/// True when the sphere of radius r around p meets segment s: segmentDistanceSquared <= r^2
/// (unfused, as inBall).
CA_HD_INLINE bool sphereMeetsSegment(Vec3f p, Float r, const Segment& s) {
    return segmentDistanceSquared(p, s) <= mulUnfused(r, r);
}

/// An entry of a tree's segment walk: a node and the part [t0, t1] of the segment that can reach
/// the spheres below it.
struct SegmentEntry {
    uint32_t node = 0;
    Float t0 = 0, t1 = 0;
};

/// The depth-first segment walk of the trees (kd_tree.h, multi_hash.h), from node 0 with the
/// whole segment: expand(entry, push) reports the node's spheres and push(child entry)es the
/// children with their part of the segment. The stack holds kStackSize entries.
template <int kStackSize, class Expand>
CA_HD void walkSegmentTree(const Segment& s, Expand&& expand) {
    SegmentEntry stack[kStackSize];
    int top = 0;
    stack[top++] = SegmentEntry{0, 0, s.tEnd};
    auto push = [&](SegmentEntry e) { stack[top++] = e; };
    while (top > 0) expand(stack[--top], push);
}

/// The largest |component| of v.
CA_HD_INLINE Float maxAbs(Vec3f v) {
    return maxComponent(abs(v));
}

/// Relative slack of the walks along segments (grids and kd-tree): the rounding of
/// segmentDistanceSquared and of the walks' own clipping is a few ulps of the coordinates
/// involved; 1e-5 of their magnitude is far above it. Costs candidates, never a result.
inline constexpr Float kSegmentSlack = 1e-5f;

/// How far from segment s a structure looks for centres of spheres of radius <= `radius`:
/// conservativeReach(radius) plus kSegmentSlack x the magnitude of the coordinates involved
/// (the segment's ends, `sceneScale`: the structure's own coordinates, and the radius).
CA_HD_INLINE Float segmentReach(const Segment& s, Float radius, Float sceneScale) {
    const Float scale = max(maxAbs(s.origin), maxAbs(s.end())) + sceneScale + std::fabs(radius);
    return conservativeReach(radius) + kSegmentSlack * scale;
}

/// The test both ball queries make of point i at position p (its stored copy in a kd-tree):
/// "p lies within `radius` of center" (kSpheres false) or "i's sphere covers center" (true).
template <bool kSpheres>
CA_HD_INLINE bool acceptsPosition(const PointSet& points, uint32_t i, Vec3f p, Vec3f center,
                                  Float radius) {
    return kSpheres ? inBall(center, p, points.radiusOf(i)) : inBall(p, center, radius);
}

/// acceptsPosition for point i at its position in the PointSet.
template <bool kSpheres>
CA_HD_INLINE bool acceptsPoint(const PointSet& points, uint32_t i, Vec3f center, Float radius) {
    return acceptsPosition<kSpheres>(points, i, points.positions[i], center, radius);
}

/// The queries of a structure's view, written once (CRTP, no virtual call). View provides
///   points, maxRadius (the largest radius of the points),
///   visit<kSpheres>(center, reach, radius, f): f(i) once for each point i that may lie within
///       `reach` of center (at least those) and passes acceptsPoint<kSpheres>(.., center, radius);
///   visitSegment(segment, f): f(i) once for each point i with
///       sphereMeetsSegment(position i, radius i, segment);
///   searchNearest(center, heap): heap.consider(i, position i, center) for at least every point
///       that can be among the heap's k nearest (k_nearest.h).
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
    /// f(i) for every point i whose sphere (radius i) meets the segment o + t d, t in [0, tMax]
    /// (seed 004: the spheres a ray segment passes through): segmentDistanceSquared <= r_i^2.
    template <class F>
    CA_HD void forEachSphereOnSegment(Vec3f o, Vec3f d, Float tMax, F&& f) const {
        static_cast<const View&>(*this).visitSegment(Segment(o, d, tMax), f);
    }
    /// The min(k, kMaxNeighbors) points nearest to center with inBall(position, center,
    /// maxRadius), ascending by (squared distance, index): indices[0, count) (and their squared
    /// distances when distancesSquared is not null; both arrays hold at least min(k, 64)).
    CA_HD void kNearest(Vec3f center, uint32_t k, Float maxRadius, uint32_t* indices,
                        uint32_t& count, Float* distancesSquared = nullptr) const {
        NearestHeap heap(k, maxRadius);
        if (heap.capacity() > 0) static_cast<const View&>(*this).searchNearest(center, heap);
        heap.finish(indices, count, distancesSquared);
    }
};

/// Integer cell coordinates (grids and hash grids).
struct CellCoord {
    int32_t x = 0, y = 0, z = 0;
    CA_HD bool operator==(const CellCoord& o) const { return x == o.x && y == o.y && z == o.z; }
    CA_HD int32_t operator[](int axis) const { return axis == 0 ? x : (axis == 1 ? y : z); }
};

/// A callback that ignores the index it is given (for the PointLookup concept).
struct IgnoreIndex {
    CA_HD void operator()(uint32_t) const {}
};

/// The shape every lookup structure has (brute_force.h, uniform_grid.h, hash_grid.h, kd_tree.h):
///   S::build(exec, points)  builds on Exec's device (CpuExec now; GpuExec under nvcc) from a
///                           PointSet in that device's memory;
///   s.view()                a plain struct for kernels (copy it into a lambda by value) with the
///                           CA_HD queries forEachPointWithin(center, radius, f),
///                           forEachSphereCovering(x, f), forEachSphereOnSegment(o, d, tMax, f)
///                           (each calling f(uint32_t pointIndex) once per point found, in an
///                           order fixed by the build, not by thread count) and
///                           kNearest(center, k, maxRadius, indices, count) (BallQueries above);
///   s.memoryBytes()         device memory the structure holds (not counting the PointSet).
template <class S, class Exec>
concept PointLookup = requires(Exec exec, const PointSet& points, const S& s, uint32_t* indices,
                               uint32_t& count) {
    { S::build(exec, points) } -> std::same_as<S>;
    { s.memoryBytes() } -> std::convertible_to<size_t>;
    s.view().forEachPointWithin(Vec3f(), Float(), IgnoreIndex{});
    s.view().forEachSphereCovering(Vec3f(), IgnoreIndex{});
    s.view().forEachSphereOnSegment(Vec3f(), Vec3f(), Float(), IgnoreIndex{});
    s.view().kNearest(Vec3f(), 1u, Float(), indices, count);
};

}  // namespace caustica
