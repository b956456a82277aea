// bvh_traversal.h — closest-hit and any-hit BVH traversal, one source for CPU and GPU.
//
// Stack-based, no recursion, no allocation: at an inner node all (up to four) child boxes are
// tested, the nearest child hit is visited next and the others are pushed far to near together with
// their entry distances, so that they are skipped on pop when a closer hit has been found
// meanwhile.
//
// Choices measured with bench/bench_rays.cpp (docs/PERFORMANCE.md): 4-wide nodes with SoA boxes
// (1.3-1.7x faster than the binary layout they are collapsed from); the next node chosen with
// branches rather than selects (a select makes the next fetch wait for the box tests); ordering by
// entry distance rather than by direction signs; precomputed leaf-order primitives.
#pragma once

#include <cstdint>

#include "caustica/accel/bvh.h"
#include "caustica/accel/primitive_intersect.h"
#include "caustica/scene/ray.h"
#include "caustica/scene/scene.h"

namespace caustica {
namespace bvh_detail {

/// Per-ray data for the slab test. Zero (and denormal) direction components give an inverse of
/// +-FLT_MAX instead of infinity, so that (lo - o) * invD is never 0 * inf = NaN.
struct TraversalRay {
    Vec3f o, invD;
    CA_HD explicit TraversalRay(const Ray& ray) : o(ray.o) {
        for (int i = 0; i < 3; ++i) {
            const Float inv = 1 / ray.d[i];
            invD[i] = std::fabs(inv) <= kInfinity ? inv : std::copysign(kInfinity, ray.d[i]);
        }
    }
};

/// Slab tests (Kay and Kajiya, "Ray Tracing Complex Scenes", SIGGRAPH 1986) of the four child
/// boxes of `node` against [0, tMax]. Returns a bit mask of the children hit and their entry
/// distances. The exit distance is enlarged by 1 + 2 gamma(3) so that rounding never culls a box
/// the ray touches (Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013; as pbrt-v4 does). Empty
/// slots have NaN boxes, for which every comparison fails.
CA_HD_INLINE uint32_t intersectChildren(const BvhNode& node, const TraversalRay& r, Float tMax,
                                        Float tEntry[BvhNode::kWidth]) {
    constexpr Float kRobustScale = 1 + 2 * (3 * 0x1p-24f) / (1 - 3 * 0x1p-24f);
    const Float o[3] = {r.o.x, r.o.y, r.o.z}, invD[3] = {r.invD.x, r.invD.y, r.invD.z};
    Float tExit[BvhNode::kWidth];
    // Straight-line loops over the four children: vectorised on the CPU (4-wide SSE).
    for (int k = 0; k < BvhNode::kWidth; ++k) {
        Float t0[3], t1[3];
        for (int axis = 0; axis < 3; ++axis) {
            t0[axis] = (node.lo[axis][k] - o[axis]) * invD[axis];
            t1[axis] = (node.hi[axis][k] - o[axis]) * invD[axis];
        }
        // tEntry is not clamped to 0: it only orders and culls subtrees, which a negative value
        // does correctly, and the overlap test below checks tExit >= 0 instead.
        tEntry[k] = max(max(min(t0[0], t1[0]), min(t0[1], t1[1])), min(t0[2], t1[2]));
        tExit[k] = min(min(max(t0[0], t1[0]), max(t0[1], t1[1])), max(t0[2], t1[2])) * kRobustScale;
    }
    uint32_t mask = 0;
    for (int k = 0; k < BvhNode::kWidth; ++k)
        mask |= uint32_t((tEntry[k] <= min(tExit[k], tMax)) & (tExit[k] >= 0)) << k;
    return mask;
}

/// Tests primitives [begin, begin + count) of primIndices, updating `hit` (whose t is the current
/// search limit).
template <bool AnyHit>
CA_HD_INLINE bool intersectLeaf(const BvhView& bvh, const SceneView& scene, uint32_t begin,
                                uint32_t count, const Ray& ray, Hit& hit) {
    bool found = false;
    const uint32_t numTriangles = scene.numTriangles();
    const uint32_t end = begin + count;
    if (bvh.prims.empty()) {
        for (uint32_t i = begin; i < end; ++i) {
            if (intersectPrimitive(scene, bvh.primIndices[i], ray, hit)) {
                if (AnyHit) return true;
                found = true;
            }
        }
        return found;
    }
    for (uint32_t i = begin; i < end; ++i) {
        const BvhPrimitive& p = bvh.prims[i];
        const uint32_t id = p.primId;
        Float t, b1 = 0, b2 = 0;
        const bool h = id < numTriangles
                           ? intersectTriangle(ray.o, ray.d, hit.t, p.p0, p.e1, p.e2, t, b1, b2)
                           : intersectSphere(ray.o, ray.d, hit.t, p.p0, p.e1.x, t);
        if (h) {
            if (AnyHit) return true;
            hit.t = t;
            hit.primId = id;
            hit.b1 = b1;
            hit.b2 = b2;
            found = true;
        }
    }
    return found;
}

/// Shared traversal loop. `best.t` holds the search limit on entry and the closest t on exit.
/// The child being visited is carried in registers as (offset, count), copied from its parent's
/// slot, so each step costs one dependent memory access: the node of its children.
template <bool AnyHit>
CA_HD bool traverse(const BvhView& bvh, const SceneView& scene, const Ray& ray, Hit& best) {
    if (bvh.nodes.empty()) return false;
    const TraversalRay r(ray);
    struct Entry {
        uint32_t offset, count;
        Float tNear;
    };
    Entry stack[kBvhStackSize];
    int sp = 0;
    uint32_t offset = 0, count = 0;  // start at the root node
    bool found = false;
    for (;;) {
        if (count > 0) {
            if (intersectLeaf<AnyHit>(bvh, scene, offset, count, ray, best)) {
                if (AnyHit) return true;
                found = true;
            }
        } else {
            const BvhNode& node = bvh.nodes[offset];
            Float tEntry[BvhNode::kWidth];
            uint32_t mask = intersectChildren(node, r, best.t, tEntry);
            if (mask != 0) {
                // Children hit, sorted front to back by entry distance (insertion sort of <= 4).
                int order[BvhNode::kWidth];
                int n = 0;
                for (int k = 0; k < BvhNode::kWidth; ++k) {
                    if (!(mask & (1u << k))) continue;
                    int j = n++;
                    for (; j > 0 && tEntry[order[j - 1]] > tEntry[k]; --j) order[j] = order[j - 1];
                    order[j] = k;
                }
                // Farther children wait on the stack, the nearest is visited now.
                for (int j = n - 1; j > 0; --j) {
                    const int k = order[j];
                    stack[sp++] = Entry{node.offset[k], node.count[k], tEntry[k]};
                }
                offset = node.offset[order[0]];
                count = node.count[order[0]];
                continue;
            }
        }
        // Pop the next subtree that may still hold a closer hit.
        for (;;) {
            if (sp == 0) return found;
            --sp;
            if (AnyHit || stack[sp].tNear <= best.t) {
                offset = stack[sp].offset;
                count = stack[sp].count;
                break;
            }
        }
    }
}

}  // namespace bvh_detail

/// Closest hit of `ray` with t in (0, ray.tMax). On a hit, fills `hit` (t, primId, b1, b2) and
/// returns true; otherwise leaves `hit` unchanged.
CA_HD_INLINE bool bvhIntersect(const BvhView& bvh, const SceneView& scene, const Ray& ray,
                               Hit& hit) {
    Hit best;
    best.t = ray.tMax;
    if (!bvh_detail::traverse<false>(bvh, scene, ray, best)) return false;
    hit = best;
    return true;
}

/// True if anything is hit with t in (0, ray.tMax) (shadow rays).
CA_HD_INLINE bool bvhOccluded(const BvhView& bvh, const SceneView& scene, const Ray& ray) {
    Hit best;
    best.t = ray.tMax;
    return bvh_detail::traverse<true>(bvh, scene, ray, best);
}

}  // namespace caustica
