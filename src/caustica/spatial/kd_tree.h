// kd_tree.h — a balanced, implicit kd-tree over a PointSet: the points reordered into one array
// in left-balanced order (Jensen's photon map, "Realistic Image Synthesis Using Photon Mapping",
// 2001, sec. 6.3): node t is a point, its children are nodes 2t + 1 and 2t + 2 when below n, so
// there are no pointers and the depth is bit_width(n) <= 32. Each node splits its subtree at its
// own coordinate along the longest side of its domain, an axis stored in 2 bits. Built level by
// level with a radix sort (kd_tree_build.h). Every query walks the tree with a fixed stack.
#pragma once

#include <cstddef>
#include <cstdint>

#include "caustica/parallel/buffer.h"
#include "caustica/spatial/kd_tree_build.h"
#include "caustica/spatial/point_extent.h"
#include "caustica/spatial/point_set.h"
#include "caustica/util/error.h"

namespace caustica {

/// Entries of a query's stack. A walk pops a node and pushes at most its two children, the
/// nearer last, so the stack holds at most one pending sibling per level below the root and
/// the top node: bit_width(n) <= 32 entries for n < 2^32 points.
inline constexpr int kKdStackSize = 32;

/// What kernels query. Node t's left subtree holds points with coordinate <= its own along
/// axisOf(t), the right subtree points with coordinate >= it (equal ones may be on either side).
struct KdTreeView : BallQueries<KdTreeView> {
    PointSet points;
    Span<const KdNode> nodes;        // left-balanced: node t's children are 2t + 1, 2t + 2
    Span<const uint32_t> axisWords;  // split axis of node t: 2 bits, word t / 16, bits 2 (t % 16)
    Float maxRadius = 0;             // the largest radius of the points
    Float coordinateScale = 0;       // largest |coordinate| of the points (segment slack)

    /// The split axis of node t (0, 1, 2 for x, y, z).
    CA_HD int axisOf(uint64_t t) const { return int(axisWords[t >> 4] >> (2 * (t & 15))) & 3; }

    /// Fixed-radius walk: the far child of a node is visited unless its split plane is farther
    /// than `reach` from center, tested as (c_k - split_k)^2 > reach^2 in float. That is exact,
    /// with no margin: |c_k - q_k| >= |c_k - split_k| for every q beyond the plane, rounding is
    /// monotone, so inBall's computed |q - c|^2 >= (c_k - split_k)^2 as computed; a point it
    /// accepts has |q - c|^2 <= radius^2 <= reach^2 (reach: the radius, or maxRadius).
    template <bool kSpheres, class F>
    CA_HD void visit(Vec3f center, Float reach, Float radius, F& f) const {
        const uint64_t n = nodes.size();
        if (n == 0) return;
        const Float reach2 = reach * reach;
        uint32_t stack[kKdStackSize];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const uint32_t t = stack[--top];
            const KdNode node = nodes[t];
            if (acceptsPosition<kSpheres>(points, node.index, node.position, center, radius))
                f(node.index);
            const uint64_t left = 2 * uint64_t(t) + 1;
            if (left >= n) continue;
            const int k = axisOf(t);
            const Float diff = center[k] - node.position[k];
            const uint64_t near = diff < 0 ? left : left + 1, far = diff < 0 ? left + 1 : left;
            if (far < n && !(diff * diff > reach2)) stack[top++] = uint32_t(far);
            if (near < n) stack[top++] = uint32_t(near);
        }
    }

    /// Segment walk: each stack entry carries the part [t0, t1] of the segment that can reach
    /// its subtree; a child gets the part whose coordinate along the split axis is on its side
    /// of the plane widened by segmentReach (the largest radius plus the rounding slack).
    template <class F>
    CA_HD void visitSegment(const Segment& s, F& f) const {
        const uint64_t n = nodes.size();
        if (n == 0) return;
        const Float reach = segmentReach(s, maxRadius, coordinateScale);
        walkSegmentTree<kKdStackSize>(s, [&](SegmentEntry e, auto&& push) {
            const KdNode node = nodes[e.node];
            if (sphereMeetsSegment(node.position, points.radiusOf(node.index), s)) f(node.index);
            const uint64_t left = 2 * uint64_t(e.node) + 1;
            if (left >= n) return;
            const int k = axisOf(e.node);
            const Float split = node.position[k];
            SegmentEntry l{uint32_t(left), e.t0, e.t1}, r{uint32_t(left + 1), e.t0, e.t1};
            bool goLeft = true, goRight = left + 1 < n;
            if (split == split) {  // a NaN coordinate orders nothing: both sides
                goLeft = s.clip(k, -kUnbounded, split + reach, l.t0, l.t1);
                goRight = goRight && s.clip(k, split - reach, kUnbounded, r.t0, r.t1);
            }
            if (goRight) push(r);
            if (goLeft) push(l);
        });
    }

