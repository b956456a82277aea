// simd4.h — the small vector toolkit of the BVH traversal, one source for CPU and GPU:
//   CA_BVH_INLINE  CA_HD_INLINE with inlining forced on the host as well
//   Float4         four floats (util/float4.h): an SSE register on the host, a plain array in
//                  GPU code (and on hosts without SSE2)
//   lowestBit      index of the lowest set bit of a non-zero mask (highestBit: the highest)
// Float4's operations round exactly like the scalar expressions they stand for, so SSE and scalar
// traversals give bit-identical results.
#pragma once

#include <cstdint>

#include "caustica/util/float4.h"
#include "caustica/util/platform.h"

#define CA_BVH_SSE CA_FLOAT4_SSE

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

}  // namespace caustica
