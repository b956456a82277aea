// multi_hash.h — the multi-level hash table of seed 004 (Zhdanov et al. 2023): a kd-tree that
// halves space into geometrically equal halves (a spatial median, not the points' median), with a
// regular grid laid over each chosen node and stored as a hash table, so that empty cells take no
// memory. Here the chosen nodes are the tree's leaves: a node is halved while it holds more than
// `leafPoints` points, so leaves sit at many levels, small where photons crowd into a caustic and
// large where they are sparse, and each leaf picks the cell size of its own grid from its own
// density (multi_hash_build.h: chooseLeafLevel). The grids of all leaves are cubes of one Morton
// lattice (2^16 cells per axis over the points' cube) at the leaf's level, so the tree and the
// cells are prefixes of the points' Morton codes. Queries walk the tree (integer boxes and the
// largest radius per node prune it), then the cells of the leaves they reach (grid_walk.h).
#pragma once

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "caustica/parallel/buffer.h"
#include "caustica/parallel/launch.h"
#include "caustica/parallel/primitives.h"
#include "caustica/spatial/cell_sort.h"
#include "caustica/spatial/grid_walk.h"
#include "caustica/spatial/hash_grid.h"
#include "caustica/spatial/multi_hash_build.h"
#include "caustica/spatial/point_extent.h"
#include "caustica/spatial/point_set.h"
#include "caustica/util/error.h"

namespace caustica {

/// The build's rule (docs/PHOTON_LOOKUP.md measures alternatives).
struct MultiHashOptions {
    uint32_t leafPoints = 4096;  // a node with more points is halved (at most 48 times)
    Float pointsPerCell = 16;    // Density: a leaf's cells are the coarsest holding at most this many on average
    MultiHashCellRule cellRule = MultiHashCellRule::Density;
};

/// A query's stack: a walk pops a node and pushes at most its two children, and the tree is at
/// most 48 levels deep, so 49 entries suffice.
inline constexpr int kMultiHashStackSize = 64;

struct MultiHashView;

/// One leaf's grid as grid_walk.h sees it: cells of 2^shift lattice cells, clamped to the
/// cells its points occupy; the first and last cell of each axis take everything beyond.
struct MultiHashLeafGrid {
    const MultiHashView* view;
    MultiHashLeaf leaf;
    PointSet points;

    CA_HD int32_t cellOnAxis(int axis, Float v) const;
    CA_HD int32_t firstCell(int axis) const { return leaf.cellLo[axis]; }
    CA_HD int32_t lastCell(int axis) const { return leaf.cellHi[axis]; }
    CA_HD Float cellLower(int axis, int32_t c) const;
    CA_HD Float cellUpper(int axis, int32_t c) const;
    CA_HD Float cellSize() const;
    template <class Test, class Report>
    CA_HD void forEachInRow(int32_t x0, int32_t x1, int32_t y, int32_t z, Test&& test,
                            Report&& report) const;
    /// report(i) for every point i of the leaf with test(i), once each.
    template <class Test, class Report>
    CA_HD void forEachPoint(Test&& test, Report&& report) const;
};

/// What kernels query.
struct MultiHashView : BallQueries<MultiHashView> {
    PointSet points;
    MortonLattice lattice;
    Span<const MultiHashNode> nodes;   // depth-first; nodes[0] is the root
    Span<const MultiHashLeaf> leaves;
    CellLists cells;                   // points grouped by bucket; a leaf's buckets are contiguous
    Float maxRadius = 0;               // the largest radius of the points
    Float coordinateScale = 0;         // largest |coordinate| of the points' cube (slack)

    /// A point's cell in a leaf's grid: its lattice coordinates >> shift.
    CA_HD CellCoord cellOf(Vec3f p, uint32_t shift) const {
        return {int32_t(lattice.quantize(0, p.x) >> shift), int32_t(lattice.quantize(1, p.y) >> shift),
                int32_t(lattice.quantize(2, p.z) >> shift)};
    }
    CA_HD MultiHashLeafGrid leafGrid(uint32_t leaf) const { return {this, leaves[leaf], points}; }

