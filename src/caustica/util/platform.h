// platform.h — the one macro that makes a function callable from CPU and GPU code.
//
// Everything marked CA_HD is shared kernel code: it is compiled by g++ for the CPU and by nvcc for
// the GPU (cuda/kernel_check.cu proves it in CI). Such code must not use virtual calls, exceptions,
// std::function, heap allocation or host-only library calls.
#pragma once

#if defined(__CUDACC__)
#define CA_HD __host__ __device__
#define CA_HD_INLINE __host__ __device__ __forceinline__
#else
#define CA_HD
#define CA_HD_INLINE inline
#endif

// CA_HD_INLINE with inlining forced on the host as well (g++ otherwise keeps some small, hot
// functions of the per-hit code as calls: each then passes its vectors through the stack).
#if defined(__CUDACC__)
#define CA_HD_FORCE_INLINE __host__ __device__ __forceinline__
#elif defined(__GNUC__)
#define CA_HD_FORCE_INLINE inline __attribute__((always_inline))
#else
#define CA_HD_FORCE_INLINE inline
#endif

#if defined(__CUDA_ARCH__)
#define CA_GPU_CODE 1
#else
#define CA_GPU_CODE 0
#endif