    /// Bounded k-nearest search (Friedman, Bentley & Finkel 1977): nearer child first; a far
    /// child is pushed with a lower bound of the squared distances in it, max(parent's bound,
    /// (c_k - split_k)^2), exact for the same reason as visit's test, and skipped (when pushed
    /// and when popped) if that bound exceeds the heap's limit. A bound equal to the limit is
    /// still searched: a point at the k-th distance with a smaller index wins.
    CA_HD void searchNearest(Vec3f center, NearestHeap& heap) const {
        const uint64_t n = nodes.size();
        if (n == 0) return;
        walkNearest<kKdStackSize>(heap, [&](NearestEntry e, auto&& push) {
            const KdNode node = nodes[e.node];
            heap.consider(node.index, node.position, center);
            const uint64_t left = 2 * uint64_t(e.node) + 1;
            if (left >= n) return;
            const int k = axisOf(e.node);
            const Float diff = center[k] - node.position[k];
            const uint64_t near = diff < 0 ? left : left + 1, far = diff < 0 ? left + 1 : left;
            const Float farBound = max(e.bound, diff * diff);  // NaN: never pruned
            if (far < n) push(NearestEntry{uint32_t(far), farBound});
            if (near < n) push(NearestEntry{uint32_t(near), e.bound});
        });
    }
};

/// A kd-tree over a PointSet (see point_set.h for the interface). Build: bounding box, largest
/// radius, then per level a kernel choosing the axes, a key kernel, a radix sort and a placing
/// kernel (kd_tree_build.h). Memory: 16 bytes per node (position and index) and 2 bits of axis,
/// i.e. 16.25 bytes per point; build scratch about 29 bytes per point.
class KdTree {
public:
    template <class Exec>
    static KdTree build(Exec exec, const PointSet& points) {
        const size_t n = points.size();
        if (n >= (uint64_t(1) << 32))
            throw Error("spatial: a kd-tree holds at most 2^32 - 1 points");
        KdTree tree;
        const Bounds3f box = pointBounds(exec, points.positions);
        Float scale = box.empty() ? Float(0) : max(maxAbs(box.lo), maxAbs(box.hi));
        if (!(scale <= kInfinity)) scale = kUnbounded;  // infinite or NaN: no pruning of segments
        tree.nodes_ = Buffer<KdNode>(Exec::device(), n);
        tree.axisWords_ = Buffer<uint32_t>(Exec::device(), (n + 15) / 16);
        if (n > 0)
            spatial_detail::buildKdTree(exec, points.positions, box, tree.nodes_.data(),
                                        tree.axisWords_.data());
        tree.view_.points = points;
        tree.view_.nodes = tree.nodes_.constSpan();
        tree.view_.axisWords = tree.axisWords_.constSpan();
        tree.view_.maxRadius = maxRadius(exec, points);
        tree.view_.coordinateScale = scale;
        return tree;
    }

    KdTreeView view() const { return view_; }
    /// Device memory held: 16 bytes per point and 4 per 16 points (the PointSet not counted).
    size_t memoryBytes() const {
        return nodes_.size() * sizeof(KdNode) + axisWords_.size() * sizeof(uint32_t);
    }
    /// Levels of the tree: bit_width(n) (0 when empty), at most kKdStackSize.
    int depth() const { return int(std::bit_width(uint64_t(nodes_.size()))); }

private:
    KdTreeView view_;
    Buffer<KdNode> nodes_;
    Buffer<uint32_t> axisWords_;
};

}  // namespace caustica