    /// The tree walk of the ball queries: nodes whose integer box overlaps the integer box of
    /// center +- reach (spheres: the node's largest radius when smaller), then in each leaf the
    /// cells of that box, or every point of the leaf when the box has more cells than buckets.
    template <bool kSpheres, class F>
    CA_HD void visit(Vec3f center, Float reach, Float radius, F& f) const {
        if (nodes.empty()) return;
        uint32_t qlo[3] = {0, 0, 0}, qhi[3] = {0, 0, 0};
        Float boxReach = -1;  // the reach of the box in qlo, qhi (none yet)
        auto setBox = [&](Float r) {
            const Float w = conservativeReach(r);
            for (int a = 0; a < 3; ++a) {
                qlo[a] = lattice.quantize(a, center[a] - w);
                qhi[a] = lattice.quantize(a, center[a] + w);
            }
            boxReach = r;
        };
        auto accepts = [&](uint32_t i) { return acceptsPoint<kSpheres>(points, i, center, radius); };
        uint32_t stack[kMultiHashStackSize];
        int top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const uint32_t t = stack[--top];
            const MultiHashNode& node = nodes[t];
            const Float r = kSpheres ? min(reach, node.maxRadius) : reach;
            if (r != boxReach) setBox(r);
            if (!overlaps(node, qlo, qhi)) continue;
            if (!node.isLeaf) {
                stack[top++] = node.child;
                stack[top++] = t + 1;
                continue;
            }
            const MultiHashLeafGrid g = leafGrid(node.child);
            int32_t c0[3], c1[3];
            for (int a = 0; a < 3; ++a) {
                c0[a] = max(int32_t(qlo[a] >> g.leaf.shift), g.leaf.cellLo[a]);
                c1[a] = min(int32_t(qhi[a] >> g.leaf.shift), g.leaf.cellHi[a]);
            }
            forEachInCellBox(g, CellCoord{c0[0], c0[1], c0[2]}, CellCoord{c1[0], c1[1], c1[2]},
                             Float(g.leaf.bucketMask) + 1, accepts, f);
        }
    }

    /// Nodes whose box, widened by segmentReach of their largest radius, the segment crosses;
    /// in each leaf the cells along the segment (grid_walk.h), or every point of the leaf when
    /// the walk would visit more cells than the leaf has buckets.
    template <class F>
    CA_HD void visitSegment(const Segment& s, F& f) const {
        if (nodes.empty()) return;
        walkSegmentTree<kMultiHashStackSize>(s, [&](SegmentEntry e, auto&& push) {
            const MultiHashNode& node = nodes[e.node];
            const Float reach = segmentReach(s, node.maxRadius, coordinateScale);
            Vec3f lo, hi;
            worldBox(node, lo, hi);
            for (int a = 0; a < 3; ++a)
                if (!s.clip(a, lo[a] - reach, hi[a] + reach, e.t0, e.t1)) return;
            if (!node.isLeaf) {
                push(SegmentEntry{node.child, e.t0, e.t1});
                push(SegmentEntry{e.node + 1, e.t0, e.t1});
                return;
            }
            const MultiHashLeafGrid g = leafGrid(node.child);
            forEachSphereAlongWalkOrScan(g, s, reach, lo, hi, Float(g.leaf.bucketMask) + 1, f);
        });
    }

