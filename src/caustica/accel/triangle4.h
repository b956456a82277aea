// triangle4.h — one ray against four precomputed triangles at once with SSE (host only).
//
// The lanes run exactly the operations of intersectTriangle (primitive_intersect.h) in the same
// order, without fused multiply-adds, so every lane's t, b1, b2 are bit-identical to the scalar
// test's; the GPU and hosts without SSE keep the scalar loop (bvh_traversal.h, intersectLeaf).
// Triangles are read from the leaf-order BvhPrimitive array (40 bytes each, AoS) and transposed
// into lanes, so the layout the GPU reads stays unchanged.
#pragma once

#include <cstdint>

#include "caustica/accel/bvh.h"
#include "caustica/accel/simd4.h"

#if CA_BVH_SSE
namespace caustica::bvh_detail {

/// Three coordinates of four triangles (or of one vector in all four lanes).
struct Vec3x4 {
    __m128 x, y, z;
};

inline Vec3x4 broadcast3(Vec3f v) {
    return {_mm_set1_ps(v.x), _mm_set1_ps(v.y), _mm_set1_ps(v.z)};
}
inline Vec3x4 operator-(Vec3x4 a, Vec3x4 b) {
    return {_mm_sub_ps(a.x, b.x), _mm_sub_ps(a.y, b.y), _mm_sub_ps(a.z, b.z)};
}
// dot and cross in the evaluation order of math.h's.
inline __m128 dot(Vec3x4 a, Vec3x4 b) {
    return _mm_add_ps(_mm_add_ps(_mm_mul_ps(a.x, b.x), _mm_mul_ps(a.y, b.y)), _mm_mul_ps(a.z, b.z));
}
inline Vec3x4 cross(Vec3x4 a, Vec3x4 b) {
    return {_mm_sub_ps(_mm_mul_ps(a.y, b.z), _mm_mul_ps(a.z, b.y)),
            _mm_sub_ps(_mm_mul_ps(a.z, b.x), _mm_mul_ps(a.x, b.z)),
            _mm_sub_ps(_mm_mul_ps(a.x, b.y), _mm_mul_ps(a.y, b.x))};
}

/// Four triangles in lanes: p0, e1, e2 and the primitive ids.
struct Triangle4 {
    Vec3x4 p0, e1, e2;
    __m128i ids;

    /// Transposes prims[index[0..3]]. A BvhPrimitive is p0.xyz id | e1.xyz e2.x | e2.yz; the
    /// three 16-byte loads per triangle (at bytes 0, 16 and 24) stay inside the record.
    static Triangle4 load(const BvhPrimitive* prims, const uint32_t index[4]) {
        static_assert(sizeof(BvhPrimitive) == 40, "the loads below assume the 40-byte record");
        __m128 a[4], b[4], c[4];
        for (int l = 0; l < 4; ++l) {
            const float* f = reinterpret_cast<const float*>(prims + index[l]);
            a[l] = _mm_loadu_ps(f);      // p0.x p0.y p0.z id
            b[l] = _mm_loadu_ps(f + 4);  // e1.x e1.y e1.z e2.x
            c[l] = _mm_loadu_ps(f + 6);  // e1.z e2.x e2.y e2.z
        }
        _MM_TRANSPOSE4_PS(a[0], a[1], a[2], a[3]);
        _MM_TRANSPOSE4_PS(b[0], b[1], b[2], b[3]);
        _MM_TRANSPOSE4_PS(c[0], c[1], c[2], c[3]);
        return Triangle4{
            {a[0], a[1], a[2]}, {b[0], b[1], b[2]}, {b[3], c[2], c[3]}, _mm_castps_si128(a[3])};
    }
    /// Lanes whose id is below `numTriangles` (the others are spheres or cylinders).
    uint32_t triangleLanes(uint32_t numTriangles) const {
        const __m128i bias = _mm_set1_epi32(int(0x80000000u));  // unsigned compare via signed
        const __m128i lt = _mm_cmplt_epi32(_mm_xor_si128(ids, bias),
                                           _mm_xor_si128(_mm_set1_epi32(int(numTriangles)), bias));
        return uint32_t(_mm_movemask_ps(_mm_castsi128_ps(lt)));
    }
};

/// intersectTriangle on four lanes: returns the mask of lanes hit in (0, tMax) and their t, b1, b2.
inline uint32_t intersectTriangle4(const Vec3x4& o, const Vec3x4& d, float tMax,
                                   const Triangle4& tri, float tOut[4], float b1Out[4],
                                   float b2Out[4]) {
    const __m128 zero = _mm_setzero_ps(), signBit = _mm_set1_ps(-0.0f);
    const __m128 limit = _mm_set1_ps(tMax);
    const Vec3x4 n = cross(tri.e1, tri.e2);
    const __m128 den = dot(d, n);
    const Vec3x4 c = tri.p0 - o;
    const Vec3x4 r = cross(c, d);
    // u = e2 . r, v = -(e1 . r), tNum = c . n, all negated where den < 0 (a sign flip, as `-x`).
    const __m128 flip = _mm_and_ps(_mm_cmplt_ps(den, zero), signBit);
    const __m128 u = _mm_xor_ps(dot(tri.e2, r), flip);
    const __m128 v = _mm_xor_ps(_mm_xor_ps(dot(tri.e1, r), signBit), flip);
    const __m128 tNum = _mm_xor_ps(dot(c, n), flip);
    const __m128 absDen = _mm_xor_ps(den, flip);
    __m128 ok = _mm_and_ps(_mm_cmpgt_ps(absDen, zero), _mm_cmpge_ps(u, zero));
    ok = _mm_and_ps(ok, _mm_cmpge_ps(v, zero));
    ok = _mm_and_ps(ok, _mm_cmple_ps(_mm_add_ps(u, v), absDen));
    ok = _mm_and_ps(ok, _mm_cmpgt_ps(tNum, zero));
    ok = _mm_and_ps(ok, _mm_cmplt_ps(tNum, _mm_mul_ps(absDen, limit)));
    if (_mm_movemask_ps(ok) == 0) return 0;
    const __m128 invDen = _mm_div_ps(_mm_set1_ps(1.0f), absDen);
    const __m128 t = _mm_mul_ps(tNum, invDen);
    ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpgt_ps(t, zero), _mm_cmplt_ps(t, limit)));
    _mm_storeu_ps(tOut, t);
    _mm_storeu_ps(b1Out, _mm_mul_ps(u, invDen));
    _mm_storeu_ps(b2Out, _mm_mul_ps(v, invDen));
    return uint32_t(_mm_movemask_ps(ok));
}

}  // namespace caustica::bvh_detail
#endif  // CA_BVH_SSE
