// bvh.h — the own bounding volume hierarchy: flat node layout shared by CPU and GPU traversal, and
// the binned-SAH builder that runs on the host (bvh_build.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

#include "caustica/scene/scene.h"
#include "caustica/util/math.h"
#include "caustica/util/span.h"

namespace caustica {

/// Deepest leaf the builder creates (root = depth 0). Traversal stacks hold at most one entry per
/// level, so kBvhStackSize > kBvhMaxDepth guarantees they never overflow.
inline constexpr int kBvhMaxDepth = 62;
inline constexpr int kBvhStackSize = 64;

/// One BVH node, 32 bytes. Siblings are stored side by side, so the two children of an interior
/// node fill one 64-byte cache line and traversal tests both boxes with a single line fetched:
///   nodes[0]            the root (nodes[1] is unused padding that aligns the pairs)
///   nodes[offset + 0/1] the children of an interior node; pairs are laid out in depth-first order
///                       (a pair, then the subtree of its first node, then that of its second)
/// A leaf's primitives are primIndices[offset, offset + count).
struct alignas(32) BvhNode {
    Vec3f lo;
    uint32_t offset = 0;     // interior: index of the first child (even); leaf: first primitive
    Vec3f hi;
    uint32_t countAxis = 0;  // bits 0-29: primitive count (0 = interior), bits 30-31: split axis

    static constexpr uint32_t kCountMask = (1u << 30) - 1;
    CA_HD bool isLeaf() const { return (countAxis & kCountMask) != 0; }
    CA_HD uint32_t primCount() const { return countAxis & kCountMask; }
    CA_HD int axis() const { return int(countAxis >> 30); }
};
static_assert(sizeof(BvhNode) == 32, "BvhNode must stay 32 bytes");

/// Primitive data in leaf order, precomputed for traversal so that a leaf test reads one contiguous
/// 40-byte record instead of an index and three scattered vertices. Triangle: p0 = vertex 0,
/// e1 = p1 - p0, e2 = p2 - p0 (the exact values intersectPrimitive computes, so results are
/// bit-identical). Sphere: p0 = centre, e1.x = radius.
struct BvhPrimitive {
    Vec3f p0;
    uint32_t primId = 0;  // = primIndices[i], kept here to save a memory access per primitive
    Vec3f e1, e2;
};

/// What kernels take: spans over the BVH arrays (device copies on the GPU). `prims` may be empty,
/// in which case leaves read the scene's triangles and spheres through primIndices.
struct BvhView {
    Span<const BvhNode> nodes;
    Span<const uint32_t> primIndices;   // leaf order -> primitive id (triangles first, then spheres)
    Span<const BvhPrimitive> prims;     // leaf order, parallel to primIndices; optional
};

/// Builder settings. Costs are the SAH constants of MacDonald and Booth, "Heuristics for Ray
/// Tracing Using Space Subdivision" (1990), relative to one primitive test.
struct BvhBuildOptions {
    int binCount = 32;                 // SAH bins per axis (Wald 2007), 2..256
    int maxLeafSize = 8;               // larger nodes are always split
    float traversalCost = 1.0f;        // cost of one node visit (two child box tests)
    float intersectionCost = 1.0f;     // cost of one primitive test
    bool precomputePrimitives = true;  // fill Bvh::prims (see BvhPrimitive)
};

/// Figures for `caustica info` and the tests.
struct BvhStats {
    uint32_t nodeCount = 0, leafCount = 0, maxDepth = 0;  // nodeCount excludes the padding node
    double averageLeafSize = 0;  // primitives per leaf
    double sahCost = 0;          // expected cost of a random ray hitting the root box
    size_t memoryBytes = 0;      // nodes + primIndices + prims
    double buildMilliseconds = 0;
};

/// std::allocator with a stronger alignment: node pairs start on 64-byte cache-line boundaries.
template <class T, size_t Alignment>
struct AlignedAllocator {
    using value_type = T;
    template <class U>
    struct rebind {
        using other = AlignedAllocator<U, Alignment>;
    };
    AlignedAllocator() = default;
    template <class U>
    AlignedAllocator(const AlignedAllocator<U, Alignment>&) {}
    T* allocate(size_t n) {
        return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(Alignment)));
    }
    void deallocate(T* p, size_t) { ::operator delete(p, std::align_val_t(Alignment)); }
    template <class U>
    bool operator==(const AlignedAllocator<U, Alignment>&) const { return true; }
};

/// A built BVH: host arrays plus its statistics.
struct Bvh {
    std::vector<BvhNode, AlignedAllocator<BvhNode, 64>> nodes;
    std::vector<uint32_t> primIndices;
    std::vector<BvhPrimitive> prims;
    BvhStats stats;

    BvhView view() const {
        return BvhView{Span<const BvhNode>(nodes.data(), nodes.size()), primIndices, prims};
    }
};

/// Builds a binned-SAH BVH over all primitives of `scene` (Wald, "On fast Construction of SAH-based
/// Bounding Volume Hierarchies", IEEE RT 2007). Subtrees are built in parallel with TBB; the result
/// is identical for any thread count. An empty scene gives an empty BVH (no nodes).
Bvh buildBvh(const Scene& scene, const BvhBuildOptions& options = {});

}  // namespace caustica