    /// Nearest child first; a node is skipped when a lower bound of the squared distances to
    /// its box (made conservative for the rounding of the lattice) exceeds the heap's limit. In
    /// a leaf, rings of cells outward (grid_walk.h), or every point of the leaf when the cells
    /// within the heap's limit outnumber twice its buckets.
    CA_HD void searchNearest(Vec3f center, NearestHeap& heap) const {
        if (nodes.empty()) return;
        walkNearest<kMultiHashStackSize>(heap, [&](NearestEntry e, auto&& push) {
            const MultiHashNode& node = nodes[e.node];
            if (node.isLeaf) {
                nearestInLeaf(node.child, center, heap);
                return;
            }
            NearestEntry near{e.node + 1, boxBound(nodes[e.node + 1], center)};
            NearestEntry far{node.child, boxBound(nodes[node.child], center)};
            if (far.bound < near.bound) {
                const NearestEntry swap = near;
                near = far;
                far = swap;
            }
            push(far);
            push(near);
        });
    }

private:
    CA_HD static bool overlaps(const MultiHashNode& n, const uint32_t* qlo, const uint32_t* qhi) {
        return n.qlo[0] <= qhi[0] && qlo[0] <= n.qhi[0] && n.qlo[1] <= qhi[1] && qlo[1] <= n.qhi[1] &&
               n.qlo[2] <= qhi[2] && qlo[2] <= n.qhi[2];
    }
    /// The nominal world box of a node's lattice cells.
    CA_HD void worldBox(const MultiHashNode& n, Vec3f& lo, Vec3f& hi) const {
        for (int a = 0; a < 3; ++a) {
            lo[a] = lattice.lower(a, n.qlo[a]);
            hi[a] = lattice.lower(a, n.qhi[a] + 1);
        }
    }
    /// A lower bound of |p - center|^2 in float for every point p of node n: the gaps to its
    /// nominal box, shrunk by kSegmentSlack of the coordinates' magnitude (a point's lattice
    /// cell is computed with rounding) and by kRingSlack (the rounding of the squares).
    CA_HD Float boxBound(const MultiHashNode& n, Vec3f center) const {
        Vec3f lo, hi;
        worldBox(n, lo, hi);
        const Float slack = kSegmentSlack * (maxAbs(center) + coordinateScale);
        Float d2 = 0;
        for (int a = 0; a < 3; ++a) {
            const Float gap = max(max(lo[a] - center[a], center[a] - hi[a]) - slack, Float(0));
            d2 += gap * gap;
        }
        return d2 * (1 - kRingSlack);
    }
    CA_HD void nearestInLeaf(uint32_t leaf, Vec3f center, NearestHeap& heap) const {
        const MultiHashLeafGrid g = leafGrid(leaf);
        const Float reach = conservativeReach(std::sqrt(heap.limit()));
        Float cellCount = 1;
        int32_t extent = 0;
        for (int a = 0; a < 3; ++a) {
            cellCount *= Float(g.cellOnAxis(a, center[a] + reach)) - Float(g.cellOnAxis(a, center[a] - reach)) + 1;
            extent = max(extent, g.leaf.cellHi[a] - g.leaf.cellLo[a]);
        }
        if (cellCount > 2 * (Float(g.leaf.bucketMask) + 1)) {
            g.forEachPoint([](uint32_t) { return true; },
                           [&](uint32_t i) { heap.consider(i, points.positions[i], center); });
            return;
        }
        // Rings up to the leaf's extent cover all its cells: the search never gives up.
        searchRings(g, center, extent, g.cellSize(), coordinateScale, heap);
    }
};

CA_HD inline int32_t MultiHashLeafGrid::cellOnAxis(int axis, Float v) const {
    const int32_t c = int32_t(view->lattice.quantize(axis, v) >> leaf.shift);
    return min(max(c, leaf.cellLo[axis]), leaf.cellHi[axis]);
}
CA_HD inline Float MultiHashLeafGrid::cellLower(int axis, int32_t c) const {
    return c <= leaf.cellLo[axis] ? -kUnbounded : view->lattice.lower(axis, uint32_t(c) << leaf.shift);
}
CA_HD inline Float MultiHashLeafGrid::cellUpper(int axis, int32_t c) const {
    return c >= leaf.cellHi[axis] ? kUnbounded : view->lattice.lower(axis, uint32_t(c + 1) << leaf.shift);
}
CA_HD inline Float MultiHashLeafGrid::cellSize() const {
    return view->lattice.cellWidth * Float(uint32_t(1) << leaf.shift);
}
template <class Test, class Report>
CA_HD void MultiHashLeafGrid::forEachInRow(int32_t x0, int32_t x1, int32_t y, int32_t z, Test&& test,
                                           Report&& report) const {
    const CellLists& cells = view->cells;
    for (int32_t x = x0; x <= x1; ++x) {
        const CellCoord cell{x, y, z};
        const uint32_t b = leaf.bucketOffset + (hashCell(cell) & leaf.bucketMask);
        for (uint32_t k = cells.cellStart[b]; k < cells.cellStart[b + 1]; ++k) {
            const uint32_t i = cells.order[k];
            if (test(i) && view->cellOf(points.positions[i], leaf.shift) == cell) report(i);
        }
    }
}
template <class Test, class Report>
CA_HD void MultiHashLeafGrid::forEachPoint(Test&& test, Report&& report) const {
    const CellLists& cells = view->cells;
    const uint32_t end = cells.cellStart[leaf.bucketOffset + leaf.bucketMask + 1];
    for (uint32_t k = cells.cellStart[leaf.bucketOffset]; k < end; ++k)
        if (test(cells.order[k])) report(cells.order[k]);
}

