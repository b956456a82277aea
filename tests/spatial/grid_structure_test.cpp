// grid_structure_test.cpp — properties of the grids themselves: every neighbouring cell is
// visited (queries at cell corners), hash collisions give no duplicates, the build is the same
// for 1 and N threads, cells are grouped correctly, memory stays bounded.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <set>

#include "spatial/spatial_test_points.h"

namespace caustica::test {
namespace {

template <class S>
class GridStructureTest : public ::testing::Test {};
using Structures = ::testing::Types<UniformGrid, HashGrid>;
TYPED_TEST_SUITE(GridStructureTest, Structures);

/// Cell size 1 (build radius 0.5, a point at the origin so that the uniform grid starts there):
/// around each interior lattice node, one point in each of the 8 cells that meet at the node,
/// all within 0.45 of it. A query at the node must find all 8: a grid that reduces its
/// neighbourhood (skips a row, a layer, the last cell of a range) misses some.
TYPED_TEST(GridStructureTest, QueryAtACellCornerVisitsAllEightCells) {
    std::vector<Vec3f> points{Vec3f(0, 0, 0), Vec3f(4, 4, 4)};
    std::vector<Vec3f> nodes;
    for (int z = 1; z <= 3; ++z)
        for (int y = 1; y <= 3; ++y)
            for (int x = 1; x <= 3; ++x) {
                const Vec3f node{Float(x), Float(y), Float(z)};
                nodes.push_back(node);
                for (int o = 0; o < 8; ++o)
                    points.push_back(node + Vec3f(o & 1 ? 0.25f : -0.25f, o & 2 ? 0.25f : -0.25f,
                                                  o & 4 ? 0.25f : -0.25f));
            }
    std::vector<Float> radii(points.size(), 0.5f);
    const DevicePoints dev(points, 0.5f, radii);
    const TypeParam grid = TypeParam::build(CpuExec{}, dev.set());
    ASSERT_EQ(grid.cellSize(), 1.0f);
    for (const Vec3f& node : nodes) {
        EXPECT_EQ(pointsWithin(grid.view(), node, 0.45f).size(), 8u) << node.x << node.y << node.z;
        EXPECT_EQ(spheresCovering(grid.view(), node).size(), 8u) << node.x << node.y << node.z;
    }
}

TEST(HashGridTest, CollidingBucketsGiveNoDuplicates) {
    // 64 points in a 3 x 3 x 3-cell region: 64 buckets for 27+ cells, so cells share buckets.
    const auto points = randomPoints(64, 41, 0, 3);
    const DevicePoints dev(points, 0.5f);
    const HashGrid grid = HashGrid::build(CpuExec{}, dev.set());
    const HashGridView view = grid.view();
    std::set<uint32_t> buckets;
    size_t cells = 0;
    for (int z = 0; z < 4; ++z)
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x, ++cells) buckets.insert(view.bucketOf({x, y, z}));
    ASSERT_LT(buckets.size(), cells) << "no collision among the visited cells: choose another seed";
    const BruteForce reference = BruteForce::build(CpuExec{}, dev.set());
    for (const Vec3f& c : randomPoints(200, 42, 0, 3))
        for (Float r : {0.5f, 1.0f, 1.5f})
            EXPECT_EQ(pointsWithin(view, c, r), pointsWithin(reference.view(), c, r));
}

TEST(HashGridTest, TableIsTheNextPowerOfTwoOfThePointCount) {
    for (size_t n : {0, 1, 2, 3, 1000, 1024, 1025}) {
        const DevicePoints dev(randomPoints(n, 43), 0.1f);
        const HashGrid grid = HashGrid::build(CpuExec{}, dev.set());
        EXPECT_EQ(grid.bucketCount(), std::bit_ceil(std::max<size_t>(n, 1)));
        if (n > 0) {
            EXPECT_EQ(grid.cellSize(), 0.2f);  // 2 x the radius
        }
        EXPECT_EQ(grid.memoryBytes(), (n + grid.bucketCount() + 1) * sizeof(uint32_t));
    }
}

TEST(UniformGridTest, CellSizeFromRadiusAndBoundedCellCount) {
    const DevicePoints dev(randomPoints(1000, 44), 0.05f);
    const UniformGrid grid = UniformGrid::build(CpuExec{}, dev.set());
    EXPECT_EQ(grid.cellSize(), 0.1f);
    EXPECT_EQ(grid.resolution().x, 10);
    // A radius far below the spacing of the points: the grid grows its cells, not its memory.
    const DevicePoints tiny(randomPoints(1000, 45), 1e-6f);
    const UniformGrid small = UniformGrid::build(CpuExec{}, tiny.set());
    EXPECT_LE(small.memoryBytes(), (1000 + 4096 + 1) * sizeof(uint32_t) + 1000 * sizeof(Vec3f));
    // Cells of one largest radius on request (SPPM's photon grid).
    const DevicePoints wide(randomPoints(1000, 44), 0.1f);
    EXPECT_EQ(UniformGrid::build(CpuExec{}, wide.set()).cellSize(), 0.2f);
    const UniformGrid narrow = UniformGrid::build(CpuExec{}, wide.set(), 1);
    EXPECT_EQ(narrow.cellSize(), 0.1f);
    EXPECT_EQ(narrow.resolution().x, 10);
}

/// The positions in cell order are the points' positions, permuted as the cells' order.
TEST(UniformGridTest, CellPositionsFollowTheCellOrder) {
    const auto points = clusteredPoints(3000, 47, Vec3f(0.5f, 0.5f, 0.5f), 0.2f);
    const DevicePoints dev(points, 0.02f);
    const UniformGrid grid = UniformGrid::build(CpuExec{}, dev.set(), 1);
    const auto view = grid.view();
    ASSERT_EQ(view.cellPositions.size(), points.size());
    for (size_t k = 0; k < points.size(); ++k) {
        const Vec3f p = points[view.cells.order[k]], q = view.cellPositions[k];
        ASSERT_TRUE(p.x == q.x && p.y == q.y && p.z == q.z) << k;
    }
    EXPECT_EQ(grid.memoryBytes(), (points.size() + view.cells.cellStart.size()) * sizeof(uint32_t) +
                                      points.size() * sizeof(Vec3f));
}

/// Every cell holds exactly the points whose cell it is, ascending (a stable counting sort).
TYPED_TEST(GridStructureTest, CellsHoldTheirPointsInAscendingOrder) {
    const auto points = clusteredPoints(5000, 46, Vec3f(0.5f, 0.5f, 0.5f), 0.2f);
    const DevicePoints dev(points, 0.03f);
    const TypeParam grid = TypeParam::build(CpuExec{}, dev.set());
    const auto view = grid.view();
    const size_t cells = view.cells.cellStart.size() - 1;
    ASSERT_EQ(view.cells.cellStart[cells], points.size());
    std::vector<int> seen(points.size(), 0);
    for (size_t c = 0; c < cells; ++c) {
        ASSERT_LE(view.cells.cellStart[c], view.cells.cellStart[c + 1]);
        for (uint32_t k = view.cells.cellStart[c]; k < view.cells.cellStart[c + 1]; ++k) {
            const uint32_t i = view.cells.order[k];
            ++seen[i];
            if (k > view.cells.cellStart[c]) {
                EXPECT_LT(view.cells.order[k - 1], i);
            }
            EXPECT_EQ(view.keyOf(points[i]), c);
        }
    }
    for (int s : seen) ASSERT_EQ(s, 1);
}

/// The build and the order of the results are the same on 1 thread and on 8.
TYPED_TEST(GridStructureTest, SameOnOneAndManyThreads) {
    const auto points = randomPoints(200000, 47);
    const auto radii = randomRadii(points.size(), 48, 0.f, 0.01f);
    const DevicePoints dev(points, 0, radii);
    auto run = [&](int threads) {
        tbb::task_arena arena(threads);
        std::vector<uint32_t> out;
        arena.execute([&] {
            const TypeParam grid = TypeParam::build(CpuExec{}, dev.set());
            const auto view = grid.view();
            out.assign(view.cells.order.begin(), view.cells.order.end());
            out.insert(out.end(), view.cells.cellStart.begin(), view.cells.cellStart.end());
            for (const Vec3f& x : randomPoints(500, 49))  // results in visiting order
                view.forEachSphereCovering(x, [&](uint32_t i) { out.push_back(i); });
        });
        return out;
    };
    EXPECT_EQ(run(1), run(8));
}

}  // namespace
}  // namespace caustica::test
