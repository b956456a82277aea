// bvh_build.cpp — binned-SAH BVH construction on the host (see bvh.h).
//
// Top-down: each node bins its primitives' centroids on all three axes, evaluates the surface area
// heuristic at every bin boundary and partitions in place (Wald, IEEE RT 2007). Large subtrees are
// built as parallel TBB tasks; every decision depends only on the primitives of the subtree, and
// the binary tree is collapsed afterwards into 8-wide nodes (see BvhNode) in one depth-first pass,
// so the result does not depend on how tasks were scheduled.
#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "caustica/accel/bvh.h"

namespace caustica {
namespace {

struct PrimRef {
    Bounds3f bounds;
    Vec3f centroid;
    uint32_t id = 0;
};

/// Temporary pointer tree; leaves reference ranges of the partitioned PrimRef array.
struct BuildNode {
    Bounds3f bounds;
    uint32_t begin = 0, count = 0;  // count > 0: leaf
    int axis = 0;
    std::unique_ptr<BuildNode> child[2];
};

constexpr uint32_t kParallelThreshold = 4096;  // subtrees larger than this become TBB tasks
constexpr int kMaxBins = 256;

struct Split {
    int axis = -1;
    int bin = 0;  // primitives whose centroid falls in bins [0, bin) go left
    float cost = kInfinity;
};

class Builder {
public:
    Builder(const BvhBuildOptions& options, std::vector<PrimRef>& refs)
        : refs_(refs), binCount_(std::clamp(options.binCount, 2, kMaxBins)),
          maxLeafSize_(std::clamp(options.maxLeafSize, 1, 1 << 24)),
          leafGroup_(uint32_t(std::clamp(options.leafGroup, 1, 64))),
          traversalCost_(options.traversalCost), intersectionCost_(options.intersectionCost) {}

    std::unique_ptr<BuildNode> build(uint32_t begin, uint32_t end, int depth) const {
        auto node = std::make_unique<BuildNode>();
        Bounds3f centroidBounds;
        for (uint32_t i = begin; i < end; ++i) {
            node->bounds.extend(refs_[i].bounds);
            centroidBounds.extend(refs_[i].centroid);
        }
        const uint32_t n = end - begin;
        auto makeLeaf = [&] {
            node->begin = begin;
            node->count = n;
            return std::move(node);
        };
        if (n == 1 || depth >= kBvhMaxDepth) return makeLeaf();

        const Split split = findSplit(begin, end, centroidBounds);
        uint32_t mid;
        if (split.axis < 0) {
            // All centroids coincide: SAH cannot separate them. Split by index if too many.
            if (n <= uint32_t(maxLeafSize_)) return makeLeaf();
            mid = begin + n / 2;
            node->axis = maxDimension(node->bounds.diagonal());
        } else {
            const float area = node->bounds.surfaceArea();
            const float leafCost = intersectionCost_ * groups(n);
            const float splitCost = traversalCost_ + intersectionCost_ * split.cost / area;
            if (n <= uint32_t(maxLeafSize_) && (!(area > 0) || leafCost <= splitCost))
                return makeLeaf();
            const float lo = centroidBounds.lo[split.axis];
            const float scale = binScale(centroidBounds, split.axis);
            PrimRef* first = refs_.data() + begin;
            PrimRef* middle = std::partition(first, refs_.data() + end, [&](const PrimRef& r) {
                return binIndex(r.centroid[split.axis], lo, scale) < split.bin;
            });
            mid = uint32_t(middle - refs_.data());
            node->axis = split.axis;
        }

        if (n > kParallelThreshold) {
            tbb::parallel_invoke([&] { node->child[0] = build(begin, mid, depth + 1); },
                                 [&] { node->child[1] = build(mid, end, depth + 1); });
        } else {
            node->child[0] = build(begin, mid, depth + 1);
            node->child[1] = build(mid, end, depth + 1);
        }
        return node;
    }

private:
    /// Leaf tests a leaf of n primitives costs: groups of leafGroup_ are tested at once.
    float groups(uint32_t n) const { return float((n + leafGroup_ - 1) / leafGroup_); }

    float binScale(const Bounds3f& cb, int axis) const {
        return float(binCount_) / (cb.hi[axis] - cb.lo[axis]);
    }
    int binIndex(float c, float lo, float scale) const {
        const float f = (c - lo) * scale;  // compare in float: no overflowing int conversion
        return f > 0 ? (f < float(binCount_ - 1) ? int(f) : binCount_ - 1) : 0;
    }