namespace spatial_detail {

/// codes[i] = Morton code of point i's lattice cell, order[i] = i.
template <class Exec>
void writeMortonCodes(Exec exec, const PointSet& points, MortonLattice lattice, uint64_t* codes,
                      uint32_t* order) {
    const Vec3f* positions = points.positions.data();
    launch(
        exec, "spatial.multihash_codes", points.size(),
        [=] CA_HD(size_t i) {
            const Vec3f p = positions[i];
            codes[i] = mortonCode48(lattice.quantize(0, p.x), lattice.quantize(1, p.y), lattice.quantize(2, p.z));
            order[i] = uint32_t(i);
        },
        256);
}

/// keys[k] = the global bucket of the k-th point in Morton order: its leaf (a binary search
/// over the leaves' first positions) and the hash of its cell in the leaf's grid.
template <class Exec>
void writeBucketKeys(Exec exec, size_t n, MultiHashView view, const uint32_t* order, const uint32_t* leafStarts,
                     uint32_t leafCount, uint32_t* keys) {
    launch(
        exec, "spatial.multihash_keys", n,
        [=] CA_HD(size_t k) {
            uint32_t lo = 0, hi = leafCount - 1;  // the last leaf whose first position is <= k
            while (lo < hi) {
                const uint32_t mid = (lo + hi + 1) / 2;
                if (leafStarts[mid] <= k)
                    lo = mid;
                else
                    hi = mid - 1;
            }
            const MultiHashLeaf leaf = view.leaves[lo];
            const CellCoord cell = view.cellOf(view.points.positions[order[k]], leaf.shift);
            keys[k] = leaf.bucketOffset + (hashCell(cell) & leaf.bucketMask);
        },
        256);
}

}  // namespace spatial_detail

