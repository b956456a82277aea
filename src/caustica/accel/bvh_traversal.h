// bvh_traversal.h — closest-hit and any-hit BVH traversal, one source for CPU and GPU.
//
// Stack-based, no recursion, no allocation: at an inner node all (up to eight) child boxes are
// tested, the first child hit in visiting order (orderChildren: nearest first for closest-hit
// queries, slot order for any-hit ones) is visited next and the others are pushed with their entry
// distances, so that they are skipped on pop when a closer hit has been found meanwhile.
//
// Two more variants share the slab tests, the child ordering and the leaf step (BvhTraversal): a
// short-stack traversal, whose stack is a small ring buffer that drops its oldest entries when full
// and, once it runs empty after such a loss, continues by backtracking through parent links
// (Bvh::parents); and the stackless traversal, the same with no stack at all. Both follow the
// parent-link scheme of Hapala et al., "Efficient Stack-less BVH Traversal for Ray Tracing" (SCCG
// 2011), on wide nodes as in Afra and Szirmay-Kalos, "Stackless Multi-BVH Traversal for CPU, MIC
// and GPU Ray Tracing" (CGF 33(1), 2014), with the children of a node visited in the same order as
// the stack traversal.
//
// Choices measured with bench/bench_rays.cpp (docs/PERFORMANCE.md): 8-wide nodes with SoA boxes
// tested as two SSE halves, near/far planes chosen per ray; the next node chosen with branches
// rather than selects (a select makes the next fetch wait for the box tests); ordering by entry
// distance rather than by direction signs (closest hit), no ordering at all (any hit);
// precomputed leaf-order primitives, tested four at a time on the host (triangle4.h).
#pragma once

#include <cstdint>

#include "caustica/accel/bvh.h"
#include "caustica/accel/primitive_intersect.h"
#include "caustica/accel/simd4.h"
#include "caustica/accel/triangle4.h"
#include "caustica/scene/ray.h"
#include "caustica/scene/scene.h"