    /// Best SAH split over all axes; cost = A_left * G(N_left) + A_right * G(N_right), with G the
    /// leaf tests of N primitives (groups()).
    Split findSplit(uint32_t begin, uint32_t end, const Bounds3f& cb) const {
        Split best;
        for (int axis = 0; axis < 3; ++axis) {
            const float lo = cb.lo[axis], scale = binScale(cb, axis);
            if (!(cb.hi[axis] > lo) || !std::isfinite(scale)) continue;
            Bounds3f bins[kMaxBins];
            uint32_t counts[kMaxBins] = {};
            for (uint32_t i = begin; i < end; ++i) {
                const int b = binIndex(refs_[i].centroid[axis], lo, scale);
                bins[b].extend(refs_[i].bounds);
                ++counts[b];
            }
            // Sweep from the right, storing the cost of the right side of each boundary.
            float rightCost[kMaxBins];
            Bounds3f acc;
            uint32_t count = 0;
            for (int b = binCount_ - 1; b > 0; --b) {
                acc.extend(bins[b]);
                count += counts[b];
                rightCost[b] = count ? acc.surfaceArea() * groups(count) : -1.0f;
            }
            acc = Bounds3f();
            count = 0;
            for (int b = 1; b < binCount_; ++b) {
                acc.extend(bins[b - 1]);
                count += counts[b - 1];
                if (count == 0 || rightCost[b] < 0) continue;
                const float cost = acc.surfaceArea() * groups(count) + rightCost[b];
                if (cost < best.cost) best = Split{axis, b, cost};
            }
        }
        return best;
    }

    std::vector<PrimRef>& refs_;
    int binCount_, maxLeafSize_;
    uint32_t leafGroup_;
    float traversalCost_, intersectionCost_;
};

/// Collapses the binary tree into `width`-wide nodes (see BvhNode) in depth-first order and
/// gathers the statistics.
class Collapser {
public:
    Collapser(Bvh& bvh, const BvhBuildOptions& options, int width, float rootArea)
        : bvh_(bvh), options_(options), width_(width),
          invRootArea_(rootArea > 0 ? 1.0 / rootArea : 0.0) {}

    /// Emits the node whose children are those of `root` (or `root` itself if it is a leaf).
    void emitRoot(const BuildNode& root) {
        const BuildNode* only[1] = {&root};
        if (root.count > 0) {
            bvh_.stats.sahCost += options_.traversalCost;
            emit(only, 1, 1);
        } else {
            emitChildrenOf(root, 1);
        }
    }

private:
    /// Emits the node holding the children of binary node `b`, after pulling up grandchildren of
    /// the largest inner children until `width` slots are used. Returns the node's index.
    uint32_t emitChildrenOf(const BuildNode& b, uint32_t depth) {
        const BuildNode* children[BvhNode::kWidth] = {b.child[0].get(), b.child[1].get()};
        int n = 2;
        while (n < width_) {
            int open = -1;
            float openArea = -1;
            for (int k = 0; k < n; ++k) {
                const float area = children[k]->bounds.surfaceArea();
                if (children[k]->count == 0 && area > openArea) {
                    open = k;
                    openArea = area;
                }
            }
            if (open < 0) break;
            const BuildNode* opened = children[open];
            children[open] = opened->child[0].get();
            children[n++] = opened->child[1].get();
        }
        bvh_.stats.sahCost +=
            double(b.bounds.surfaceArea()) * invRootArea_ * options_.traversalCost;
        return emit(children, n, depth);
    }

    uint32_t emit(const BuildNode* const* children, int n, uint32_t depth) {
        BvhStats& s = bvh_.stats;
        ++s.nodeCount;
        s.maxDepth = std::max(s.maxDepth, depth);
        const uint32_t index = uint32_t(bvh_.nodes.size());
        bvh_.nodes.emplace_back();
        BvhNode node;
        const float nan = std::numeric_limits<float>::quiet_NaN();
        for (int k = 0; k < BvhNode::kWidth; ++k) {
            const Bounds3f b = k < n ? children[k]->bounds : Bounds3f();
            for (int axis = 0; axis < 3; ++axis) {
                node.lo[axis][k] = k < n ? b.lo[axis] : nan;  // empty slot: never hit
                node.hi[axis][k] = k < n ? b.hi[axis] : nan;
            }
            node.offset[k] = 0;
            node.count[k] = 0;
            if (k < n && children[k]->count > 0) {
                node.offset[k] = children[k]->begin;
                node.count[k] = children[k]->count;
                ++s.leafCount;
                s.sahCost += double(b.surfaceArea()) * invRootArea_ * options_.intersectionCost *
                             children[k]->count;
            }
        }
        // A traversal of this node pushes at most n - 1 siblings before descending into one child.
        uint32_t stack = 0;
        for (int k = 0; k < n; ++k) {
            if (children[k]->count > 0) continue;
            node.offset[k] = emitChildrenOf(*children[k], depth + 1);
            stack = std::max(stack, stackNeed_);
        }
        stackNeed_ = stack + uint32_t(n - 1);
        s.maxStack = std::max(s.maxStack, stackNeed_);
        bvh_.nodes[index] = node;
        return index;
    }

