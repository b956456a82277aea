// multi_hash_test.cpp — the multi-level hash table itself (the queries are compared with brute
// force in the shared query tests): every point sits in exactly one leaf, in its own cell's
// bucket; leaves hold at most leafPoints points; nodes bound their points and radii; each leaf's
// level follows the documented rule; a clustered set gets grids at several levels; memory is
// what memoryBytes() says; the build is the same on 1 and 2 threads; the leaves' statistics do
// not depend on the chunks measureLeaves cuts them into.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

#include "spatial/spatial_test_points.h"

namespace caustica::test {
namespace {

/// A caustic in a room: `dense` points within 0.01 of (0.3, 0.05, 0.4) and `sparse` points
/// uniform in the unit cube.
std::vector<Vec3f> causticInARoom(size_t dense, size_t sparse, uint64_t seed) {
    std::vector<Vec3f> p = clusteredPoints(dense, seed, Vec3f(0.3f, 0.05f, 0.4f), 0.01f);
    const std::vector<Vec3f> room = randomPoints(sparse, seed + 1);
    p.insert(p.end(), room.begin(), room.end());
    return p;
}

/// For every leaf: the indices of its points (from its buckets).
std::vector<std::vector<uint32_t>> leafPoints(const MultiHash& m) {
    const MultiHashView v = m.view();
    std::vector<std::vector<uint32_t>> out(v.leaves.size());
    for (size_t l = 0; l < v.leaves.size(); ++l)
        v.leafGrid(uint32_t(l)).forEachPoint([](uint32_t) { return true; },
                                             [&](uint32_t i) { out[l].push_back(i); });
    return out;
}

/// Cells the points occupy at a level (cells of 2^(16 - level) lattice cells).
size_t occupiedCells(const MultiHashView& v, const std::vector<Vec3f>& points,
                     const std::vector<uint32_t>& indices, uint32_t level) {
    std::set<std::tuple<int32_t, int32_t, int32_t>> cells;
    for (uint32_t i : indices) {
        const CellCoord c = v.cellOf(points[i], uint32_t(kLatticeBits) - level);
        cells.insert({c.x, c.y, c.z});
    }
    return cells.size();
}

/// Checks the structure's invariants for `points` (radii optional) built with `options`.
void expectValidMultiHash(const std::vector<Vec3f>& points, const std::vector<Float>& radii,
                          MultiHashOptions options) {
    const DevicePoints dev(points, 0.01f, radii);
    const MultiHash m = MultiHash::build(CpuExec{}, dev.set(), options);
    const MultiHashView v = m.view();
    const auto leaves = leafPoints(m);
    std::vector<int> seen(points.size(), 0);
    for (size_t l = 0; l < leaves.size(); ++l) {
        const MultiHashLeaf& leaf = v.leaves[l];
        ASSERT_FALSE(leaves[l].empty()) << "leaf " << l;
        const uint32_t level = uint32_t(kLatticeBits) - leaf.shift;
        if (level < uint32_t(kLatticeBits)) {  // at the finest level a leaf may hold any number
            EXPECT_LE(leaves[l].size(), options.leafPoints) << "leaf " << l;
        }
        // Each point is in the bucket of its own cell, inside the leaf's cell box.
        for (uint32_t i : leaves[l]) {
            ASSERT_LT(i, points.size());
            ++seen[i];
            const CellCoord c = v.cellOf(points[i], leaf.shift);
            for (int a = 0; a < 3; ++a) {
                EXPECT_GE(c[a], leaf.cellLo[a]);
                EXPECT_LE(c[a], leaf.cellHi[a]);
            }
            bool inBucket = false;
            v.leafGrid(uint32_t(l)).forEachInRow(c.x, c.x, c.y, c.z, [](uint32_t) { return true; },
                                                  [&](uint32_t j) { inBucket = inBucket || j == i; });
            EXPECT_TRUE(inBucket) << "point " << i << " not found in its cell";
        }
        // The rule, recomputed here from its definition.
        const uint32_t first = (leaf.depth + 2) / 3;
        EXPECT_GE(level, first);
        uint32_t density = kLatticeBits;
        for (uint32_t j = kLatticeBits; j-- > first;)
            if (Float(leaves[l].size()) <= options.pointsPerCell * Float(occupiedCells(v, points, leaves[l], j)))
                density = j;
        Float largest = 0;
        for (uint32_t i : leaves[l]) largest = std::max(largest, radii.empty() ? 0.01f : radii[i]);
        uint32_t radius = first;
        while (radius < uint32_t(kLatticeBits) &&
               v.lattice.cellWidth * Float(1u << (kLatticeBits - radius - 1)) >= 2 * largest)
            ++radius;
        const uint32_t expected = options.cellRule == MultiHashCellRule::Density  ? density
                                  : options.cellRule == MultiHashCellRule::Radius ? radius
                                                                                  : std::min(density, radius);
        EXPECT_EQ(level, expected) << "leaf " << l << " density " << density << " radius " << radius;
    }
    for (int s : seen) ASSERT_EQ(s, 1);
    // Nodes bound their points and radii; leaves are reached once.
    std::vector<int> leafSeen(v.leaves.size(), 0);
    for (size_t t = 0; t < v.nodes.size(); ++t) {
        const MultiHashNode& node = v.nodes[t];
        std::vector<uint32_t> below;
        if (node.isLeaf) {
            ++leafSeen[node.child];
            below = leaves[node.child];
        } else {
            ASSERT_GT(node.child, t + 1);
            ASSERT_LT(node.child, v.nodes.size());
        }
        for (uint32_t i : below) {
            for (int a = 0; a < 3; ++a) {
                const uint32_t q = v.lattice.quantize(a, points[i][a]);
                EXPECT_GE(q, node.qlo[a]);
                EXPECT_LE(q, node.qhi[a]);
            }
            EXPECT_LE(radii.empty() ? 0.01f : radii[i], node.maxRadius);
        }
        if (!node.isLeaf) {
            for (const uint32_t c : {uint32_t(t + 1), node.child}) {
                for (int a = 0; a < 3; ++a) {
                    EXPECT_LE(node.qlo[a], v.nodes[c].qlo[a]);
                    EXPECT_GE(node.qhi[a], v.nodes[c].qhi[a]);
                }
                EXPECT_LE(v.nodes[c].maxRadius, node.maxRadius);
            }
        }
    }
    for (int s : leafSeen) EXPECT_EQ(s, 1);
    EXPECT_EQ(m.memoryBytes(), 4 * points.size() + 4 * (m.bucketCount() + 1) +
                                   sizeof(MultiHashNode) * m.nodeCount() + sizeof(MultiHashLeaf) * m.leafCount());
}

TEST(MultiHashTest, InvariantsOnRandomClusteredAndDegenerateSets) {
    const auto room = causticInARoom(4000, 2000, 3);
    const auto radii = randomRadii(room.size(), 4, 0.f, 0.02f);
    for (const MultiHashOptions options :
         {MultiHashOptions{16, 1}, MultiHashOptions{64, 4}, MultiHashOptions{},
          MultiHashOptions{64, 4, MultiHashCellRule::Radius}, MultiHashOptions{64, 16, MultiHashCellRule::Coarser}}) {
        expectValidMultiHash(randomPoints(3000, 1), {}, options);
        expectValidMultiHash(room, radii, options);
        expectValidMultiHash(latticePoints(12, 0.25f), {}, options);
        expectValidMultiHash(std::vector<Vec3f>(300, Vec3f(0.5f)), {}, options);  // all identical
        expectValidMultiHash({Vec3f(1, 2, 3)}, {}, options);
    }
}

TEST(MultiHashTest, ACausticGetsFinerGridsThanTheRoom) {
    // The point of the structure: one hash grid has one cell size; here the leaves in the caustic
    // have cells at least 8x smaller than those of the room around it.
    const auto points = causticInARoom(20000, 20000, 5);
    const DevicePoints dev(points, 0.01f);
    const MultiHash m = MultiHash::build(CpuExec{}, dev.set(), MultiHashOptions{1024, 4});
    const MultiHashView v = m.view();
    uint32_t finestShift = 32, coarsestShift = 0;
    for (const MultiHashLeaf& leaf : v.leaves) {
        finestShift = std::min(finestShift, leaf.shift);
        coarsestShift = std::max(coarsestShift, leaf.shift);
    }
    EXPECT_GE(coarsestShift, finestShift + 3);
    EXPECT_GT(m.leafCount(), 16u);
    // Memory: far below the kd-tree's 16 bytes per point.
    EXPECT_LT(double(m.memoryBytes()) / double(points.size()), 12.0);
}

TEST(MultiHashTest, RefusesBadOptions) {
    const DevicePoints dev(randomPoints(10, 1), 0.01f);
    EXPECT_THROW(MultiHash::build(CpuExec{}, dev.set(), MultiHashOptions{16, 0}), Error);
}

TEST(MultiHashTest, SameStructureOnOneAndTwoThreads) {
    const auto points = causticInARoom(30000, 30000, 7);
    const DevicePoints dev(points, 0.01f);
    auto layout = [&](int threads) {
        std::vector<uint32_t> out;
        tbb::task_arena arena(threads);
        arena.execute([&] {
            const MultiHash m = MultiHash::build(CpuExec{}, dev.set(), MultiHashOptions{512, 2});
            const MultiHashView v = m.view();
            out.assign(v.cells.order.begin(), v.cells.order.end());
            out.insert(out.end(), v.cells.cellStart.begin(), v.cells.cellStart.end());
            for (const MultiHashNode& n : v.nodes) {
                out.insert(out.end(), {n.qlo[0], n.qlo[1], n.qlo[2], n.qhi[0], n.qhi[1], n.qhi[2], n.child, n.isLeaf});
            }
            for (const MultiHashLeaf& l : v.leaves) out.insert(out.end(), {l.bucketOffset, l.bucketMask, l.shift});
        });
        return out;
    };
    EXPECT_EQ(layout(1), layout(2));
}

using spatial_detail::MultiHashLeafStats;

/// measureLeaves' statistics for one leaf as one serial pass over its points (the kernel before it
/// was cut into chunks): the box, the largest radius and the level by the documented rule.
MultiHashLeafStats leafStatsInOnePass(const PointSet& points, const MortonLattice& lattice,
                                      const std::vector<uint64_t>& codes, const std::vector<uint32_t>& order,
                                      const spatial_detail::MultiHashLeafRange& range, MultiHashCellRule rule,
                                      Float pointsPerCell) {
    MultiHashLeafStats s;
    for (int a = 0; a < 3; ++a) s.qlo[a] = kLatticeMax;
    uint32_t newCells[kLatticeBits + 1] = {};
    for (uint32_t k = range.start; k < range.end; ++k) {
        for (int a = 0; a < 3; ++a) {
            const uint32_t q = lattice.quantize(a, points.positions[order[k]][a]);
            s.qlo[a] = std::min(s.qlo[a], q);
            s.qhi[a] = std::max(s.qhi[a], q);
        }
        s.maxRadius = std::max(s.maxRadius, points.radiusOf(order[k]));
        if (k == range.start) continue;
        uint32_t j = 0;
        while (j <= uint32_t(kLatticeBits) &&
               (codes[k] >> (kMortonBits - 3 * j)) == (codes[k - 1] >> (kMortonBits - 3 * j)))
            ++j;
        if (j <= uint32_t(kLatticeBits)) ++newCells[j];
    }
    uint32_t occupiedAt[kLatticeBits + 1];
    uint32_t occupied = 1;
    for (int j = 0; j <= kLatticeBits; ++j) occupiedAt[j] = occupied += newCells[j];
    s.level = spatial_detail::chooseLeafLevel(rule, range.end - range.start, range.depth, pointsPerCell, occupiedAt,
                                              s.maxRadius, lattice.cellWidth);
    s.occupied = occupiedAt[s.level];
    return s;
}

TEST(MultiHashTest, LeafStatisticsDoNotDependOnTheChunkSize) {
    // measureLeaves cuts each leaf into chunks of points (one work item each) and merges them per
    // leaf: every chunk size must give what one pass over each leaf gives, field for field.
    std::vector<Vec3f> points = causticInARoom(6000, 3000, 11);
    points.insert(points.end(), 200, Vec3f(0.7f, 0.7f, 0.7f));  // a leaf's worth of equal codes
    const std::vector<Float> radii = randomRadii(points.size(), 12, 0.f, 0.03f);
    const DevicePoints dev(points, 0.01f, radii);
    const PointSet set = dev.set();
    MortonLattice lattice;
    Bounds3f box;
    for (const Vec3f& p : points) box.extend(p);
    const Float side = maxComponent(box.diagonal());
    lattice.lo = box.lo;
    lattice.scale = Float(1u << kLatticeBits) / side;
    lattice.cellWidth = side / Float(1u << kLatticeBits);
    std::vector<uint32_t> order(points.size());
    std::vector<uint64_t> keyOf(points.size());
    for (uint32_t i = 0; i < points.size(); ++i) {
        order[i] = i;
        keyOf[i] = mortonCode48(lattice.quantize(0, points[i].x), lattice.quantize(1, points[i].y),
                                lattice.quantize(2, points[i].z));
    }
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return keyOf[a] < keyOf[b]; });
    std::vector<uint64_t> codes(points.size());
    for (size_t k = 0; k < order.size(); ++k) codes[k] = keyOf[order[k]];
    const spatial_detail::MultiHashTopology topology(codes, 700);  // leaves of up to 700 points
    ASSERT_GT(topology.leaves.size(), 8u);
    for (const MultiHashCellRule rule : {MultiHashCellRule::Density, MultiHashCellRule::Radius}) {
        for (const uint32_t chunk : {1u, 3u, 128u, 700u, 1u << 20}) {
            std::vector<MultiHashLeafStats> stats(topology.leaves.size());
            spatial_detail::measureLeaves(CpuExec{}, set, lattice, codes.data(), order.data(), topology.leaves, rule,
                                          4.f, stats.data(), chunk);
            for (size_t l = 0; l < stats.size(); ++l) {
                const MultiHashLeafStats want =
                    leafStatsInOnePass(set, lattice, codes, order, topology.leaves[l], rule, 4.f);
                const MultiHashLeafStats& got = stats[l];
                SCOPED_TRACE(::testing::Message() << "chunk " << chunk << ", leaf " << l);
                for (int a = 0; a < 3; ++a) {
                    EXPECT_EQ(got.qlo[a], want.qlo[a]);
                    EXPECT_EQ(got.qhi[a], want.qhi[a]);
                }
                EXPECT_EQ(got.maxRadius, want.maxRadius);
                EXPECT_EQ(got.level, want.level);
                EXPECT_EQ(got.occupied, want.occupied);
            }
        }
    }
}

TEST(MultiHashTest, LeafChunksCoverEachLeafOnce) {
    const std::vector<spatial_detail::MultiHashLeafRange> leaves = {{0, 5, 3}, {5, 6, 4}, {6, 300, 2}};
    std::vector<spatial_detail::MultiHashChunk> chunks;
    std::vector<uint32_t> first;
    spatial_detail::leafChunks(leaves, 128, chunks, first);
    ASSERT_EQ(first, (std::vector<uint32_t>{0, 1, 2, 5}));
    uint32_t next = 0;
    for (size_t l = 0; l < leaves.size(); ++l)
        for (uint32_t c = first[l]; c < first[l + 1]; ++c) {
            EXPECT_EQ(chunks[c].start, next);
            EXPECT_EQ(chunks[c].leafStart, leaves[l].start);
            EXPECT_LE(chunks[c].end - chunks[c].start, 128u);
            EXPECT_GT(chunks[c].end, chunks[c].start);
            next = chunks[c].end;
        }
    EXPECT_EQ(next, 300u);
}

}  // namespace
}  // namespace caustica::test
