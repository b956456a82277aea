// simd4.h — the small vector toolkit of the BVH traversal, one source for CPU and GPU:
//   CA_BVH_INLINE  CA_HD_INLINE with inlining forced on the host as well
//   Float4         four floats: an SSE register on the host, a plain array in GPU code (and on
//                  hosts without SSE2), where the loops become scalar code
//   lowestBit      index of the lowest set bit of a non-zero mask (highestBit: the highest)
// Float4's operations round exactly like the scalar expressions they stand for (min/max follow
// caustica::min/max, including which operand a NaN yields), so SSE and scalar traversals give
// bit-identical results.
#pragma once

#include <cstdint>

#include "caustica/util/platform.h"

#if !defined(__CUDA_ARCH__) && (defined(__SSE2__) || defined(_M_X64))
#define CA_BVH_SSE 1
#include <emmintrin.h>
#else
#define CA_BVH_SSE 0
#endif

// At -O3 GCC kept the triangle test, the box test and the ray set-up as calls inside the
// traversal loop; forcing them inline made the traversal 10-30% faster (docs/PERFORMANCE.md).
#if defined(__CUDACC__)
#define CA_BVH_INLINE __host__ __device__ __forceinline__
#elif defined(__GNUC__)
#define CA_BVH_INLINE inline __attribute__((always_inline))
#else
#define CA_BVH_INLINE inline
#endif
// The same for a host lambda (written between its parameter list and its body).
#if defined(__GNUC__) && !defined(__CUDACC__)
#define CA_BVH_LAMBDA_INLINE __attribute__((always_inline))
#else
#define CA_BVH_LAMBDA_INLINE
#endif

namespace caustica {

/// Index of the lowest set bit of `mask` (not 0).
CA_BVH_INLINE int lowestBit(uint32_t mask) {
#if defined(__CUDA_ARCH__)
    return __ffs(int(mask)) - 1;
#elif defined(__GNUC__)
    return __builtin_ctz(mask);
#else
    int k = 0;
    while (!(mask & 1u)) {
        mask >>= 1;
        ++k;
    }
    return k;
#endif
}

/// Index of the highest set bit of `mask` (not 0).
CA_BVH_INLINE int highestBit(uint32_t mask) {
#if defined(__CUDA_ARCH__)
    return 31 - __clz(int(mask));
#elif defined(__GNUC__)
    return 31 - __builtin_clz(mask);
#else
    int k = 31;
    while (!(mask & 0x80000000u)) {
        mask <<= 1;
        --k;
    }
    return k;
#endif
}

/// Four floats with the element-wise operations of the slab test.
struct Float4 {
#if CA_BVH_SSE
    __m128 v;

    static Float4 load(const float* p) {
        return {_mm_load_ps(p)};
    }  // p 16-byte aligned
    static Float4 broadcast(float f) {
        return {_mm_set1_ps(f)};
    }
    void store(float* p) const {
        _mm_storeu_ps(p, v);
    }
    friend Float4 operator-(Float4 a, Float4 b) {
        return {_mm_sub_ps(a.v, b.v)};
    }
    friend Float4 operator*(Float4 a, Float4 b) {
        return {_mm_mul_ps(a.v, b.v)};
    }
    // minps/maxps return the second operand unless the comparison holds: a < b ? a : b.
    friend Float4 min(Float4 a, Float4 b) {
        return {_mm_min_ps(a.v, b.v)};
    }
    friend Float4 max(Float4 a, Float4 b) {
        return {_mm_max_ps(a.v, b.v)};
    }
    /// Bit k set where a[k] <= b[k] (false for NaN).
    friend uint32_t lessEqualMask(Float4 a, Float4 b) {
        return uint32_t(_mm_movemask_ps(_mm_cmple_ps(a.v, b.v)));
    }
#else
    float v[4];

    CA_BVH_INLINE static Float4 load(const float* p) {
        return {{p[0], p[1], p[2], p[3]}};
    }
    CA_BVH_INLINE static Float4 broadcast(float f) {
        return {{f, f, f, f}};
    }
    CA_BVH_INLINE void store(float* p) const {
        for (int k = 0; k < 4; ++k) p[k] = v[k];
    }
    template <class Op>
    CA_BVH_INLINE static Float4 map(Float4 a, Float4 b, Op op) {
        Float4 r;
        for (int k = 0; k < 4; ++k) r.v[k] = op(a.v[k], b.v[k]);
        return r;
    }
    CA_BVH_INLINE friend Float4 operator-(Float4 a, Float4 b) {
        return map(a, b, [](float x, float y) { return x - y; });
    }
    CA_BVH_INLINE friend Float4 operator*(Float4 a, Float4 b) {
        return map(a, b, [](float x, float y) { return x * y; });
    }
    CA_BVH_INLINE friend Float4 min(Float4 a, Float4 b) {
        return map(a, b, [](float x, float y) { return x < y ? x : y; });
    }
    CA_BVH_INLINE friend Float4 max(Float4 a, Float4 b) {
        return map(a, b, [](float x, float y) { return x > y ? x : y; });
    }
    CA_BVH_INLINE friend uint32_t lessEqualMask(Float4 a, Float4 b) {
        uint32_t mask = 0;
        for (int k = 0; k < 4; ++k) mask |= uint32_t(a.v[k] <= b.v[k]) << k;
        return mask;
    }
#endif
};

}  // namespace caustica