/// A multi-level hash table over a PointSet (see point_set.h for the interface). Build: the
/// points' cube, Morton codes and one radix sort of them; the tree over the sorted codes on the
/// host (MultiHashTopology: about 2n / leafPoints nodes); each leaf's level (measureLeaves); a
/// radix sort of the points by bucket. Memory: 4 bytes per point, 4 per bucket (2 x the occupied
/// cells, rounded up to powers of two per leaf), 36 per node and 44 per leaf.
class MultiHash {
public:
    template <class Exec>
    static MultiHash build(Exec exec, const PointSet& points, MultiHashOptions options = {}) {
        using namespace spatial_detail;
        const size_t n = points.size();
        if (n >= (uint64_t(1) << 31)) throw Error("spatial: a multi-level hash table holds at most 2^31 points");
        if (!(options.pointsPerCell > 0)) throw Error("spatial: pointsPerCell must be > 0");
        const Device device = Exec::device();
        MultiHash m;
        m.options_ = options;
        const Bounds3f box = pointBounds(exec, points.positions);
        MortonLattice lattice;
        Float scale = 0;
        if (!box.empty()) {
            lattice.lo = box.lo;
            const Float side = maxComponent(box.diagonal());
            lattice.scale = side > 0 && side <= kInfinity ? Float(1u << kLatticeBits) / side : Float(0);
            lattice.cellWidth = lattice.scale > 0 ? side / Float(1u << kLatticeBits) : Float(0);
            scale = max(maxAbs(box.lo), maxAbs(box.hi));
            if (!(scale <= kInfinity)) scale = kUnbounded;  // infinite or NaN: no pruning of segments
        }
        MultiHashView& v = m.view_;
        v.points = points;
        v.lattice = lattice;
        v.maxRadius = maxRadius(exec, points);
        v.coordinateScale = scale;
        m.order_ = Buffer<uint32_t>(device, n);
        if (n == 0) return m;

        // Morton order, then the tree (host) over the sorted codes.
        Buffer<uint64_t> codes(device, n);
        writeMortonCodes(exec, points, lattice, codes.data(), m.order_.data());
        radixSortPairs(device, codes.span(), m.order_.span(), kMortonBits);
        const std::vector<uint64_t> hostCodes = codes.toHost();
        MultiHashTopology topology(hostCodes, options.leafPoints);

        // Per leaf: box, radius, level (device); then buckets and records (host).
        Buffer<MultiHashLeafStats> statsBuffer(device, topology.leaves.size());
        measureLeaves(exec, points, lattice, codes.data(), m.order_.data(), topology.leaves, options.cellRule,
                      options.pointsPerCell, statsBuffer.data());
        const std::vector<MultiHashLeafStats> stats = statsBuffer.toHost();
        topology.fillBoxes(stats);
        std::vector<MultiHashLeaf> leaves(stats.size());
        std::vector<uint32_t> leafStarts(stats.size());
        uint64_t buckets = 0;
        for (size_t l = 0; l < stats.size(); ++l) {
            MultiHashLeaf& leaf = leaves[l];
            const uint32_t count = std::bit_ceil(2 * stats[l].occupied);
            leaf.bucketOffset = uint32_t(buckets);
            leaf.bucketMask = count - 1;
            leaf.shift = uint32_t(kLatticeBits) - stats[l].level;
            leaf.depth = topology.leaves[l].depth;
            for (int a = 0; a < 3; ++a) {
                leaf.cellLo[a] = int32_t(stats[l].qlo[a] >> leaf.shift);
                leaf.cellHi[a] = int32_t(stats[l].qhi[a] >> leaf.shift);
            }
            leafStarts[l] = topology.leaves[l].start;
            buckets += count;
        }
        if (buckets >= UINT32_MAX) throw Error("spatial: the multi-level hash table needs too many buckets");
        m.nodes_ = Buffer<MultiHashNode>(device, topology.nodes);
        m.leaves_ = Buffer<MultiHashLeaf>(device, leaves);
        v.nodes = m.nodes_.constSpan();
        v.leaves = m.leaves_.constSpan();

        // Points grouped by bucket: a stable sort of the Morton order by global bucket.
        const Buffer<uint32_t> starts(device, leafStarts);
        Buffer<uint32_t> keys(device, n);
        writeBucketKeys(exec, n, v, m.order_.data(), starts.data(), uint32_t(leafStarts.size()), keys.data());
        radixSortPairs(device, keys.span(), m.order_.span(), keyBitsFor(buckets));
        m.cellStart_ = Buffer<uint32_t>(device, size_t(buckets) + 1);
        findCellStarts(exec, keys.data(), n, uint32_t(buckets), m.cellStart_.data());
        v.cells = CellLists{m.order_.constSpan(), m.cellStart_.constSpan()};
        return m;
    }

    MultiHashView view() const { return view_; }
    /// Device memory held: order, bucket starts, nodes and leaves (the PointSet not counted).
    size_t memoryBytes() const {
        return (order_.size() + cellStart_.size()) * sizeof(uint32_t) + nodes_.size() * sizeof(MultiHashNode) +
               leaves_.size() * sizeof(MultiHashLeaf);
    }
    size_t nodeCount() const { return nodes_.size(); }
    size_t leafCount() const { return leaves_.size(); }
    size_t bucketCount() const { return cellStart_.size() > 0 ? cellStart_.size() - 1 : 0; }
    const MultiHashOptions& options() const { return options_; }

private:
    MultiHashView view_;
    MultiHashOptions options_;
    Buffer<uint32_t> order_, cellStart_;
    Buffer<MultiHashNode> nodes_;
    Buffer<MultiHashLeaf> leaves_;
};

}  // namespace caustica
