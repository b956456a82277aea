// multi_hash_build.h — the pieces of multi_hash.h's build: the Morton lattice over the points'
// cube, the spatial-median tree over the sorted codes (decided on the host: a few nodes per
// leafPoints points), the per-leaf statistics that choose each leaf's grid level (a kernel per
// leaf), and the records kernels read. The per-point work (codes, sorts, keys) runs through Exec.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "caustica/parallel/buffer.h"
#include "caustica/parallel/launch.h"
#include "caustica/spatial/point_set.h"

namespace caustica {

/// Bits per axis of the lattice: 2^16 cells along each side of the points' cube. The tree splits
/// at most 3 x 16 = 48 times; finer detail is left to a leaf's grid.
inline constexpr int kLatticeBits = 16;
inline constexpr uint32_t kLatticeMax = (1u << kLatticeBits) - 1;
inline constexpr int kMortonBits = 3 * kLatticeBits;

/// The lattice over the points' bounding cube: integer coordinates q in [0, 2^16) per axis.
/// quantize() is monotone in v (a subtraction, a product by a positive scale, a floor, a clamp),
/// so a point inside [c - r, c + r] has q inside [quantize(c - r), quantize(c + r)]: the ball
/// queries work on integer boxes and need no rounding margin beyond conservativeReach.
struct MortonLattice {
    Vec3f lo{0};
    Float scale = 0;      // lattice cells per unit length; 0 (a cube of side 0 or infinite): all in cell 0
    Float cellWidth = 0;  // the cube's side / 2^16 (nominal bounds only)

