// kd_tree_test.cpp — the kd-tree itself: every point is one node; every node separates its
// subtrees along its axis (left <= split <= right); the axis is its domain's longest side;
// memory is 16 bytes per point plus 2 bits; the depth fits the query stack; the build and the
// order of every query's results are the same on 1 and 2 threads (for the grids too).
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "spatial/spatial_test_points.h"

namespace caustica::test {
namespace {

/// Checks the layout of `tree` over `points`: a permutation, nodes carry their point's
/// position, and every node's subtrees lie on their side of its split plane.
void expectValidTree(const KdTree& tree, const std::vector<Vec3f>& points) {
    const KdTreeView view = tree.view();
    const size_t n = points.size();
    ASSERT_EQ(view.nodes.size(), n);
    std::vector<int> seen(n, 0);
    for (size_t t = 0; t < n; ++t) {
        const KdNode node = view.nodes[t];
        ASSERT_LT(node.index, n);
        ++seen[node.index];
        EXPECT_EQ(node.position, points[node.index]);
        EXPECT_LT(view.axisOf(t), 3);
    }
    for (int s : seen) ASSERT_EQ(s, 1);
    // Every node t against each of its ancestors a: on a's side of a's plane.
    for (size_t t = 1; t < n; ++t) {
        for (size_t child = t; child > 0; child = (child - 1) / 2) {
            const size_t a = (child - 1) / 2;
            const int k = view.axisOf(a);
            const Float split = view.nodes[a].position[k], v = view.nodes[t].position[k];
            if (child == 2 * a + 1) {
                ASSERT_LE(v, split) << "node " << t << " left of " << a;
            } else {
                ASSERT_GE(v, split) << "node " << t << " right of " << a;
            }
        }
    }
}

TEST(KdTreeTest, EveryNodeSeparatesItsSubtrees) {
    for (size_t n : {1, 2, 3, 7, 8, 100, 1000, 5000}) {
        const auto points = randomPoints(n, 91);
        const DevicePoints dev(points, 0.1f);
        expectValidTree(KdTree::build(CpuExec{}, dev.set()), points);
    }
    const auto lattice = latticePoints(9, 1.0f);  // many equal coordinates
    const DevicePoints dev(lattice, 0.5f);
    expectValidTree(KdTree::build(CpuExec{}, dev.set()), lattice);
    std::vector<Vec3f> same(333, Vec3f(1, 2, 3));  // all identical
    same.push_back(Vec3f(1, 2, 4));
    const DevicePoints sameDev(same, 0.f);
    expectValidTree(KdTree::build(CpuExec{}, sameDev.set()), same);
}

TEST(KdTreeTest, SplitsTheLongestSideOfTheDomain) {
    // A slab 100 x 1 x 0.01: the root splits x; its children's domains are still longest in x.
    std::vector<Vec3f> points = randomPoints(4000, 92);
    for (Vec3f& p : points) p = Vec3f(p.x * 100, p.y, p.z * 0.01f);
    const DevicePoints dev(points, 0.1f);
    const KdTree tree = KdTree::build(CpuExec{}, dev.set());
    expectValidTree(tree, points);
    EXPECT_EQ(tree.view().axisOf(0), 0);
    EXPECT_EQ(tree.view().axisOf(1), 0);
    EXPECT_EQ(tree.view().axisOf(2), 0);
    // The root is the median along x: 2047 nodes on its left (left-balanced, 4000 nodes).
    const Float split = tree.view().nodes[0].position.x;
    EXPECT_EQ(std::count_if(points.begin(), points.end(), [&](Vec3f p) { return p.x < split; }),
              2047);
}

TEST(KdTreeTest, MemoryIsSixteenBytesPerPointAndTwoBitsOfAxis) {
    for (size_t n : {0, 1, 2, 15, 16, 17, 1000, 4097}) {
        const DevicePoints dev(randomPoints(n, 93), 0.1f);
        const KdTree tree = KdTree::build(CpuExec{}, dev.set());
        EXPECT_EQ(tree.memoryBytes(), 16 * n + 4 * ((n + 15) / 16)) << n;
        EXPECT_EQ(tree.depth(), n == 0 ? 0 : int(std::bit_width(n))) << n;
        EXPECT_LE(tree.depth(), kKdStackSize);
    }
    static_assert(sizeof(KdNode) == 16);
}

/// Runs `body` in an arena of `threads` threads.
template <class Body>
void withThreads(int threads, Body&& body) {
    tbb::task_arena arena(threads);
    arena.execute(body);
}

template <class S>
class ThreadCountTest : public ::testing::Test {};
using Structures = ::testing::Types<UniformGrid, HashGrid, KdTree, MultiHash, MultiHashSmallLeaves>;
TYPED_TEST_SUITE(ThreadCountTest, Structures);

/// Every query's results, in the order reported, after a build on `threads` threads.
template <class S>
std::vector<uint32_t> resultsOnThreads(int threads, const DevicePoints& dev) {
    std::vector<uint32_t> out;
    withThreads(threads, [&] {
        const S structure = S::build(CpuExec{}, dev.set());
        const auto view = structure.view();
        auto add = [&](uint32_t i) { out.push_back(i); };
        for (const Vec3f& x : randomPoints(300, 94)) {
            view.forEachPointWithin(x, 0.01f, add);
            view.forEachSphereCovering(x, add);
            view.forEachSphereOnSegment(x, Vec3f(0.1f, -0.05f, 0.02f), 1.0f, add);
            const NearestResult r = nearest(view, x, 16, 0.05f);
            out.insert(out.end(), r.indices.begin(), r.indices.end());
        }
        out.push_back(uint32_t(structure.memoryBytes()));
    });
    return out;
}

TYPED_TEST(ThreadCountTest, SameBuildAndResultsOnOneAndTwoThreads) {
    const auto points = randomPoints(60000, 95);
    const DevicePoints dev(points, 0, randomRadii(points.size(), 96, 0.f, 0.01f));
    EXPECT_EQ(resultsOnThreads<TypeParam>(1, dev), resultsOnThreads<TypeParam>(2, dev));
}

TEST(KdTreeTest, SameNodesOnOneAndTwoThreads) {
    const auto points = clusteredPoints(60000, 97, Vec3f(0.5f), 0.3f);
    const DevicePoints dev(points, 0.01f);
    auto nodes = [&](int threads) {
        std::vector<uint32_t> out;
        withThreads(threads, [&] {
            const KdTree tree = KdTree::build(CpuExec{}, dev.set());
            for (const KdNode& node : tree.view().nodes) out.push_back(node.index);
            out.insert(out.end(), tree.view().axisWords.begin(), tree.view().axisWords.end());
        });
        return out;
    };
    EXPECT_EQ(nodes(1), nodes(2));
}

}  // namespace
}  // namespace caustica::test
