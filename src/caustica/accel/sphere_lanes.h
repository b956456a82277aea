// sphere_lanes.h — intersectSphere (primitive_intersect.h) for four rays at once with SSE2, to the
// bit: the same operations on the same operands in the same order as the scalar test, lane by
// lane (no FMA: baseline x86-64 code). Host only; the Embree packets' direct sphere
// (embree_accel.cpp) tests its lanes with it, the single-ray queries with the scalar test.
#pragma once

#if defined(__SSE2__) || defined(_M_X64)
#define CA_SPHERE_LANES 1
#include <emmintrin.h>

#include <cstdint>

#include "caustica/util/math.h"

namespace caustica {

/// Four rays, one lane each: origins, directions and the search limits tMax.
struct RayLanes4 {
    __m128 ox, oy, oz, dx, dy, dz, tMax;
};

namespace sphere_lanes_detail {
inline __m128 dot(__m128 ax, __m128 ay, __m128 az, __m128 bx, __m128 by, __m128 bz) {
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(ax, bx), _mm_mul_ps(ay, by)), _mm_mul_ps(az, bz));
}
inline __m128 select(__m128 mask, __m128 a, __m128 b) {
    return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b));
}
}  // namespace sphere_lanes_detail

/// For each lane k, intersectSphere(o, d, tMax, center, radius, t): returns the mask of the lanes
/// that hit, with their t in t[k] (the other entries are unspecified).
inline uint32_t intersectSphere4(const RayLanes4& r, Vec3f center, Float radius, float (&t)[4]) {
    using namespace sphere_lanes_detail;
    const __m128 zero = _mm_setzero_ps(), signBit = _mm_set1_ps(-0.0f);
    const __m128 fx = _mm_sub_ps(r.ox, _mm_set1_ps(center.x)), fy = _mm_sub_ps(r.oy, _mm_set1_ps(center.y)),
                 fz = _mm_sub_ps(r.oz, _mm_set1_ps(center.z));
    const __m128 a = dot(r.dx, r.dy, r.dz, r.dx, r.dy, r.dz);
    const __m128 bPrime = _mm_xor_ps(dot(fx, fy, fz, r.dx, r.dy, r.dz), signBit);  // -dot(f, d)
    const __m128 r2 = _mm_set1_ps(radius * radius);
    const __m128 c = _mm_sub_ps(dot(fx, fy, fz, fx, fy, fz), r2);
    const __m128 k = _mm_div_ps(bPrime, a);
    const __m128 lx = _mm_add_ps(fx, _mm_mul_ps(r.dx, k)), ly = _mm_add_ps(fy, _mm_mul_ps(r.dy, k)),
                 lz = _mm_add_ps(fz, _mm_mul_ps(r.dz, k));
    const __m128 disc = _mm_mul_ps(a, _mm_sub_ps(r2, dot(lx, ly, lz, lx, ly, lz)));
    __m128 hit = _mm_cmpge_ps(disc, zero);  // false for NaN, as !(disc >= 0) rejects it
    // q = bPrime + copysign(sqrt(disc), bPrime); a lane with q == 0 misses.
    const __m128 root = _mm_sqrt_ps(disc);
    const __m128 q = _mm_add_ps(bPrime, _mm_or_ps(_mm_andnot_ps(signBit, root), _mm_and_ps(signBit, bPrime)));
    hit = _mm_and_ps(hit, _mm_cmpneq_ps(q, zero));
    const __m128 t0 = _mm_div_ps(c, q), t1 = _mm_div_ps(q, a);
    const __m128 swap = _mm_cmpgt_ps(t0, t1);  // if (t0 > t1) swap
    const __m128 lo = select(swap, t1, t0), hi = select(swap, t0, t1);
    const __m128 loInside = _mm_and_ps(_mm_cmpgt_ps(lo, zero), _mm_cmplt_ps(lo, r.tMax));
    const __m128 hiInside = _mm_and_ps(_mm_cmpgt_ps(hi, zero), _mm_cmplt_ps(hi, r.tMax));
    _mm_storeu_ps(t, select(loInside, lo, hi));
    return uint32_t(_mm_movemask_ps(_mm_and_ps(hit, _mm_or_ps(loInside, hiInside))));
}

}  // namespace caustica
#else
#define CA_SPHERE_LANES 0  // no SSE2: the packets test their direct sphere lane by lane
#endif
