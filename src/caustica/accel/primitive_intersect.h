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

namespace caustica {

/// Ray–triangle intersection in the Möller–Trumbore form (Möller and Trumbore, "Fast, Minimum
/// Storage Ray/Triangle Intersection", JGT 1997) rewritten with scalar triple products around the
/// unnormalised geometric normal n = e1 x e2, as Embree's Möller intersector does. By Cramer's rule
/// on o + t d = p0 + b1 e1 + b2 e2, with c = p0 - o, r = c x d and den = d . n:
///     t = (c . n) / den,   b1 = (e2 . r) / den,   b2 = -(e1 . r) / den.
/// Divisions happen only for accepted hits. A zero-area triangle whose cross product is exactly
/// zero (repeated vertices) has den = 0 and is never hit. `p0` is vertex 0, `e1 = p1 - p0`,
/// `e2 = p2 - p0`; b1, b2 are the barycentrics of vertices 1 and 2.
CA_BVH_INLINE bool intersectTriangle(Vec3f o, Vec3f d, Float tMax, Vec3f p0, Vec3f e1, Vec3f e2,
                                     Float& tOut, Float& b1Out, Float& b2Out) {
    const Vec3f n = cross(e1, e2);
    const Float den = dot(d, n);
    const Vec3f c = p0 - o;
    const Vec3f r = cross(c, d);
    Float u = dot(e2, r), v = -dot(e1, r), tNum = dot(c, n);
    Float absDen = den;
    if (den < 0) {
        u = -u;
        v = -v;
        tNum = -tNum;
        absDen = -den;
    }
    // One branch for all conditions (non-short-circuit &): a chain of data-dependent early exits
    // mispredicts often in traversal. Every comparison rejects NaNs (non-finite input).
    if (!((absDen > 0) & (u >= 0) & (v >= 0) & (u + v <= absDen) & (tNum > 0) &
          (tNum < absDen * tMax)))
        return false;
    const Float invDen = 1 / absDen;
    const Float t = tNum * invDen;
    if (!(t > 0 && t < tMax)) return false;
    tOut = t;
    b1Out = u * invDen;
    b2Out = v * invDen;
    return true;
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
        const Vec3f p0 = scene.positions[tri.x];
        Float t, b1, b2;
        if (!intersectTriangle(ray.o, ray.d, tMax, p0, scene.positions[tri.y] - p0,
                               scene.positions[tri.z] - p0, t, b1, b2))
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
