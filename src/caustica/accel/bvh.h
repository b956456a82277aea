// bvh.h — the own bounding volume hierarchy: flat 8-wide node layout shared by CPU and GPU
// traversal, and the binned-SAH builder that runs on the host (bvh_build.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

#include "caustica/accel/parallelogram_intersect.h"
#include "caustica/scene/scene.h"
#include "caustica/util/math.h"
#include "caustica/util/span.h"

namespace caustica {

/// Deepest level of the binary SAH tree the builder creates (root = depth 0); deeper subtrees
/// become leaves.
inline constexpr int kBvhMaxDepth = 62;
/// Entries of the traversal stack. The builder guarantees that no traversal needs more (see
/// BvhBuildOptions::width).
inline constexpr int kBvhStackSize = 64;
/// Default entries of the short stack of BvhTraversal::ShortStack (see bvh_traversal.h).
inline constexpr int kBvhShortStackSize = 8;
/// Value of Bvh::parents[0]: the root has no parent.
inline constexpr uint32_t kBvhNoParent = ~0u;
/// Low bits of a parent link (Bvh::parents) that hold the child slot.
inline constexpr int kBvhSlotBits = 3;

/// One node of the 8-wide BVH: the boxes and links of up to eight children, 256 bytes (four cache
/// lines). Boxes are stored axis by axis (SoA), so the eight slab tests run as two 4-wide SSE
/// halves on the CPU (Float4, simd4.h), while the GPU runs them as scalar code. `hi` follows `lo`
/// directly, so a ray can address the near plane of an axis as lo or hi by one index
/// (bvh_traversal.h). Nodes are in depth-first order, nodes[0] is the root.
///
/// Child slot k is
///   a leaf          count[k] > 0: primitives primIndices[offset[k], offset[k] + count[k])
///   an inner node   count[k] = 0: its node is nodes[offset[k]]
///   empty           count[k] = 0 and a NaN box, which no ray hits (isEmpty; this relies on IEEE
///                   comparisons, so kernels must not be built with -ffast-math / --use_fast_math)
///
/// The binary SAH tree is collapsed into this layout by pulling up grandchildren, largest surface
/// area first (Wald, Benthin and Boulos, "Getting Rid of Packets: Efficient SIMD Single-Ray
/// Traversal using Multi-branching BVHs", IEEE RT 2008).
struct alignas(64) BvhNode {
    static constexpr int kWidth = 8;
    float lo[3][kWidth];  // lo[axis][child]
    float hi[3][kWidth];
    uint32_t offset[kWidth];  // leaf: first primitive; inner node: node index
    uint32_t count[kWidth];   // leaf: primitive count (> 0); inner node or empty slot: 0

