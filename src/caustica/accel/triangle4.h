// triangle4.h — one ray against four precomputed triangles at once with SSE (host only).
//
// The lanes run exactly the operations of the watertight intersectTriangle (primitive_intersect.h)
// in the same order, without fused multiply-adds, so every lane's t, b1, b2 are bit-identical to
// the scalar test's (its double-precision redo of zero edge functions included); the GPU and hosts without SSE keep the scalar loop (bvh_traversal.h, intersectLeaf).
// Triangles are read from the leaf-order BvhPrimitive array (40 bytes each, AoS) and transposed
// into lanes, so the layout the GPU reads stays unchanged.
#pragma once

#include <cstdint>

#include "caustica/accel/bvh.h"
#include "caustica/accel/primitive_intersect.h"
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

/// Four triangles in lanes: their vertices and the primitive ids.
struct Triangle4 {
    Vec3x4 p0, p1, p2;
    __m128i ids;

    /// Transposes prims[index[0..3]]. A BvhPrimitive is p0.xyz id | p1.xyz p2.x | p2.yz; the
    /// three 16-byte loads per triangle (at bytes 0, 16 and 24) stay inside the record.
    CA_BVH_INLINE static Triangle4 load(const BvhPrimitive* prims, const uint32_t index[4]) {
        static_assert(sizeof(BvhPrimitive) == 40, "the loads below assume the 40-byte record");
        __m128 a[4], b[4], c[4];
        for (int l = 0; l < 4; ++l) {
            const float* f = reinterpret_cast<const float*>(prims + index[l]);
            a[l] = _mm_loadu_ps(f);      // p0.x p0.y p0.z id
            b[l] = _mm_loadu_ps(f + 4);  // p1.x p1.y p1.z p2.x
            c[l] = _mm_loadu_ps(f + 6);  // p1.z p2.x p2.y p2.z
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

/// The watertight intersectTriangleWith (primitive_intersect.h) on four lanes, for the ray of origin
/// `o` (broadcast) and per-ray constants `r`: returns the mask of lanes hit in (0, tMax) and their
/// t, b1, b2. Forced inline: GCC kept it as a call in the leaf loop (8% of a path-tracing profile).
CA_BVH_INLINE uint32_t intersectTriangle4(const Vec3x4& o, const WatertightRay& r, float tMax,
                                   const Triangle4& tri, float tOut[4], float b1Out[4],
                                   float b2Out[4]) {
    const __m128 zero = _mm_setzero_ps(), signBit = _mm_set1_ps(-0.0f);
    const __m128 sx = _mm_set1_ps(r.sx), sy = _mm_set1_ps(r.sy), sz = _mm_set1_ps(r.sz);
    // Vertices relative to the origin, sheared: x, y in the plane, z along the ray. The axes are
    // picked by indexing an array: selecting registers by kx, ky, kz compiled to 18 branches.
    __m128 rel[3][3];  // [vertex][axis]
    const Vec3x4* vertices[3] = {&tri.p0, &tri.p1, &tri.p2};
    for (int k = 0; k < 3; ++k) {
        rel[k][0] = _mm_sub_ps(vertices[k]->x, o.x);
        rel[k][1] = _mm_sub_ps(vertices[k]->y, o.y);
        rel[k][2] = _mm_sub_ps(vertices[k]->z, o.z);
    }
    struct Sheared {
        __m128 x, y, z;
    };
    // Forced inline, as the function: GCC kept the lambda as a call (7% of a shadow-ray profile).
    auto shear = [&](const __m128* p) CA_BVH_LAMBDA_INLINE {
        const __m128 z = p[r.kz];
        return Sheared{_mm_sub_ps(p[r.kx], _mm_mul_ps(sx, z)), _mm_sub_ps(p[r.ky], _mm_mul_ps(sy, z)),
                       z};
    };
    const Sheared a = shear(rel[0]), b = shear(rel[1]), c = shear(rel[2]);
    auto edge = [](const Sheared& p, const Sheared& q) {
        return _mm_sub_ps(_mm_mul_ps(p.x, q.y), _mm_mul_ps(p.y, q.x));
    };
    __m128 u = edge(c, b), v = edge(a, c), w = edge(b, a);
    const uint32_t redo = uint32_t(_mm_movemask_ps(_mm_or_ps(
        _mm_or_ps(_mm_cmpeq_ps(u, zero), _mm_cmpeq_ps(v, zero)), _mm_cmpeq_ps(w, zero))));
    if (redo != 0) {  // some lane's ray passes through an edge or vertex: as the scalar test
        alignas(16) float ax[4], ay[4], bx[4], by[4], cx[4], cy[4], uu[4], vv[4], ww[4];
        _mm_store_ps(ax, a.x), _mm_store_ps(ay, a.y), _mm_store_ps(bx, b.x);
        _mm_store_ps(by, b.y), _mm_store_ps(cx, c.x), _mm_store_ps(cy, c.y);
        _mm_store_ps(uu, u), _mm_store_ps(vv, v), _mm_store_ps(ww, w);
        for (uint32_t m = redo; m != 0; m &= m - 1) {
            const int l = lowestBit(m);
            uu[l] = watertight_detail::edgeFunctionDouble(cx[l], cy[l], bx[l], by[l]);
            vv[l] = watertight_detail::edgeFunctionDouble(ax[l], ay[l], cx[l], cy[l]);
            ww[l] = watertight_detail::edgeFunctionDouble(bx[l], by[l], ax[l], ay[l]);
        }
        u = _mm_load_ps(uu), v = _mm_load_ps(vv), w = _mm_load_ps(ww);
    }
    const __m128 anyNegative = _mm_or_ps(
        _mm_or_ps(_mm_cmplt_ps(u, zero), _mm_cmplt_ps(v, zero)), _mm_cmplt_ps(w, zero));
    const __m128 anyPositive = _mm_or_ps(
        _mm_or_ps(_mm_cmpgt_ps(u, zero), _mm_cmpgt_ps(v, zero)), _mm_cmpgt_ps(w, zero));
    __m128 ok = _mm_andnot_ps(_mm_and_ps(anyNegative, anyPositive), _mm_cmpeq_ps(zero, zero));
    if (_mm_movemask_ps(ok) == 0) return 0;
    const __m128 det = _mm_add_ps(_mm_add_ps(u, v), w);
    const __m128 tNum =
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(u, _mm_mul_ps(sz, a.z)), _mm_mul_ps(v, _mm_mul_ps(sz, b.z))),
                   _mm_mul_ps(w, _mm_mul_ps(sz, c.z)));
    // Signs flipped where det < 0 (a sign flip, as `-x`).
    const __m128 flip = _mm_and_ps(_mm_cmplt_ps(det, zero), signBit);
    const __m128 absDet = _mm_xor_ps(det, flip), tPos = _mm_xor_ps(tNum, flip);
    const __m128 limit = _mm_set1_ps(tMax);
    ok = _mm_and_ps(ok, _mm_cmpgt_ps(absDet, zero));
    ok = _mm_and_ps(ok, _mm_cmpgt_ps(tPos, zero));
    ok = _mm_and_ps(ok, _mm_cmplt_ps(tPos, _mm_mul_ps(absDet, limit)));
    if (_mm_movemask_ps(ok) == 0) return 0;
    const __m128 invDet = _mm_div_ps(_mm_set1_ps(1.0f), absDet);
    const __m128 t = _mm_mul_ps(tPos, invDet);
    ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpgt_ps(t, zero), _mm_cmplt_ps(t, limit)));
    _mm_storeu_ps(tOut, t);
    _mm_storeu_ps(b1Out, _mm_mul_ps(_mm_xor_ps(v, flip), invDet));
    _mm_storeu_ps(b2Out, _mm_mul_ps(_mm_xor_ps(w, flip), invDet));
    return uint32_t(_mm_movemask_ps(ok));
}

}  // namespace caustica::bvh_detail
#endif  // CA_BVH_SSE
