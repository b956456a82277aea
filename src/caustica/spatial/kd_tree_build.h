// kd_tree_build.h — the build of kd_tree.h: a left-balanced kd-tree (Jensen's photon map layout,
// node t's children at 2t + 1 and 2t + 2) made level by level of parallel/ primitives, as in
// Wald 2022 ("GPU-friendly, Parallel, and (Almost-)In-Place Construction of Left-Balanced k-d
// Trees", arXiv:2211.00120): every point carries the tag of the subtree it is in, one stable
// radix sort per level by (tag, coordinate along the subtree's split axis) puts each subtree's
// points in order, and the point at the subtree's left-balanced median becomes its root; the
// others move to the left or right child's subtree. A host loop over the levels launches the
// kernels through Exec, so the same text builds on the GPU. O(n log^2 n) work, deterministic.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "caustica/parallel/buffer.h"
#include "caustica/parallel/launch.h"
#include "caustica/parallel/primitives.h"
#include "caustica/spatial/point_set.h"

namespace caustica {

/// A node of the kd-tree: a point (a copy of its position, so that a query reads one 16-byte
/// record per node) and its index in the PointSet.
struct KdNode {
    Vec3f position;
    uint32_t index = 0;
};

namespace spatial_detail {

/// The bits of v ordered as the floats are: unsigned order = numeric order (-0 just before +0,
/// NaNs beyond the infinities), so a radix sort sorts coordinates.
CA_HD_INLINE uint32_t orderedBits(Float v) {
    uint32_t b;
    memcpy(&b, &v, sizeof b);
    return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
}

/// Nodes in the subtree of node c of a left-balanced tree of n nodes (levels full but the last,
/// which fills from the left): the part below n of each level's index range.
CA_HD_INLINE uint64_t kdSubtreeSize(uint64_t c, uint64_t n) {
    uint64_t size = 0;
    for (uint64_t first = c, last = c; first < n; first = 2 * first + 1, last = 2 * last + 2)
        size += (last < n ? last : n - 1) - first + 1;
    return size;
}

/// The split axis of every node t of `level`: the longest side of its domain, the points' box
/// clipped by the split planes of its ancestors (placed at upper levels, so `nodes` and `axes`
/// hold them).
template <class Exec>
void chooseKdAxes(Exec exec, int level, uint64_t n, Bounds3f root, const KdNode* nodes,
                  uint8_t* axes) {
    const uint64_t first = (uint64_t(1) << level) - 1, end = min(2 * first + 1, n);
    launch(
        exec, "spatial.kd_axes", size_t(end - first),
        [=] CA_HD(size_t j) {
            const uint64_t t = first + j;
            Bounds3f box = root;
            for (int d = 0; d < level; ++d) {  // the ancestor at depth d and its child on the path
                const uint64_t a = ((t + 1) >> (level - d)) - 1;
                const uint64_t child = ((t + 1) >> (level - d - 1)) - 1;
                const int k = axes[a];
                const Float split = nodes[a].position[k];
                if (child == 2 * a + 1)
                    box.hi[k] = min(box.hi[k], split);
                else
                    box.lo[k] = max(box.lo[k], split);
            }
            axes[t] = uint8_t(maxDimension(box.diagonal()));
        },
        64);
}

/// keys[k] = (tag, ordered coordinate of point order[k] along its subtree's axis) for the points
/// still in a subtree of `level` (tag >= first node of the level); placed ones keep (tag, 0).
template <class Exec>
void writeKdKeys(Exec exec, size_t n, uint64_t firstOfLevel, const Vec3f* positions,
                 const uint8_t* axes, const uint32_t* order, uint64_t* keys) {
    launch(
        exec, "spatial.kd_keys", n,
        [=] CA_HD(size_t k) {
            const uint64_t tag = keys[k] >> 32;
            if (tag >= firstOfLevel)
                keys[k] = (tag << 32) | orderedBits(positions[order[k]][axes[tag]]);
        },
        256);
}

/// After the sort: segmentStart[tag] = the first position of each tag's run of keys.
template <class Exec>
void findKdSegments(Exec exec, size_t n, const uint64_t* keys, uint32_t* segmentStart) {
    launch(
        exec, "spatial.kd_segments", n,
        [=] CA_HD(size_t k) {
            const uint64_t tag = keys[k] >> 32;
            if (k == 0 || (keys[k - 1] >> 32) != tag) segmentStart[tag] = uint32_t(k);
        },
        256);
}

/// The points of each subtree of `level`, sorted: the one at the left-balanced median (as many
/// before it as the left child's subtree holds) becomes node `tag`; those before it get the
/// left child's tag, those after it the right child's.
template <class Exec>
void placeKdLevel(Exec exec, size_t n, uint64_t firstOfLevel, const Vec3f* positions,
                  const uint32_t* order, const uint32_t* segmentStart, uint64_t* keys,
                  KdNode* nodes) {
    launch(
        exec, "spatial.kd_place", n,
        [=] CA_HD(size_t k) {
            const uint64_t tag = keys[k] >> 32;
            if (tag < firstOfLevel) return;
            const uint64_t local = k - segmentStart[tag];
            const uint64_t leftSize = kdSubtreeSize(2 * tag + 1, n);
            uint64_t next = tag;
            if (local < leftSize) {
                next = 2 * tag + 1;
            } else if (local > leftSize) {
                next = 2 * tag + 2;
            } else {
                nodes[tag] = KdNode{positions[order[k]], order[k]};
            }
            keys[k] = next << 32;
        },
        256);
}

/// axisWords[w] = the split axes of nodes 16 w .. 16 w + 15, 2 bits each (node 16 w lowest).
template <class Exec>
void packKdAxes(Exec exec, size_t n, const uint8_t* axes, uint32_t* axisWords) {
    launch(
        exec, "spatial.kd_pack_axes", (n + 15) / 16,
        [=] CA_HD(size_t w) {
            uint32_t word = 0;
            for (size_t j = 0; j < 16 && 16 * w + j < n; ++j)
                word |= uint32_t(axes[16 * w + j] & 3) << (2 * j);
            axisWords[w] = word;
        },
        256);
}

/// Builds the tree of n = positions.size() >= 1 points into nodes[n] and axisWords[(n + 15) / 16]
/// (memory of Exec's device). Scratch: 8 + 4 + 4 + 1 bytes per point and the sort's copy.
template <class Exec>
void buildKdTree(Exec exec, Span<const Vec3f> positions, const Bounds3f& box, KdNode* nodes,
                 uint32_t* axisWords) {
    const Device device = Exec::device();
    const size_t n = positions.size();
    Buffer<uint64_t> keys(device, n);
    Buffer<uint32_t> order(device, n), segmentStart(device, n);
    Buffer<uint8_t> axes(device, n);
    keys.zero();  // every point in the root's subtree, tag 0
    axes.zero();  // leaves keep axis 0 (never read)
    uint64_t* keyData = keys.data();
    uint32_t* orderData = order.data();
    launch(
        exec, "spatial.kd_identity", n, [=] CA_HD(size_t i) { orderData[i] = uint32_t(i); }, 256);
    const int depth = int(std::bit_width(uint64_t(n)));  // levels 0 .. depth - 1
    for (int level = 0; level < depth; ++level) {
        const uint64_t first = (uint64_t(1) << level) - 1;
        if (level + 1 < depth) {  // the last level's subtrees are single leaves: nothing to sort
            chooseKdAxes(exec, level, n, box, nodes, axes.data());
            writeKdKeys(exec, n, first, positions.data(), axes.data(), orderData, keyData);
            const int tagBits = min(level + 1, int(std::bit_width(uint64_t(n - 1))));
            radixSortPairs(device, keys.span(), order.span(), 32 + tagBits);
        }
        findKdSegments(exec, n, keyData, segmentStart.data());
        placeKdLevel(exec, n, first, positions.data(), orderData, segmentStart.data(), keyData,
                     nodes);
    }
    packKdAxes(exec, n, axes.data(), axisWords);
}

}  // namespace spatial_detail
}  // namespace caustica