namespace caustica {
namespace bvh_detail {

/// Per-ray data for the slab test. Zero (and denormal) direction components give an inverse of
/// +-FLT_MAX instead of infinity, so that (lo - o) * invD is never 0 * inf = NaN. nearPlane[axis]
/// and farPlane[axis] index the node's lo-then-hi plane array (BvhNode) at the plane of `axis`
/// that the ray meets first and last, chosen by the sign of invD: since lo <= hi, the near plane's
/// distance is exactly the min of the two that the slab test would otherwise compute (and the far
/// plane's the max), so choosing ahead saves the min/max without changing a bit.
/// `triangle` holds the per-ray constants of the watertight triangle test (primitive_intersect.h).
struct TraversalRay {
    Float4 o[3], invD[3];  // each component in all four lanes
    int nearPlane[3], farPlane[3];
    WatertightRay triangle;
    CA_BVH_INLINE explicit TraversalRay(const Ray& ray) : triangle(makeWatertightRay(ray.d)) {
        constexpr int W = BvhNode::kWidth;
        for (int axis = 0; axis < 3; ++axis) {
            const Float d = ray.d[axis], inv = 1 / d;
            const Float invDAxis = std::fabs(inv) <= kInfinity ? inv : std::copysign(kInfinity, d);
            o[axis] = Float4::broadcast(ray.o[axis]);
            invD[axis] = Float4::broadcast(invDAxis);
            const bool negative = std::signbit(invDAxis);
            nearPlane[axis] = (negative ? 3 * W : 0) + axis * W;
            farPlane[axis] = (negative ? 0 : 3 * W) + axis * W;
        }
    }
};

/// Slab tests (Kay and Kajiya, "Ray Tracing Complex Scenes", SIGGRAPH 1986) of the child boxes of
/// `node` against [0, tMax], four at a time. Returns a bit mask of the children hit and their entry
/// distances. The exit distance is enlarged by 1 + 2 gamma(3) so that rounding never culls a box
/// the ray touches (Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013; as pbrt-v4 does). Empty
/// slots have NaN boxes, for which every comparison fails.
CA_BVH_INLINE uint32_t intersectChildren(const BvhNode& node, const TraversalRay& r, Float tMax,
                                         Float tEntry[BvhNode::kWidth]) {
    constexpr Float kRobustScale = 1 + 2 * (3 * 0x1p-24f) / (1 - 3 * 0x1p-24f);
    const float* planes = &node.lo[0][0];  // lo[3][kWidth], then hi[3][kWidth]
    const Float4 robustScale = Float4::broadcast(kRobustScale), limit = Float4::broadcast(tMax),
                 zero = Float4::broadcast(0);
    uint32_t mask = 0;
    for (int k = 0; k < BvhNode::kWidth; k += 4) {
        auto distance = [&](int plane, int axis) {  // to the planes `plane` of children k..k+3
            return (Float4::load(planes + plane + k) - r.o[axis]) * r.invD[axis];
        };
        Float4 entry = distance(r.nearPlane[0], 0), exit = distance(r.farPlane[0], 0);
        for (int axis = 1; axis < 3; ++axis) {
            entry = max(entry, distance(r.nearPlane[axis], axis));
            exit = min(exit, distance(r.farPlane[axis], axis));
        }
        exit = exit * robustScale;
        // tEntry is not clamped to 0: it only orders and culls subtrees, which a negative value
        // does correctly, and the overlap test checks 0 <= exit instead.
        entry.store(tEntry + k);
        mask |= (lessEqualMask(entry, min(exit, limit)) & lessEqualMask(zero, exit)) << k;
    }
    return mask;
}

/// Orders the children in `mask` (not empty), hands all but the first to push(slot), last first,
/// and returns the first, which is visited next. Closest-hit queries go front to back by entry
/// distance (ties keep slot order). Any-hit queries take the children in slot order: they may stop
/// at any hit, so ordering buys them nothing (sorting cost 20% of the shadow rays' rate,
/// docs/PERFORMANCE.md), and push straight from the mask.
template <bool AnyHit, class Push>
CA_BVH_INLINE int orderChildren(uint32_t mask, const Float* tEntry, Push&& push) {
    const int first = lowestBit(mask);
    uint32_t rest = mask & (mask - 1);
    if (rest == 0) return first;  // one child: nothing to order
    if (AnyHit) {  // slot order: the others pushed highest first, so that they pop lowest first
        do {
            const int k = highestBit(rest);
            push(k);
            rest &= ~(1u << k);
        } while (rest != 0);
        return first;
    }
    // Insertion sort by entry distance. Its branches beat selects (even for two children, 1.4x
    // on bounce rays): a predicted branch lets the next node's fetch start before the box tests end.
    int order[BvhNode::kWidth];
    int n = 0;
    for (rest = mask; rest != 0; rest &= rest - 1) {
        const int k = lowestBit(rest);
        int j = n++;
        for (; j > 0 && tEntry[order[j - 1]] > tEntry[k]; --j) order[j] = order[j - 1];
        order[j] = k;
    }
    for (int j = n - 1; j > 0; --j) push(order[j]);
    return order[0];
}

/// Whether child `k` follows child `after` in orderChildren's order (a strict total order).
template <bool AnyHit>
CA_BVH_INLINE bool followsInOrder(int k, int after, const Float* tEntry) {
    if (AnyHit) return k > after;
    return tEntry[k] > tEntry[after] || (tEntry[k] == tEntry[after] && k > after);
}

/// Tests precomputed primitive `p` (BvhPrimitive) against [0, hit.t), updating `hit` on a hit.
/// `triangle` is the ray's WatertightRay.
CA_BVH_INLINE bool intersectPrecomputed(const BvhPrimitive& p, uint32_t numTriangles,
                                        uint32_t firstCylinder, const WatertightRay& triangle,
                                        const Ray& ray, Hit& hit) {
    const uint32_t id = p.primId;
    Float t, b1 = 0, b2 = 0;
    const bool h = id < numTriangles
                       ? intersectTriangleWith(triangle, ray.o, hit.t, p.p0, p.p1, p.p2, t, b1, b2)
                   : id < firstCylinder
                       ? intersectSphere(ray.o, ray.d, hit.t, p.p0, p.p1.x, t)
                       : intersectCylinder(ray.o, ray.d, hit.t, p.p0, p.p1, p.p2.x, p.p2.y, t);
    if (!h) return false;
    hit.t = t;
    hit.primId = id;
    hit.b1 = b1;
    hit.b2 = b2;
    return true;
}

#if CA_BVH_SSE
/// Host version of the precomputed leaf loop: four primitives at a time with intersectTriangle4
/// (triangle4.h), which gives each lane the scalar test's exact result. Of the lanes hit, the
/// smallest t wins, the earliest lane on a tie: the primitive the scalar loop would keep (it only
/// accepts t below the current limit, so it ends with the smallest t, the earliest on a tie, and
/// the limit it passes on changes no primitive's t, only whether it is taken). A last group of
/// fewer than four repeats the last primitive, which never beats its first copy. In a group that
/// holds spheres or cylinders, the triangle lanes still run as one SSE test and the others the
/// scalar one, all against the group's starting limit; the same rule then picks among them. A
/// group of one or two primitives is tested one by one.
template <bool AnyHit>
CA_BVH_INLINE bool intersectLeaf4(const BvhView& bvh, uint32_t numTriangles, uint32_t firstCylinder,
                                  uint32_t begin, uint32_t end, const TraversalRay& r,
                                  const Ray& ray, Hit& hit) {
    const Vec3x4 o{r.o[0].v, r.o[1].v, r.o[2].v};
    bool found = false;
    for (uint32_t i = begin; i < end; i += 4) {
        uint32_t index[4];
        for (uint32_t l = 0; l < 4; ++l) index[l] = min(i + l, end - 1);
        const Triangle4 tri = Triangle4::load(bvh.prims.data(), index);
        const uint32_t triangles = tri.triangleLanes(numTriangles);
        if (end - i < 3 || triangles == 0) {
            for (uint32_t j = i; j < min(i + 4, end); ++j)
                if (intersectPrecomputed(bvh.prims[j], numTriangles, firstCylinder, r.triangle, ray,
                                         hit)) {
                    if (AnyHit) return true;
                    found = true;
                }
            continue;
        }
        float t[4], b1[4], b2[4];
        uint32_t mask = intersectTriangle4(o, r.triangle, hit.t, tri, t, b1, b2) & triangles;
        // The other primitives of the group (each once: a repeated last one is not retested).
        for (uint32_t others = ~triangles & 0xFu & ((1u << min(4u, end - i)) - 1); others != 0;
             others &= others - 1) {
            const int l = lowestBit(others);
            Hit h = hit;
            if (!intersectPrecomputed(bvh.prims[index[l]], numTriangles, firstCylinder, r.triangle, ray, h))
                continue;
            t[l] = h.t;
            b1[l] = h.b1;
            b2[l] = h.b2;
            mask |= 1u << l;
        }
        if (mask == 0) continue;
        if (AnyHit) return true;
        int best = lowestBit(mask);
        for (mask &= mask - 1; mask != 0; mask &= mask - 1)
            if (t[lowestBit(mask)] < t[best]) best = lowestBit(mask);
        hit.t = t[best];
        hit.primId = bvh.prims[index[best]].primId;
        hit.b1 = b1[best];
        hit.b2 = b2[best];
        found = true;
    }
    return found;
}
#endif

/// Tests primitives [begin, begin + count) of primIndices, updating `hit` (whose t is the current
/// search limit).
template <bool AnyHit>
CA_BVH_INLINE bool intersectLeaf(const BvhView& bvh, const SceneView& scene, uint32_t begin,
                                 uint32_t count, const TraversalRay& r, const Ray& ray, Hit& hit) {
    bool found = false;
    const uint32_t numTriangles = scene.numTriangles();
    const uint32_t firstCylinder = scene.firstCylinder();
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
#if CA_BVH_SSE
    return intersectLeaf4<AnyHit>(bvh, numTriangles, firstCylinder, begin, end, r, ray, hit);
#else
    for (uint32_t i = begin; i < end; ++i) {
        if (intersectPrecomputed(bvh.prims[i], numTriangles, firstCylinder, r.triangle, ray, hit)) {
            if (AnyHit) return true;
            found = true;
        }
    }
    return found;
#endif
}

/// The step of every traversal at item (offset, count). A leaf (count > 0) has its primitives
/// tested against `best`, setting `found` on a hit, and yields no children; an inner node yields
/// the mask of its children the ray enters before best.t, with their entry distances in tEntry.
/// An any-hit traversal stops as soon as `found` is set.
template <bool AnyHit>
CA_BVH_INLINE uint32_t visitItem(const BvhView& bvh, const SceneView& scene, const Ray& ray,
                                 const TraversalRay& r, uint32_t offset, uint32_t count, Hit& best,
                                 bool& found, Float tEntry[BvhNode::kWidth]) {
    if (count == 0) return intersectChildren(bvh.nodes[offset], r, best.t, tEntry);
    if (intersectLeaf<AnyHit>(bvh, scene, offset, count, r, ray, best)) found = true;
    return 0;
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
        Float tEntry[BvhNode::kWidth];
        const uint32_t mask =
            visitItem<AnyHit>(bvh, scene, ray, r, offset, count, best, found, tEntry);
        if (AnyHit && found) return true;
        if (mask != 0) {
            const BvhNode& node = bvh.nodes[offset];
            // Farther children wait on the stack, the nearest is visited now.
            const int k = orderChildren<AnyHit>(mask, tEntry, [&](int far) {
                stack[sp++] = Entry{node.offset[far], node.count[far], tEntry[far]};
            });
            offset = node.offset[k];
            count = node.count[k];
            continue;
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

/// (parent node << kBvhSlotBits) | slot of node `index` (kBvhNoParent for the root):
/// bvh.parents[index], or, for a view without parent links, found by descending from the root. That
/// relies on the depth-first node order: every subtree occupies a contiguous index range starting
/// at its root, so the subtree holding `index` is the inner child with the largest offset <= index.
/// It costs one node fetch per level, and keeps the backtracking traversals free of any stack.
CA_HD_INLINE uint32_t parentLink(const BvhView& bvh, uint32_t index) {
    if (!bvh.parents.empty()) return bvh.parents[index];
    uint32_t node = 0;
    while (index != 0) {
        const BvhNode& n = bvh.nodes[node];
        int slot = -1;
        uint32_t child = 0;
        for (int k = 0; k < BvhNode::kWidth; ++k)
            if (!n.isEmpty(k) && !n.isLeaf(k) && n.offset[k] <= index &&
                (slot < 0 || n.offset[k] > child)) {
                slot = k;
                child = n.offset[k];
            }
        if (slot < 0) break;  // not a node of this tree
        if (child == index) return (node << kBvhSlotBits) | uint32_t(slot);
        node = child;
    }
    return kBvhNoParent;
}

/// Short-stack / stackless traversal (StackSize = 0), same contract as traverse(). Visits the same
/// children in the same order as traverse(): the children of a node are taken in ascending (entry
/// distance, slot) order, a strict total order that does not depend on the search limit, so a node
/// can be re-entered after child slot k and continue exactly with the children that follow k
/// (those culled meanwhile only ever had entry distances beyond the current limit). Needs no
/// per-node data beyond the default layout; bvh.parents (built by default) makes each step up one
/// memory access instead of a descent from the root (parentLink). The stack is a ring buffer of
/// StackSize entries: a push onto a full stack overwrites the oldest (shallowest) entry, which is
/// also the one that would have been popped last. When the stack runs empty after such a loss, the
/// traversal goes back to the parent of the item it processed last and continues there after that
/// item's slot, going up further through the parent links while a node has no child left.
// GCC 12 cannot see that a stack entry is read only after it was written (`held` guards every
// read) and warns about a 1-entry stack; nvcc's front end does not take this pragma.
#if defined(__GNUC__) && !defined(__clang__) && !defined(__CUDACC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
template <bool AnyHit, int StackSize>
CA_HD bool traverseShortStack(const BvhView& bvh, const SceneView& scene, const Ray& ray,
                              Hit& best) {
    static_assert(StackSize >= 0 && (StackSize & (StackSize - 1)) == 0,
                  "the short stack holds 0 or a power of two entries");
    if (bvh.nodes.empty()) return false;
    const TraversalRay r(ray);
    struct Entry {
        uint32_t offset, count;
        Float tNear;
        uint32_t link;  // (parent node << kBvhSlotBits) | slot of this child
    };
    Entry stack[StackSize > 0 ? StackSize : 1];
    uint32_t top = 0;   // entries pushed minus popped; stack[(top - 1) % StackSize] is the top
    int held = 0;       // entries actually held (<= StackSize)
    bool lost = false;  // some entry was overwritten (or, stackless, never stored)
    uint32_t offset = 0, count = 0;  // the item being processed: start at the root node
    uint32_t link = kBvhNoParent;    // (parent << kBvhSlotBits) | slot of the item processed last
    int after = -1;                  // >= 0: node `offset` is re-entered after child slot `after`
    bool found = false;
    for (;;) {
        Float tEntry[BvhNode::kWidth];
        uint32_t mask = visitItem<AnyHit>(bvh, scene, ray, r, offset, count, best, found, tEntry);
        if (AnyHit && found) return true;
        if (after >= 0) {  // only ever set for an inner node
            // Re-entered: keep only the children that come after slot `after`.
            for (int k = 0; k < BvhNode::kWidth; ++k)
                if (!followsInOrder<AnyHit>(k, after, tEntry)) mask &= ~(1u << k);
            after = -1;
        }
        if (mask != 0) {
            const BvhNode& node = bvh.nodes[offset];
            const int k = orderChildren<AnyHit>(mask, tEntry, [&](int far) {
                if constexpr (StackSize > 0) {
                    stack[top++ % StackSize] = Entry{node.offset[far], node.count[far], tEntry[far],
                                                     (offset << kBvhSlotBits) | uint32_t(far)};
                    if (held < StackSize)
                        ++held;
                    else
                        lost = true;
                } else {
                    lost = true;
                }
            });
            link = (offset << kBvhSlotBits) | uint32_t(k);
            count = node.count[k];
            offset = node.offset[k];
            continue;
        }
        // Pop the next subtree that may still hold a closer hit; culled entries count as done.
        bool popped = false;
        if constexpr (StackSize > 0) {
            while (held > 0) {
                const Entry& e = stack[--top % StackSize];
                --held;
                link = e.link;
                if (AnyHit || e.tNear <= best.t) {
                    offset = e.offset;
                    count = e.count;
                    popped = true;
                    break;
                }
            }
        }
        if (popped) continue;
        if (!lost || link == kBvhNoParent) return found;
        // Backtrack: continue in the parent of the last item, after that item's slot.
        offset = link >> kBvhSlotBits;
        after = int(link & ((1u << kBvhSlotBits) - 1));
        count = 0;
        link = parentLink(bvh, offset);
    }
}
#if defined(__GNUC__) && !defined(__clang__) && !defined(__CUDACC__)
#pragma GCC diagnostic pop
#endif

}  // namespace bvh_detail

/// Traversal algorithm of BvhIntersectorT, bvhIntersect and bvhOccluded. All give identical
/// results (same hits, same t, same primitive on ties); they differ in speed and in memory per ray.
enum class BvhTraversal {
    Stack,       // full stack of kBvhStackSize entries (the default)
    ShortStack,  // ring buffer of ShortStackSize entries + backtracking through Bvh::parents
    Stackless,   // no stack: backtracking through Bvh::parents only (with either, a view
                 // without parent links finds parents by descending from the root: slow)
};

namespace bvh_detail {
template <BvhTraversal Traversal, int ShortStackSize, bool AnyHit>
CA_HD_INLINE bool traverseWith(const BvhView& bvh, const SceneView& scene, const Ray& ray,
                               Hit& best) {
    if constexpr (Traversal == BvhTraversal::Stack) {
        return traverse<AnyHit>(bvh, scene, ray, best);
    } else {
        constexpr int size = Traversal == BvhTraversal::Stackless ? 0 : ShortStackSize;
        return traverseShortStack<AnyHit, size>(bvh, scene, ray, best);
    }
}
}  // namespace bvh_detail

/// Closest hit of `ray` with t in (0, ray.tMax). On a hit, fills `hit` (t, primId, b1, b2) and
/// returns true; otherwise leaves `hit` unchanged. The parallelograms outside the tree
/// (BvhView::quads) are tested first, as Embree's intersector does: the nearest one's t becomes
/// the traversal's limit, so the tree yields a primitive only if it is nearer.
template <BvhTraversal Traversal = BvhTraversal::Stack, int ShortStackSize = kBvhShortStackSize>
CA_HD_INLINE bool bvhIntersect(const BvhView& bvh, const SceneView& scene, const Ray& ray,
                               Hit& hit) {
    Hit best;
    best.t = ray.tMax;
    bool found = false;
    for (size_t i = 0; i < bvh.quads.size(); ++i) {
        Float t, u, v;
        if (intersectParallelogram<Float>(ray.o, ray.d, best.t, bvh.quads[i], t, u, v)) {
            best = parallelogramHit(bvh.quads[i], t, u, v);
            found = true;
        }
    }
    if (bvh_detail::traverseWith<Traversal, ShortStackSize, false>(bvh, scene, ray, best)) found = true;
    if (!found) return false;
    hit = best;
    return true;
}

/// True if anything is hit with t in (0, ray.tMax) (shadow rays).
template <BvhTraversal Traversal = BvhTraversal::Stack, int ShortStackSize = kBvhShortStackSize>
CA_HD_INLINE bool bvhOccluded(const BvhView& bvh, const SceneView& scene, const Ray& ray) {
    for (size_t i = 0; i < bvh.quads.size(); ++i) {
        Float t, u, v;
        if (intersectParallelogram<Float>(ray.o, ray.d, ray.tMax, bvh.quads[i], t, u, v)) return true;
    }
    Hit best;
    best.t = ray.tMax;
    return bvh_detail::traverseWith<Traversal, ShortStackSize, true>(bvh, scene, ray, best);
}

}  // namespace caustica