    Bvh& bvh_;
    const BvhBuildOptions& options_;
    int width_;
    double invRootArea_;
    uint32_t stackNeed_ = 0;  // stack bound of the subtree emitted last
};

}  // namespace

Bvh buildBvh(const Scene& scene, const BvhBuildOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    Bvh bvh;
    // The parallelograms tested as planes, and the primitives left for the tree.
    std::vector<uint32_t> treePrims;
    {
        const std::vector<PreparedParallelogram> quads = directParallelograms(scene, options.directParallelograms);
        std::vector<bool> direct(scene.triangles.size(), false);
        for (const PreparedParallelogram& q : quads) {
            bvh.quads.push_back(q);  // the plain plane, without the host's four-lane splat
            direct[q.mesh.first] = direct[q.mesh.second] = true;
        }
        treePrims.reserve(scene.numPrimitives());
        for (uint32_t id = 0; id < scene.numPrimitives(); ++id)
            if (id >= direct.size() || !direct[id]) treePrims.push_back(id);
    }
    const uint32_t numPrims = uint32_t(treePrims.size());
    if (numPrims > 0) {
        std::vector<PrimRef> refs(numPrims);
        tbb::parallel_for(uint32_t(0), numPrims, [&](uint32_t i) {
            const uint32_t id = treePrims[i];
            refs[i].bounds = scene.primitiveBounds(id);
            refs[i].centroid = refs[i].bounds.center();
            refs[i].id = id;
        });
        std::unique_ptr<BuildNode> root = Builder(options, refs).build(0, numPrims, 0);

        // A traversal needs at most (width - 1) stack entries per level; should a pathological
        // tree need more than kBvhStackSize, fall back to narrower nodes (binary: one entry per
        // level).
        const int width = std::clamp(options.width, 2, BvhNode::kWidth);
        for (int w : {width, std::min(width, 4), 2}) {
            bvh.nodes.clear();
            bvh.stats = BvhStats();
            bvh.stats.width = uint32_t(w);
            bvh.nodes.reserve(size_t(numPrims));
            Collapser(bvh, options, w, root->bounds.surfaceArea()).emitRoot(*root);
            if (bvh.stats.maxStack <= uint32_t(kBvhStackSize)) break;
        }
        bvh.nodes.shrink_to_fit();
        root.reset();

        // Links hold the node index in 32 - kBvhSlotBits bits; larger trees get none (their
        // backtracking traversals then find parents by descending from the root, see
        // bvh_traversal.h).
        if (options.parentLinks && bvh.nodes.size() < (size_t(1) << (32 - kBvhSlotBits))) {
            bvh.parents.assign(bvh.nodes.size(), kBvhNoParent);
            for (uint32_t i = 0; i < uint32_t(bvh.nodes.size()); ++i) {
                const BvhNode& node = bvh.nodes[i];
                for (int k = 0; k < BvhNode::kWidth; ++k)
                    if (!node.isEmpty(k) && !node.isLeaf(k))
                        bvh.parents[node.offset[k]] = (i << kBvhSlotBits) | uint32_t(k);
            }
        }

        bvh.primIndices.resize(numPrims);
        for (uint32_t i = 0; i < numPrims; ++i) bvh.primIndices[i] = refs[i].id;
        if (options.precomputePrimitives) {
            bvh.prims.resize(numPrims);
            const uint32_t numTriangles = uint32_t(scene.triangles.size());
            tbb::parallel_for(uint32_t(0), numPrims, [&](uint32_t i) {
                const uint32_t id = bvh.primIndices[i];
                BvhPrimitive& p = bvh.prims[i];
                p.primId = id;
                if (id < numTriangles) {
                    const Vec3u tri = scene.triangles[id];
                    p.p0 = scene.positions[tri.x];
                    p.p1 = scene.positions[tri.y];
                    p.p2 = scene.positions[tri.z];
                } else if (id < numTriangles + scene.spheres.size()) {
                    const Sphere& sphere = scene.spheres[id - numTriangles];
                    p.p0 = sphere.center;
                    p.p1 = Vec3f(sphere.radius, 0, 0);
                } else {
                    const Cylinder& c = scene.cylinders[id - numTriangles - scene.spheres.size()];
                    p.p0 = c.base;
                    p.p1 = c.axis;
                    p.p2 = Vec3f(c.radius, c.length, 0);
                }
            });
        }
    }
    BvhStats& s = bvh.stats;
    s.directParallelograms = uint32_t(bvh.quads.size());
    s.averageLeafSize = s.leafCount ? double(numPrims) / s.leafCount : 0.0;
    s.memoryBytes = bvh.nodes.size() * sizeof(BvhNode) + bvh.primIndices.size() * sizeof(uint32_t) +
                    bvh.prims.size() * sizeof(BvhPrimitive) + bvh.parents.size() * sizeof(uint32_t) +
                    bvh.quads.size() * sizeof(ParallelogramPlane);
    s.buildMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return bvh;
}

}  // namespace caustica
