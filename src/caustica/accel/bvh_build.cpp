// bvh_build.cpp — binned-SAH BVH construction on the host (see bvh.h).
//
// Top-down: each node bins its primitives' centroids on all three axes, evaluates the surface area
// heuristic at every bin boundary and partitions in place (Wald, IEEE RT 2007). Large subtrees are
// built as parallel TBB tasks; every decision depends only on the primitives of the subtree, and the
// tree is flattened afterwards in one depth-first pass (sibling pairs, see BvhNode), so the result
// does not depend on how tasks were scheduled.
#include <algorithm>
#include <chrono>
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
          maxLeafSize_(std::clamp(options.maxLeafSize, 1, int(BvhNode::kCountMask))),
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
            const float leafCost = intersectionCost_ * float(n);
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
    float binScale(const Bounds3f& cb, int axis) const {
        return float(binCount_) / (cb.hi[axis] - cb.lo[axis]);
    }
    int binIndex(float c, float lo, float scale) const {
        const float f = (c - lo) * scale;  // compare in float: no overflowing int conversion
        return f > 0 ? (f < float(binCount_ - 1) ? int(f) : binCount_ - 1) : 0;
    }

    /// Best SAH split over all axes; cost = A_left * N_left + A_right * N_right.
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
                rightCost[b] = count ? acc.surfaceArea() * float(count) : -1.0f;
            }
            acc = Bounds3f();
            count = 0;
            for (int b = 1; b < binCount_; ++b) {
                acc.extend(bins[b - 1]);
                count += counts[b - 1];
                if (count == 0 || rightCost[b] < 0) continue;
                const float cost = acc.surfaceArea() * float(count) + rightCost[b];
                if (cost < best.cost) best = Split{axis, b, cost};
            }
        }
        return best;
    }

    std::vector<PrimRef>& refs_;
    int binCount_, maxLeafSize_;
    float traversalCost_, intersectionCost_;
};

/// Flattening into sibling pairs (see BvhNode): a pair is appended, then the subtree below its
/// first node, then the subtree below its second, recursively.
class Flattener {
public:
    Flattener(Bvh& bvh, const BvhBuildOptions& options, float rootArea)
        : bvh_(bvh), options_(options), invRootArea_(rootArea > 0 ? 1.0 / rootArea : 0.0) {}

    void emitRoot(const BuildNode& root) {
        bvh_.nodes.emplace_back();
        if (root.count == 0) bvh_.nodes.emplace_back();  // padding: pairs start at even indices
        emit(root, 0, 0);
    }

private:
    /// Fills node `index` (already allocated) from `b` and emits its subtree.
    void emit(const BuildNode& b, uint32_t index, uint32_t depth) {
        BvhStats& s = bvh_.stats;
        ++s.nodeCount;
        s.maxDepth = std::max(s.maxDepth, depth);
        const double relArea = double(b.bounds.surfaceArea()) * invRootArea_;
        BvhNode& node = bvh_.nodes[index];
        node.lo = b.bounds.lo;
        node.hi = b.bounds.hi;
        if (b.count > 0) {
            node.offset = b.begin;
            node.countAxis = b.count;
            ++s.leafCount;
            s.sahCost += relArea * options_.intersectionCost * b.count;
            return;
        }
        s.sahCost += relArea * options_.traversalCost;
        const uint32_t pair = uint32_t(bvh_.nodes.size());
        node.offset = pair;
        node.countAxis = uint32_t(b.axis) << 30;
        bvh_.nodes.emplace_back();  // invalidates `node`
        bvh_.nodes.emplace_back();
        emit(*b.child[0], pair, depth + 1);
        emit(*b.child[1], pair + 1, depth + 1);
    }

    Bvh& bvh_;
    const BvhBuildOptions& options_;
    double invRootArea_;
};

}  // namespace

Bvh buildBvh(const Scene& scene, const BvhBuildOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    Bvh bvh;
    const uint32_t numPrims = scene.numPrimitives();
    if (numPrims > 0) {
        std::vector<PrimRef> refs(numPrims);
        tbb::parallel_for(uint32_t(0), numPrims, [&](uint32_t id) {
            refs[id].bounds = scene.primitiveBounds(id);
            refs[id].centroid = refs[id].bounds.center();
            refs[id].id = id;
        });
        std::unique_ptr<BuildNode> root = Builder(options, refs).build(0, numPrims, 0);

        bvh.nodes.reserve(2 * size_t(numPrims));
        Flattener(bvh, options, root->bounds.surfaceArea()).emitRoot(*root);
        bvh.nodes.shrink_to_fit();
        root.reset();

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
                    p.e1 = scene.positions[tri.y] - p.p0;
                    p.e2 = scene.positions[tri.z] - p.p0;
                } else {
                    const Sphere& sphere = scene.spheres[id - numTriangles];
                    p.p0 = sphere.center;
                    p.e1 = Vec3f(sphere.radius, 0, 0);
                }
            });
        }
    }
    BvhStats& s = bvh.stats;
    s.averageLeafSize = s.leafCount ? double(numPrims) / s.leafCount : 0.0;
    s.memoryBytes = bvh.nodes.size() * sizeof(BvhNode) + bvh.primIndices.size() * sizeof(uint32_t) +
                    bvh.prims.size() * sizeof(BvhPrimitive);
    s.buildMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return bvh;
}

}  // namespace caustica