    CA_HD uint32_t quantize(int axis, Float v) const {
        const Float t = std::floor((v - lo[axis]) * scale);
        if (!(t > 0)) return 0;  // also NaN
        return t >= Float(kLatticeMax) ? kLatticeMax : uint32_t(t);
    }
    /// The nominal lower bound of lattice coordinate q (q = 2^16: the cube's upper side).
    CA_HD Float lower(int axis, uint32_t q) const { return lo[axis] + Float(q) * cellWidth; }
};

/// The 48-bit Morton code of lattice coordinates: bit 47 - d is the side of the split at depth
/// d, along axis d % 3 (x first). A node of the tree at depth d is a d-bit prefix.
CA_HD_INLINE uint64_t mortonCode48(uint32_t x, uint32_t y, uint32_t z) {
    auto spread = [](uint64_t v) {  // bit i of v to bit 3i
        v &= 0xffff;
        v = (v | v << 16) & 0x0000ff0000ffull;
        v = (v | v << 8) & 0x00f00f00f00full;
        v = (v | v << 4) & 0x0c30c30c30c3ull;
        v = (v | v << 2) & 0x249249249249ull;
        return v;
    };
    return spread(x) << 2 | spread(y) << 1 | spread(z);
}

/// A node of the tree as kernels read it: the integer box of its points (tight, in lattice
/// cells) and their largest radius. Nodes are in depth-first order: an internal node's left
/// child follows it, `child` is its right child; a leaf's `child` is its index in the leaves.
struct MultiHashNode {
    uint32_t qlo[3] = {0, 0, 0}, qhi[3] = {0, 0, 0};
    uint32_t child = 0;
    uint32_t isLeaf = 0;
    Float maxRadius = 0;
};

/// A leaf: a regular grid of cubic cells of 2^shift lattice cells over its points, stored as
/// its own hash table of buckets [bucketOffset, bucketOffset + bucketMask]. Its points are
/// order[cellStart[bucketOffset] .. cellStart[bucketOffset + bucketMask + 1]).
struct MultiHashLeaf {
    uint32_t bucketOffset = 0, bucketMask = 0;
    uint32_t shift = 0;                          // kLatticeBits - the grid's level
    uint32_t depth = 0;                          // of its node in the tree (its level >= ceil(depth / 3))
    int32_t cellLo[3] = {0, 0, 0}, cellHi[3] = {0, 0, 0};  // the cells its points occupy (box)
};

/// How a leaf chooses the cells of its grid (docs/PHOTON_LOOKUP.md measures them).
enum class MultiHashCellRule : uint32_t {
    Density,  // the coarsest level with at most pointsPerCell points per occupied cell
    Radius,   // the finest level with cells at least 2 x the leaf's largest radius (a hash grid per leaf)
    Coarser,  // the coarser of the two
};

namespace spatial_detail {

/// What the host decides per leaf: the range of the sorted points and the depth of its node.
struct MultiHashLeafRange {
    uint32_t start = 0, end = 0;
    uint32_t depth = 0;
};

/// What the leaf kernel measures: the integer box, the largest radius, the chosen level and
/// the cells its points occupy at that level.
struct MultiHashLeafStats {
    uint32_t qlo[3] = {0, 0, 0}, qhi[3] = {0, 0, 0};
    Float maxRadius = 0;
    uint32_t level = 0;
    uint32_t occupied = 1;
};

/// The grid level of a leaf (seed 004's "regular grids laid over chosen nodes"), never coarser
/// than the node itself (level >= ceil(depth / 3)). Density: the coarsest level at which its
/// points occupy cells holding at most `pointsPerCell` points on average (count / occupied
/// cells; occupiedAt[j] = cells occupied at level j, cells of 2^(16 - j) lattice cells); the
/// finest level when none does. Radius: the finest level whose cells are at least 2 x the
/// leaf's largest radius (latticeWidth: the width of a lattice cell). Coarser: the smaller level.
CA_HD_INLINE uint32_t chooseLeafLevel(MultiHashCellRule rule, uint32_t count, uint32_t depth, Float pointsPerCell,
                                      const uint32_t* occupiedAt, Float maxRadius, Float latticeWidth) {
    const uint32_t first = (depth + 2) / 3;
    uint32_t density = kLatticeBits;
    for (uint32_t j = first; j < uint32_t(kLatticeBits); ++j)
        if (Float(count) <= pointsPerCell * Float(occupiedAt[j])) {
            density = j;
            break;
        }
    if (rule == MultiHashCellRule::Density) return density;
    uint32_t radius = first;  // cells of level j are latticeWidth x 2^(16 - j) wide
    while (radius < uint32_t(kLatticeBits) &&
           latticeWidth * Float(uint32_t(1) << (kLatticeBits - radius - 1)) >= 2 * maxRadius)
        ++radius;
    return rule == MultiHashCellRule::Radius ? radius : min(radius, density);
}

/// Points per work item of measureLeaves: each leaf's range is cut into chunks of at most this
/// many points, each summarised by one work item, before a work item per leaf merges its chunks.
/// One work item per leaf walked up to MultiHashOptions::leafPoints (4096) points in one serial
/// loop: a GPU ran that as a few dozen long threads (3.5 ms an SPPM iteration on an H200,
/// docs/PERFORMANCE.md 2026-11-30); in chunks the same work spreads over thousands of threads.
inline constexpr uint32_t kLeafChunkPoints = 128;

/// A chunk of a leaf's range [start, end) of the Morton order; leafStart is the leaf's first point.
struct MultiHashChunk {
    uint32_t start = 0, end = 0, leafStart = 0;
};

/// What a chunk's points give their leaf: their integer box, largest radius, and how many of them
/// first differ from their predecessor in the leaf at each level (see measureLeaves).
struct MultiHashChunkStats {
    uint32_t qlo[3] = {kLatticeMax, kLatticeMax, kLatticeMax}, qhi[3] = {0, 0, 0};
    Float maxRadius = 0;
    uint32_t newCells[kLatticeBits + 1] = {};
};

/// The leaves' ranges cut into chunks of at most chunkPoints points, in leaf order: leaf l's
/// chunks are [firstChunk[l], firstChunk[l + 1]).
inline void leafChunks(const std::vector<MultiHashLeafRange>& leaves, uint32_t chunkPoints,
                       std::vector<MultiHashChunk>& chunks, std::vector<uint32_t>& firstChunk) {
    chunkPoints = chunkPoints < 1 ? 1 : chunkPoints;
    chunks.clear();
    firstChunk.assign(1, 0);
    for (const MultiHashLeafRange& leaf : leaves) {
        for (uint32_t start = leaf.start; start < leaf.end; start += min(chunkPoints, leaf.end - start))
            chunks.push_back(MultiHashChunk{start, start + min(chunkPoints, leaf.end - start), leaf.start});
        firstChunk.push_back(uint32_t(chunks.size()));
    }
}

/// Each leaf's box, largest radius and level, from one pass over its points in Morton order (two
/// neighbours differ at every level from the first at which their codes' prefixes differ, so the
/// occupied cells of all levels come from one histogram): a work item per chunk of the points
/// (leafChunks), then a work item per leaf merging its chunks. Minima, maxima and counts, so the
/// statistics do not depend on the chunk size (tests/spatial/multi_hash_test.cpp).
template <class Exec>
void measureLeaves(Exec exec, PointSet points, MortonLattice lattice, const uint64_t* codes,
                   const uint32_t* order, const std::vector<MultiHashLeafRange>& leafRanges,
                   MultiHashCellRule rule, Float pointsPerCell, MultiHashLeafStats* stats,
                   uint32_t chunkPoints = kLeafChunkPoints) {
    const Device device = Exec::device();
    std::vector<MultiHashChunk> hostChunks;
    std::vector<uint32_t> hostFirstChunk;
    leafChunks(leafRanges, chunkPoints, hostChunks, hostFirstChunk);
    // These buffers are freed when this returns, right after the launches: on a GPU the backend's
    // cudaFree waits for the device first (cuda/primitives_cuda.cu), as the caller's toHost would.
    const Buffer<MultiHashLeafRange> rangeBuffer(device, leafRanges);
    const Buffer<MultiHashChunk> chunkBuffer(device, hostChunks);
    const Buffer<uint32_t> firstChunkBuffer(device, hostFirstChunk);
    Buffer<MultiHashChunkStats> chunkStatsBuffer(device, hostChunks.size());
    const MultiHashLeafRange* ranges = rangeBuffer.data();
    const MultiHashChunk* chunks = chunkBuffer.data();
    const uint32_t* firstChunk = firstChunkBuffer.data();
    MultiHashChunkStats* chunkStats = chunkStatsBuffer.data();
    launch(
        exec, "spatial.multihash_chunks", hostChunks.size(),
        [=] CA_HD(size_t c) {
            const MultiHashChunk chunk = chunks[c];
            MultiHashChunkStats s;
            for (uint32_t k = chunk.start; k < chunk.end; ++k) {
                const uint32_t i = order[k];
                const Vec3f p = points.positions[i];
                for (int a = 0; a < 3; ++a) {
                    const uint32_t q = lattice.quantize(a, p[a]);
                    s.qlo[a] = min(s.qlo[a], q);
                    s.qhi[a] = max(s.qhi[a], q);
                }
                s.maxRadius = max(s.maxRadius, points.radiusOf(i));
                if (k == chunk.leafStart) continue;
                uint32_t j = 0;  // the first level whose cells tell point k from point k - 1
                while (j <= uint32_t(kLatticeBits) &&
                       (codes[k] >> (kMortonBits - 3 * j)) == (codes[k - 1] >> (kMortonBits - 3 * j)))
                    ++j;
                if (j <= uint32_t(kLatticeBits)) ++s.newCells[j];
            }
            chunkStats[c] = s;
        },
        16);
    launch(
        exec, "spatial.multihash_leaves", leafRanges.size(),
        [=] CA_HD(size_t l) {
            MultiHashLeafStats s;
            uint32_t newCells[kLatticeBits + 1] = {};
            for (int a = 0; a < 3; ++a) {
                s.qlo[a] = kLatticeMax;
                s.qhi[a] = 0;
            }
            for (uint32_t c = firstChunk[l]; c < firstChunk[l + 1]; ++c) {
                const MultiHashChunkStats& part = chunkStats[c];
                for (int a = 0; a < 3; ++a) {
                    s.qlo[a] = min(s.qlo[a], part.qlo[a]);
                    s.qhi[a] = max(s.qhi[a], part.qhi[a]);
                }
                s.maxRadius = max(s.maxRadius, part.maxRadius);
                for (int j = 0; j <= kLatticeBits; ++j) newCells[j] += part.newCells[j];
            }
            uint32_t occupiedAt[kLatticeBits + 1];
            uint32_t occupied = 1;
            for (int j = 0; j <= kLatticeBits; ++j) occupiedAt[j] = occupied += newCells[j];
            const MultiHashLeafRange range = ranges[l];
            s.level = chooseLeafLevel(rule, range.end - range.start, range.depth, pointsPerCell, occupiedAt,
                                      s.maxRadius, lattice.cellWidth);
            s.occupied = occupiedAt[s.level];
            stats[l] = s;
        },
        1);
}

/// The host part of the build: the spatial-median tree over the sorted Morton codes. A node
/// with more than leafPoints points (and a depth below 48) is halved at the middle of its box
/// along axis depth % 3; a half without points is dropped (the node is replaced by its other
/// half), so every internal node has two children and every leaf holds points.
class MultiHashTopology {
public:
    MultiHashTopology(const std::vector<uint64_t>& codes, uint32_t leafPoints)
        : codes_(codes), leafPoints_(leafPoints < 1 ? 1 : leafPoints) {
        if (!codes_.empty()) build(0, uint32_t(codes_.size()), 0);
    }
    std::vector<MultiHashNode> nodes;          // boxes and radii filled later (fillBoxes)
    std::vector<MultiHashLeafRange> leaves;    // in Morton order

