// primitive_intersect.h — ray–triangle, ray–sphere and ray–cylinder tests shared by every
// traversal (own BVH on CPU and GPU, the brute-force reference in the tests, Embree's sphere and
// cylinder callbacks).
//
// Conventions: rays need not have unit direction; a hit is accepted only for t in the open interval
// (0, tMax). Ray origins are expected to be offset off the surface they leave (spawnRay), so no
// epsilon is applied at t = 0.
#pragma once

#include <cstdint>

#include "caustica/accel/simd4.h"  // CA_BVH_INLINE
#include "caustica/scene/ray.h"
#include "caustica/scene/scene.h"
#include "caustica/util/math.h"
#include "caustica/util/unfused.h"

namespace caustica {

/// Per-ray constants of the watertight ray–triangle test (Woop, Benthin and Wald, "Watertight
/// Ray/Triangle Intersection", JCGT 2(1), 2013, sec. 3): the ray is mapped to the +z axis of a
/// sheared space, in which triangles are tested in 2D. kz is the axis of the largest |d|, kx and
/// ky the next two (cyclically), swapped when d[kz] < 0 so that the winding is kept; the shear is
/// sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = 1 / d[kz]. Compute once per ray.
struct WatertightRay {
    int kx, ky, kz;
    Float sx, sy, sz;
};

CA_BVH_INLINE WatertightRay makeWatertightRay(Vec3f d) {
    const Float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
    const int kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1, ky = kx == 2 ? 0 : kx + 1;
    if (d[kz] < 0) {
        const int k = kx;
        kx = ky;
        ky = k;
    }
    return WatertightRay{kx, ky, kz, d[kx] / d[kz], d[ky] / d[kz], 1 / d[kz]};
}

namespace watertight_detail {
// Watertightness rests on a shared edge's function being the exact negation in its two
// triangles, so no product may be fused into a multiply-add: every product is mulUnfused
// (util/unfused.h; a host build with -mfma would need -ffp-contract=off, which the watertight and
// triangle4 tests would show).
/// The 2D edge function px qy - py qx of the edge (p, q) in sheared space; (q, p) gives exactly
/// its negation, as the two triangles of a shared edge evaluate it.
CA_BVH_INLINE Float edgeFunction(Float px, Float py, Float qx, Float qy) {
    return mulUnfused(px, qy) - mulUnfused(py, qx);
}
/// The same in double precision, where the products are exact: its sign is exact, for edge
/// functions that came out exactly 0 in float (the ray passes through an edge or vertex).
CA_BVH_INLINE Float edgeFunctionDouble(Float px, Float py, Float qx, Float qy) {
    return Float(double(px) * double(qy) - double(py) * double(qx));
}
}  // namespace watertight_detail

/// Watertight ray–triangle intersection (Woop, Benthin and Wald, JCGT 2013, fig. 2 and sec. 4),
/// for the triangle of vertices p0, p1, p2 (exact positions, not precomputed edges): the vertices
/// relative to the ray origin are sheared (WatertightRay) and the 2D edge functions
///     U = E(p2, p1),   V = E(p0, p2),   W = E(p1, p0),   E(p, q) = px qy - py qx
/// are computed from the same operands for an edge in both its triangles, so a ray through a
/// shared edge or vertex never slips between them; where any is exactly 0 all three are redone
/// in double precision. Both windings are hit (all >= 0 or all <= 0); det = U + V + W,
/// t = (U z0 + V z1 + W z2) / det with z = sz * (p - o)[kz], tested against (0, tMax) scaled by
/// |det| before dividing. b1 = V / det and b2 = W / det are the barycentrics of vertices 1 and 2.
/// Zero-area triangles (det = 0) and non-finite input are never hit.
CA_BVH_INLINE bool intersectTriangleWith(const WatertightRay& r, Vec3f o, Float tMax, Vec3f p0,
                                         Vec3f p1, Vec3f p2, Float& tOut, Float& b1Out,
                                         Float& b2Out) {
    using namespace watertight_detail;
    const Vec3f a = p0 - o, b = p1 - o, c = p2 - o;
    const Float ax = a[r.kx] - mulUnfused(r.sx, a[r.kz]), ay = a[r.ky] - mulUnfused(r.sy, a[r.kz]);
    const Float bx = b[r.kx] - mulUnfused(r.sx, b[r.kz]), by = b[r.ky] - mulUnfused(r.sy, b[r.kz]);
    const Float cx = c[r.kx] - mulUnfused(r.sx, c[r.kz]), cy = c[r.ky] - mulUnfused(r.sy, c[r.kz]);
    Float u = edgeFunction(cx, cy, bx, by), v = edgeFunction(ax, ay, cx, cy),
          w = edgeFunction(bx, by, ax, ay);
    if ((u == 0) | (v == 0) | (w == 0)) {
        u = edgeFunctionDouble(cx, cy, bx, by);
        v = edgeFunctionDouble(ax, ay, cx, cy);
        w = edgeFunctionDouble(bx, by, ax, ay);
    }
    // One branch per stage (non-short-circuit |, &): data-dependent early exits mispredict.
    if (((u < 0) | (v < 0) | (w < 0)) & ((u > 0) | (v > 0) | (w > 0))) return false;
    const Float det = u + v + w;
    const Float tNum = u * mulUnfused(r.sz, a[r.kz]) + v * mulUnfused(r.sz, b[r.kz]) +
                       w * mulUnfused(r.sz, c[r.kz]);
    // Signs flipped where det < 0, so that the tests below read as for det > 0. Every
    // comparison rejects NaNs.
    const bool flip = det < 0;
    const Float absDet = flip ? -det : det, tPos = flip ? -tNum : tNum;
    if (!((absDet > 0) & (tPos > 0) & (tPos < absDet * tMax))) return false;
    const Float invDet = 1 / absDet;
    const Float t = tPos * invDet;
    if (!(t > 0 && t < tMax)) return false;
    tOut = t;
    b1Out = (flip ? -v : v) * invDet;
    b2Out = (flip ? -w : w) * invDet;
    return true;
}

/// intersectTriangleWith for a single ray (the per-ray constants computed here).
CA_BVH_INLINE bool intersectTriangle(Vec3f o, Vec3f d, Float tMax, Vec3f p0, Vec3f p1, Vec3f p2,
                                     Float& tOut, Float& b1Out, Float& b2Out) {
    return intersectTriangleWith(makeWatertightRay(d), o, tMax, p0, p1, p2, tOut, b1Out, b2Out);
}

/// Ray–sphere intersection with the numerically robust quadratic of Haines, Günther and
/// Akenine-Möller, "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, 2019,
/// ch. 7): the discriminant is formed from the squared distance between the centre and the line
/// (eq. 7.5), and the two roots as t0 = c / q, t1 = q / a with q = b' + sign(b') sqrt(disc)
/// (eq. 7.6), avoiding cancellation. Returns the nearest root in (0, tMax); an origin inside the
/// sphere gets the far root.
CA_HD_INLINE bool intersectSphere(Vec3f o, Vec3f d, Float tMax, Vec3f center, Float radius,
                                  Float& tOut) {
    const Vec3f f = o - center;
    const Float a = dot(d, d);
    const Float bPrime = -dot(f, d);  // -b/2 of a t^2 + b t + c
    const Float c = dot(f, f) - radius * radius;
    const Vec3f l = f + d * (bPrime / a);  // centre -> closest point on the line
    const Float disc = a * (radius * radius - dot(l, l));
    if (!(disc >= 0)) return false;  // also rejects NaN (a = 0 or non-finite input)
    const Float q = bPrime + std::copysign(std::sqrt(disc), bPrime);
    if (q == 0) return false;  // tangent through the origin: both roots are 0
    Float t0 = c / q, t1 = q / a;
    if (t0 > t1) {
        const Float tmp = t0;
        t0 = t1;
        t1 = tmp;
    }
    if (t0 > 0 && t0 < tMax) {
        tOut = t0;
        return true;
    }
    if (t1 > 0 && t1 < tMax) {
        tOut = t1;
        return true;
    }
    return false;
}

/// Ray–cylinder intersection for the open cylinder of radius `radius` around the segment
/// base + [0, length] * axis (unit axis). The quadratic of the ray projected onto the plane
/// perpendicular to the axis is solved in the robust form of intersectSphere (Haines et al.,
/// Ray Tracing Gems ch. 7); the nearer root in (0, tMax) whose height lies in [0, length] wins,
/// so the inside is hit through the open ends (Mitsuba's cylinder has no caps).
CA_HD_INLINE bool intersectCylinder(Vec3f o, Vec3f d, Float tMax, Vec3f base, Vec3f axis,
                                    Float radius, Float length, Float& tOut) {
    const Vec3f f = o - base;
    const Float fa = dot(f, axis), da = dot(d, axis);
    const Vec3f fp = f - axis * fa, dp = d - axis * da;  // projections off the axis
    const Float a = dot(dp, dp);
    const Float bPrime = -dot(fp, dp);
    const Float c = dot(fp, fp) - radius * radius;
    const Vec3f l = fp + dp * (bPrime / a);  // axis -> closest point of the projected line
    const Float disc = a * (radius * radius - dot(l, l));
    if (!(disc >= 0)) return false;  // also rejects a = 0 (ray parallel to the axis) and NaN
    const Float q = bPrime + std::copysign(std::sqrt(disc), bPrime);
    if (q == 0) return false;
    Float t0 = c / q, t1 = q / a;
    if (t0 > t1) {
        const Float tmp = t0;
        t0 = t1;
        t1 = tmp;
    }
    const Float h0 = fa + da * t0, h1 = fa + da * t1;
    if (t0 > 0 && t0 < tMax && h0 >= 0 && h0 <= length) {
        tOut = t0;
        return true;
    }
    if (t1 > 0 && t1 < tMax && h1 >= 0 && h1 <= length) {
        tOut = t1;
        return true;
    }
    return false;
}

/// Intersects primitive `primId` (triangles first, then spheres, then cylinders) and updates
/// `hit` when the hit is in (0, min(ray.tMax, hit.t)). Returns true if `hit` was updated.
/// Spheres and cylinders report b1 = b2 = 0.
CA_HD_INLINE bool intersectPrimitive(const SceneView& scene, uint32_t primId, const Ray& ray,
                                     Hit& hit) {
    const Float tMax = min(ray.tMax, hit.t);
    const uint32_t numTriangles = scene.numTriangles();
    if (primId < numTriangles) {
        const Vec3u tri = scene.triangles[primId];
        Float t, b1, b2;
        if (!intersectTriangle(ray.o, ray.d, tMax, scene.positions[tri.x],
                               scene.positions[tri.y], scene.positions[tri.z], t, b1, b2))
            return false;
        hit.t = t;
        hit.primId = primId;
        hit.b1 = b1;
        hit.b2 = b2;
        return true;
    }
    Float t;
    if (primId < scene.firstCylinder()) {
        const Sphere& s = scene.spheres[primId - numTriangles];
        if (!intersectSphere(ray.o, ray.d, tMax, s.center, s.radius, t)) return false;
    } else {
        const Cylinder& cy = scene.cylinders[primId - scene.firstCylinder()];
        if (!intersectCylinder(ray.o, ray.d, tMax, cy.base, cy.axis, cy.radius, cy.length, t))
            return false;
    }
    hit.t = t;
    hit.primId = primId;
    hit.b1 = hit.b2 = 0;
    return true;
}

}  // namespace caustica
