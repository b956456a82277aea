// unfused.h — products that are never fused into multiply-adds, for the spatial predicates
// (inBall, the segment distance, the k-nearest distances), so that every structure computes them
// to the same bits. The host build targets baseline x86-64, which has no FMA; nvcc contracts a product
// and a sum into one multiply-add where it sees fit, and it saw fit differently in the inlined
// copies of different structures: on an H200 the uniform grid's segment query missed one sphere
// of 24 million that the hash grid, the kd-tree, the multi-level hash and the CPU all found
// (bench_gpu_spatial, 2026-11-27). A product rounded on its own (__fmul_rn) cannot be fused.
// The watertight triangle test (accel/primitive_intersect.h) needs the same for its edge functions.
#pragma once

#include "caustica/util/math.h"

namespace caustica {

/// a * b, rounded on its own (never fused into a multiply-add).
CA_HD_INLINE Float mulUnfused(Float a, Float b) {
#ifdef __CUDA_ARCH__
    return __fmul_rn(a, b);
#else
    return a * b;
#endif
}

/// dot(a, b) as ((a.x b.x + a.y b.y) + a.z b.z) with every product rounded on its own.
CA_HD_INLINE Float dotUnfused(Vec3f a, Vec3f b) {
    return mulUnfused(a.x, b.x) + mulUnfused(a.y, b.y) + mulUnfused(a.z, b.z);
}

/// |p - c|^2 in float, unfused.
CA_HD_INLINE Float distanceSquaredUnfused(Vec3f p, Vec3f c) {
    const Vec3f d = p - c;
    return dotUnfused(d, d);
}

}  // namespace caustica