    /// Fills every node's box and radius from its leaves' statistics (children after parents:
    /// a backward pass sees both children of a node before the node).
    void fillBoxes(const std::vector<MultiHashLeafStats>& stats) {
        for (size_t t = nodes.size(); t-- > 0;) {
            MultiHashNode& n = nodes[t];
            if (n.isLeaf) {
                const MultiHashLeafStats& s = stats[n.child];
                for (int a = 0; a < 3; ++a) {
                    n.qlo[a] = s.qlo[a];
                    n.qhi[a] = s.qhi[a];
                }
                n.maxRadius = s.maxRadius;
                continue;
            }
            const MultiHashNode &l = nodes[t + 1], &r = nodes[n.child];
            for (int a = 0; a < 3; ++a) {
                n.qlo[a] = min(l.qlo[a], r.qlo[a]);
                n.qhi[a] = max(l.qhi[a], r.qhi[a]);
            }
            n.maxRadius = max(l.maxRadius, r.maxRadius);
        }
    }

private:
    uint32_t build(uint32_t start, uint32_t end, uint32_t depth) {
        while (end - start > leafPoints_ && depth < uint32_t(kMortonBits)) {
            const uint32_t split = firstWithBit(start, end, kMortonBits - 1 - int(depth));
            ++depth;
            if (split == start || split == end) continue;  // one half is empty: halve the other
            const uint32_t self = uint32_t(nodes.size());
            nodes.push_back(MultiHashNode{});
            build(start, split, depth);
            const uint32_t right = build(split, end, depth);
            nodes[self].child = right;
            return self;
        }
        const uint32_t self = uint32_t(nodes.size());
        MultiHashNode leaf;
        leaf.isLeaf = 1;
        leaf.child = uint32_t(leaves.size());
        nodes.push_back(leaf);
        leaves.push_back(MultiHashLeafRange{start, end, depth});
        return self;
    }
    /// The first k in [start, end) whose code has `bit` set (they share the bits above it).
    uint32_t firstWithBit(uint32_t start, uint32_t end, int bit) const {
        while (start < end) {
            const uint32_t mid = start + (end - start) / 2;
            if ((codes_[mid] >> bit) & 1)
                end = mid;
            else
                start = mid + 1;
        }
        return start;
    }

    const std::vector<uint64_t>& codes_;
    uint32_t leafPoints_;
};

}  // namespace spatial_detail
}  // namespace caustica
