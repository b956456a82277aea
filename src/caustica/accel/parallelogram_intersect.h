// parallelogram_intersect.h — a ray against a parallelogram (a two-triangle mesh shape that is one,
// scene/parallelogram.h) as one plane and two edge coordinates, generic over the lane type F
// (util/lane.h): F = float tests one ray, F = Float4 four rays, each lane to the bit of the float
// form. The hit is given back as the triangle of the half it falls in and that triangle's
// barycentrics, so that everything after the query (triangleSurface, the lights) sees the same
// kind of hit as from a triangle test.
#pragma once

#include <cstdint>
#include <vector>

#include "caustica/scene/parallelogram.h"
#include "caustica/scene/ray.h"
#include "caustica/util/lane.h"
#include "caustica/util/math.h"

namespace caustica {

/// A parallelogram's plane and edge vectors in every lane of F (for F = float, one of each).
template <class F>
struct ParallelogramLanes {
    Vec3Of<F> corner, normal, dualU, dualV;
};

/// A parallelogram prepared for ray tests: `normal` = cross(edgeU, edgeV) (not unit), and the
/// dual vectors dualU = cross(edgeV, normal) / |normal|², dualV = cross(normal, edgeU) / |normal|²
/// that give a point's edge coordinates: u = dot(p - corner, dualU), v = dot(p - corner, dualV).
/// Plain floats, the same layout on the host and a GPU: the own BVH's kernels read these
/// (BvhView::quads) one ray at a time.
struct ParallelogramPlane {
    Vec3f corner, normal, dualU, dualV;
    MeshParallelogram mesh;
};

/// The host's form for packets (Embree's intersector): `lanes4` holds the same four vectors
/// splat across four lanes: a packet's rays all meet the same few parallelograms, so the splat is
/// made once, not at every four-ray test.
struct PreparedParallelogram : ParallelogramPlane {
    ParallelogramLanes<Float4> lanes4;
};

namespace parallelogram_detail {
template <class F>
CA_HD_FORCE_INLINE Vec3Of<F> splat(const Vec3f& v) {
    return Vec3Of<F>{lane::splat<F>(v.x), lane::splat<F>(v.y), lane::splat<F>(v.z)};
}
}  // namespace parallelogram_detail

inline PreparedParallelogram prepareParallelogram(const MeshParallelogram& m) {
    using parallelogram_detail::splat;
    PreparedParallelogram p;
    p.corner = m.corner;
    p.normal = cross(m.edgeU, m.edgeV);
    const Float inv = 1 / lengthSquared(p.normal);
    p.dualU = cross(m.edgeV, p.normal) * inv;
    p.dualV = cross(p.normal, m.edgeU) * inv;
    p.mesh = m;
    p.lanes4 = {splat<Float4>(p.corner), splat<Float4>(p.normal), splat<Float4>(p.dualU), splat<Float4>(p.dualV)};
    return p;
}

/// The parallelogram meshes of `scene` (meshParallelogram: every rectangle shape), prepared, in
/// shape order; none when there are more than `limit` (each ray tests all of them, so a scene of
/// many is better left to the BVH as triangles). Embree's intersector and the own BVH take the
/// same ones.
inline std::vector<PreparedParallelogram> directParallelograms(const Scene& scene, uint32_t limit) {
    std::vector<PreparedParallelogram> quads;
    for (const Shape& shape : scene.shapes) {
        MeshParallelogram m;
        if (meshParallelogram(scene, shape, m)) quads.push_back(prepareParallelogram(m));
        if (quads.size() > limit) return {};
    }
    return quads;
}

/// The prepared parallelogram's vectors as F's lanes: for one lane its plain vectors, for four
/// lanes the stored splat (a PreparedParallelogram's).
template <class F, class Q>
CA_HD_FORCE_INLINE decltype(auto) lanesOf(const Q& q) {
    if constexpr (LaneTraits<F>::width == 1)
        return ParallelogramLanes<F>{q.corner, q.normal, q.dualU, q.dualV};
    else
        return (q.lanes4);  // a reference, not a copy
}

/// For each lane: whether the ray o + t·d hits the parallelogram with t in (0, tMax), both sides,
/// edges included (u, v in [0, 1]); where it does, t, u and v. A ray in the plane misses. Q is a
/// ParallelogramPlane for one lane, a PreparedParallelogram for any width.
template <class F, class Q>
CA_HD_FORCE_INLINE MaskOf<F> intersectParallelogram(const Vec3Of<F>& o, const Vec3Of<F>& d, F tMax, const Q& q,
                                                    F& t, F& u, F& v) {
    const ParallelogramLanes<F>& l = lanesOf<F>(q);
    const Vec3Of<F> toCorner = l.corner - o;
    t = dot(toCorner, l.normal) / dot(d, l.normal);  // ±inf or NaN in the plane's direction: rejected below
    const Vec3Of<F> p = d * t - toCorner;            // the hit point relative to the corner
    u = dot(p, l.dualU);
    v = dot(p, l.dualV);
    const F zero = lane::splat<F>(0), one = lane::splat<F>(1);
    return (t > zero) & (t < tMax) & (u >= zero) & (v >= zero) & (u <= one) & (v <= one);
}

/// The triangle of a parallelogram hit at edge coordinates (u, v) and its barycentrics (b1, b2)
/// as a triangle test reports them (the weights of the triangle's vertices 1 and 2).
CA_HD_INLINE void parallelogramHitTriangle(const MeshParallelogram& m, Float u, Float v, uint32_t& triangle,
                                           Float& b1, Float& b2) {
    Float w[3];
    const bool firstHalf = u + v <= 1;
    const uint8_t* slot = m.slots[firstHalf ? 0 : 1];
    if (firstHalf) {
        w[slot[0]] = 1 - u - v, w[slot[1]] = u, w[slot[2]] = v;
    } else {
        w[slot[0]] = u + v - 1, w[slot[1]] = 1 - v, w[slot[2]] = 1 - u;
    }
    triangle = firstHalf ? m.first : m.second;
    b1 = w[1];
    b2 = w[2];
}

/// The hit of a ray on parallelogram `q` at t and edge coordinates (u, v), as a triangle test of
/// its half would report it.
CA_HD_INLINE Hit parallelogramHit(const ParallelogramPlane& q, Float t, Float u, Float v) {
    Hit hit;
    hit.t = t;
    parallelogramHitTriangle(q.mesh, u, v, hit.primId, hit.b1, hit.b2);
    return hit;
}

}  // namespace caustica