    CA_HD bool isEmpty(int k) const { return !(lo[0][k] <= hi[0][k]); }
    CA_HD bool isLeaf(int k) const { return count[k] > 0; }
    CA_HD Bounds3f bounds(int k) const {
        return Bounds3f{Vec3f(lo[0][k], lo[1][k], lo[2][k]), Vec3f(hi[0][k], hi[1][k], hi[2][k])};
    }
};
static_assert(sizeof(BvhNode) == 256, "BvhNode must stay 256 bytes");
static_assert(offsetof(BvhNode, hi) == offsetof(BvhNode, lo) + sizeof(BvhNode::lo),
              "the traversal addresses lo and hi as one array");
static_assert((1 << kBvhSlotBits) >= BvhNode::kWidth, "parent links must hold any slot");

/// Primitive data in leaf order, precomputed for traversal so that a leaf test reads one contiguous
/// 40-byte record instead of an index and three scattered vertices. Triangle: the exact vertex
/// positions p0, p1, p2 (the watertight test needs them unrounded: a shared edge must be evaluated
/// from the same operands in both its triangles, primitive_intersect.h). Sphere: p0 = centre,
/// p1.x = radius. Cylinder: p0 = base, p1 = unit axis, p2 = (radius, length, 0).
struct BvhPrimitive {
    Vec3f p0;
    uint32_t primId = 0;  // = primIndices[i], kept here to save a memory access per primitive
    Vec3f p1, p2;
};

/// What kernels take: spans over the BVH arrays (device copies on the GPU). `prims` may be empty,
/// in which case leaves read the scene's triangles and spheres through primIndices.
struct BvhView {
    Span<const BvhNode> nodes;
    Span<const uint32_t> primIndices;  // leaf order -> primitive id (triangles first, then spheres)
    Span<const BvhPrimitive> prims;    // leaf order, parallel to primIndices; optional
    /// Parent links, parallel to nodes: (parent node << kBvhSlotBits) | child slot, kBvhNoParent
    /// for the root. Only the stackless and short-stack traversals read them; without them these
    /// find a node's parent by descending from the root (correct, but one node fetch per level).
    Span<const uint32_t> parents = {};
    /// Parallelogram meshes (rectangles) tested as planes before each traversal, their triangles
    /// left out of the tree (BvhBuildOptions::directParallelograms).
    Span<const ParallelogramPlane> quads = {};
};

/// Builder settings. Costs are the SAH constants of MacDonald and Booth, "Heuristics for Ray
/// Tracing Using Space Subdivision" (1990), relative to one primitive test; they steer the binary
/// tree that is then collapsed to `width` children per node.
struct BvhBuildOptions {
    int binCount = 32;                 // SAH bins per axis (Wald 2007), 2..256
    int maxLeafSize = 4;               // larger nodes are always split
    float traversalCost = 2.0f;        // cost of one binary node visit (two child box tests)
    float intersectionCost = 1.0f;     // cost of one leaf test of up to leafGroup primitives
    int leafGroup = 4;                 // primitives a leaf test handles at once (the host tests
                                       // four triangles with SSE, triangle4.h), 1..64
    int width = 8;                     // children per node, 2..8. A tree whose traversal could
                                       // overflow the stack is rebuilt narrower (never seen)
    bool precomputePrimitives = true;  // fill Bvh::prims (see BvhPrimitive)
    bool parentLinks = true;           // fill Bvh::parents (4 bytes per node; for the stackless
                                       // and short-stack traversals, see BvhTraversal)
    /// Parallelogram meshes (every rectangle shape, scene/parallelogram.h) tested as one plane each
    /// before the traversal instead of as two triangles in the tree, when the scene has at most
    /// this many (directParallelograms); 0: all stay triangles. The same test as Embree's
    /// intersector (EmbreeSceneOptions::directParallelograms): a box's walls are a few large
    /// triangles whose boxes overlap everything inside it. Fewer than Embree's 16: a ray here tests
    /// them one at a time (Embree's packets four rays at a time), and door-gap's 12 planes cost
    /// the CPU 8% more than its 24-triangle tree (docs/PERFORMANCE.md, 2026-12-01).
    uint32_t directParallelograms = 8;
};

/// Figures for `caustica info` and the tests.
struct BvhStats {
    uint32_t nodeCount = 0;  // nodes of up to `width` children each
    uint32_t leafCount = 0;
    uint32_t maxDepth = 0;       // nodes on the longest root-to-leaf path
    uint32_t width = 0;          // children per node used (see BvhBuildOptions::width)
    uint32_t directParallelograms = 0;  // parallelograms tested as planes, outside the tree
    uint32_t maxStack = 0;       // bound on the traversal stack entries this tree can need
    double averageLeafSize = 0;  // primitives per leaf
    double sahCost = 0;          // expected cost of a random ray hitting the root box: node
                                 // visits * traversalCost + primitive tests * intersectionCost
    size_t memoryBytes = 0;      // nodes + primIndices + prims + parents + quads
    double buildMilliseconds = 0;
};

/// std::allocator with a stronger alignment: nodes start on 128-byte boundaries (cache-line pairs,
/// which the adjacent-line prefetcher fetches together).
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
    bool operator==(const AlignedAllocator<U, Alignment>&) const {
        return true;
    }
};

/// A built BVH: host arrays plus its statistics.
struct Bvh {
    std::vector<BvhNode, AlignedAllocator<BvhNode, 128>> nodes;
    std::vector<uint32_t> primIndices;
    std::vector<BvhPrimitive> prims;
    std::vector<uint32_t> parents;  // see BvhView::parents; empty without options.parentLinks
    std::vector<ParallelogramPlane> quads;  // see BvhView::quads
    BvhStats stats;

    BvhView view() const {
        return BvhView{Span<const BvhNode>(nodes.data(), nodes.size()), primIndices, prims,
                       parents, quads};
    }
};

/// Builds a binned-SAH BVH over the primitives of `scene` (Wald, "On fast Construction of SAH-based
/// Bounding Volume Hierarchies", IEEE RT 2007), all but the triangles of the parallelograms it
/// tests as planes (Bvh::quads). Subtrees are built in parallel with TBB; the result is identical
/// for any thread count. A scene without other primitives gives a tree without nodes.
Bvh buildBvh(const Scene& scene, const BvhBuildOptions& options = {});

}  // namespace caustica
