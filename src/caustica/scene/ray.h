// ray.h — rays, hit records and the self-intersection-safe ray spawning used everywhere.
#pragma once

#include <cstdint>
#include <cstring>

#include "caustica/util/math.h"

#if !defined(__CUDA_ARCH__) && (defined(__SSE2__) || defined(_M_X64))
#define CA_RAY_SSE 1
#include <emmintrin.h>
#else
#define CA_RAY_SSE 0
#endif

namespace caustica {

struct Ray {
    Vec3f o, d;               // origin, direction (not necessarily unit length)
    Float tMax = kInfinity;   // hits are searched for in (0, tMax)
};

inline constexpr uint32_t kNoPrimitive = 0xffffffffu;

/// Closest-hit record. Primitive ids index triangles first, then spheres:
/// id < numTriangles is triangle id, otherwise sphere (id - numTriangles).
struct Hit {
    Float t = kInfinity;
    uint32_t primId = kNoPrimitive;
    Float b1 = 0, b2 = 0;  // triangle barycentrics of vertices 1 and 2
    CA_HD bool valid() const { return primId != kNoPrimitive; }
};

CA_HD_INLINE int32_t floatAsInt(Float f) {
    int32_t i;
    memcpy(&i, &f, sizeof f);
    return i;
}
CA_HD_INLINE Float intAsFloat(int32_t i) {
    Float f;
    memcpy(&f, &i, sizeof f);
    return f;
}

/// std::nextafter(x, 0.0f), bit for bit, without the call into libm (1% of a glass-caustic sample
/// when Embree's open ray interval was made with it): the float next to x toward zero; zero gives
/// +0, NaN stays NaN.
CA_HD_INLINE Float nextFloatTowardZero(Float x) {
    if (x == 0) return 0;
    if (x != x) return x;
    return intAsFloat(floatAsInt(x) - 1);  // one ulp less magnitude, either sign
}

namespace ray_detail {
constexpr Float kOffsetOrigin = 1.0f / 32.0f, kOffsetFloatScale = 1.0f / 65536.0f, kOffsetIntScale = 256.0f;
#if CA_RAY_SSE
/// offsetRayOrigin's loop for four coordinates side by side (p, n: the coordinates and their
/// normal's): the same operations in the same order (truncating conversion, wrapping integer add,
/// no contraction), so the same bits (tests/scene/ray_test.cpp).
CA_HD_FORCE_INLINE __m128 offsetLanes(__m128 P, __m128 N) {
    const __m128i of = _mm_cvttps_epi32(_mm_mul_ps(_mm_set1_ps(kOffsetIntScale), N));
    const __m128i negative = _mm_castps_si128(_mm_cmplt_ps(P, _mm_setzero_ps()));
    const __m128i signedOf = _mm_sub_epi32(_mm_xor_si128(of, negative), negative);  // p < 0 ? -of : of
    const __m128 moved = _mm_castsi128_ps(_mm_add_epi32(_mm_castps_si128(P), signedOf));
    const __m128 absP = _mm_and_ps(P, _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff)));
    const __m128 nearOrigin = _mm_cmplt_ps(absP, _mm_set1_ps(kOffsetOrigin));
    const __m128 nudged = _mm_add_ps(P, _mm_mul_ps(_mm_set1_ps(kOffsetFloatScale), N));
    return _mm_or_ps(_mm_and_ps(nearOrigin, nudged), _mm_andnot_ps(nearOrigin, moved));
}
#endif
}  // namespace ray_detail

/// Offsets a surface point along the geometric normal so that a ray leaving it on the side of `n`
/// does not hit the surface it starts on. Scale-aware: the offset is a fixed number of ulps of the
/// coordinate, falling back to a tiny absolute offset near the origin (Wächter and Binder, "A Fast
/// and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems, 2019, ch. 6).
CA_HD_FORCE_INLINE Vec3f offsetRayOrigin(Vec3f p, Vec3f n) {
    using namespace ray_detail;
#if CA_RAY_SSE
    // The loop below, the three coordinates as lanes of one SSE register (offsetLanes); about 20
    // instructions instead of 35, three times a bounce.
    alignas(16) float lanes[4];
    _mm_store_ps(lanes, ray_detail::offsetLanes(_mm_setr_ps(p.x, p.y, p.z, 0), _mm_setr_ps(n.x, n.y, n.z, 0)));
    return {lanes[0], lanes[1], lanes[2]};
#else
    Vec3f out;
    for (int i = 0; i < 3; ++i) {
        int32_t of = int32_t(kOffsetIntScale * n[i]);
        Float pi = intAsFloat(floatAsInt(p[i]) + (p[i] < 0 ? -of : of));
        out[i] = std::fabs(p[i]) < kOffsetOrigin ? p[i] + kOffsetFloatScale * n[i] : pi;
    }
    return out;
#endif
}

#if CA_RAY_SSE && CA_FLOAT4_SSE
/// offsetRayOrigin of four points (lane k: point k along normal k), each lane's bits as the
/// scalar function's.
inline Vec3F4 offsetRayOrigin(const Vec3F4& p, const Vec3F4& n) {
    return {{ray_detail::offsetLanes(p.x.v, n.x.v)}, {ray_detail::offsetLanes(p.y.v, n.y.v)},
            {ray_detail::offsetLanes(p.z.v, n.z.v)}};
}
#endif

/// spawnRay written into `ray` field by field. (g++ assembles a returned Ray on the stack from
/// 8- and 4-byte stores and copies it on with 16-byte loads, which wait for those stores to
/// retire: a store-forwarding stall at every bounce of a path.)
CA_HD_FORCE_INLINE void spawnRayInto(Ray& ray, Vec3f p, Vec3f ng, Vec3f d) {
    ray.o = offsetRayOrigin(p, dot(d, ng) > 0 ? ng : -ng);
    ray.d = d;
    ray.tMax = kInfinity;
}

/// A ray leaving surface point `p` (geometric normal `ng`) in direction `d`.
CA_HD_INLINE Ray spawnRay(Vec3f p, Vec3f ng, Vec3f d) {
    Ray ray;
    spawnRayInto(ray, p, ng, d);
    return ray;
}

/// A shadow ray from surface point `p` (normal `ng`) to point `target` (normal `targetNg`, or
/// zero for a point light). Both ends are offset; the ray stops just short of the target.
CA_HD_INLINE Ray spawnRayTo(Vec3f p, Vec3f ng, Vec3f target, Vec3f targetNg) {
    Vec3f toTarget = target - p;
    Vec3f o = offsetRayOrigin(p, dot(toTarget, ng) > 0 ? ng : -ng);
    Vec3f t = lengthSquared(targetNg) > 0
                  ? offsetRayOrigin(target, dot(o - target, targetNg) > 0 ? targetNg : -targetNg)
                  : target;
    return Ray{o, t - o, 1 - 1e-4f};
}

}  // namespace caustica
