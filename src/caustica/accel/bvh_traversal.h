// bvh_traversal.h — closest-hit and any-hit BVH traversal, one source for CPU and GPU.
//
// Stack-based, no recursion, no allocation: at an interior node both children's boxes are tested,
// the nearer child is visited next and the farther one pushed together with its entry distance, so
// that it is skipped on pop when a closer hit has been found meanwhile.
//
// Choices measured with bench/bench_rays.cpp (docs/PERFORMANCE.md): children stored as a pair in
// one cache line; the next node chosen with branches rather than selects (a select makes the next
// fetch wait for the box tests: 20% slower); ordering by entry distance rather than by the sign of
// the ray direction on the split axis (10-20% faster); precomputed leaf-order primitives.
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

/// Slab test (Kay and Kajiya, "Ray Tracing Complex Scenes", SIGGRAPH 1986) against [0, tMax]. The
/// far distance is enlarged by 1 + 2 gamma(3) so that rounding never culls a box the ray touches
/// (Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013; as in pbrt-v4's Bounds3::IntersectP).
CA_HD_INLINE bool intersectBox(const BvhNode& node, const TraversalRay& r, Float tMax,
                               Float& tNear) {
    constexpr Float kRobustScale = 1 + 2 * (3 * 0x1p-24f) / (1 - 3 * 0x1p-24f);
    const Float tx0 = (node.lo.x - r.o.x) * r.invD.x, tx1 = (node.hi.x - r.o.x) * r.invD.x;
    const Float ty0 = (node.lo.y - r.o.y) * r.invD.y, ty1 = (node.hi.y - r.o.y) * r.invD.y;
    const Float tz0 = (node.lo.z - r.o.z) * r.invD.z, tz1 = (node.hi.z - r.o.z) * r.invD.z;
    // The box overlaps [0, tMax] iff tEntry <= min(tExit, tMax) and tExit >= 0. tEntry is not
    // clamped to 0: it only orders and culls subtrees, and a negative value does both correctly.
    // (Clamping made GCC emit a data-dependent branch per box.)
    const Float tEntry = max(max(min(tx0, tx1), min(ty0, ty1)), min(tz0, tz1));
    const Float tExit = min(min(max(tx0, tx1), max(ty0, ty1)), max(tz0, tz1)) * kRobustScale;
    tNear = tEntry;
    return (tEntry <= min(tExit, tMax)) & (tExit >= 0);
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
/// The node being visited is carried in registers as (offset, count) — copied from its record in
/// the parent's pair, which was just read for the box test — so each step costs one dependent
/// memory access: the pair of its children.
template <bool AnyHit>
CA_HD bool traverse(const BvhView& bvh, const SceneView& scene, const Ray& ray, Hit& best) {
    if (bvh.nodes.empty()) return false;
    const TraversalRay r(ray);
    Float tNear;
    if (!intersectBox(bvh.nodes[0], r, best.t, tNear)) return false;

    struct Entry {
        uint32_t offset, count;
        Float tNear;
    };
    Entry stack[kBvhStackSize];
    int sp = 0;
    uint32_t offset = bvh.nodes[0].offset, count = bvh.nodes[0].primCount();
    bool found = false;
    for (;;) {
        if (count > 0) {
            if (intersectLeaf<AnyHit>(bvh, scene, offset, count, ray, best)) {
                if (AnyHit) return true;
                found = true;
            }
        } else {
            // Both children share one cache line; their links are read along with their boxes.
            const BvhNode& a = bvh.nodes[offset];
            const BvhNode& b = bvh.nodes[offset + 1];
            const uint32_t offsetA = a.offset, countA = a.primCount();
            const uint32_t offsetB = b.offset, countB = b.primCount();
            Float tA, tB;
            const bool hitA = intersectBox(a, r, best.t, tA);
            const bool hitB = intersectBox(b, r, best.t, tB);
            // Plain branches, not selects: the CPU predicts which child comes next and starts
            // fetching its children while the box test is still being resolved.
            if (hitA && hitB) {
                // Visit the nearer child now, the farther one later (front to back).
                if (tB < tA) {
                    stack[sp++] = Entry{offsetA, countA, tA};
                    offset = offsetB;
                    count = countB;
                } else {
                    stack[sp++] = Entry{offsetB, countB, tB};
                    offset = offsetA;
                    count = countA;
                }
                continue;
            }
            if (hitA) {
                offset = offsetA;
                count = countA;
                continue;
            }
            if (hitB) {
                offset = offsetB;
                count = countB;
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
