// point_query_test.cpp — forEachPointWithin (photons gathered around a point) of every structure
// returns exactly BruteForce's result: random, clustered, lattice (cell boundaries), empty, one
// point, duplicates; query radii from 0 to covering everything.
#include <gtest/gtest.h>

#include "spatial/spatial_test_points.h"

namespace caustica::test {
namespace {

static_assert(PointLookup<BruteForce, CpuExec>);
static_assert(PointLookup<UniformGrid, CpuExec>);
static_assert(PointLookup<HashGrid, CpuExec>);
static_assert(PointLookup<KdTree, CpuExec>);
static_assert(PointLookup<MultiHash, CpuExec>);

template <class S>
class PointQueryTest : public ::testing::Test {
protected:
    /// Builds S and BruteForce over `points` (build radius `buildRadius`) and compares the
    /// results of every query center with every radius in `radii`.
    void expectSameAsBruteForce(const std::vector<Vec3f>& points, Float buildRadius,
                                const std::vector<Vec3f>& centers,
                                const std::vector<Float>& radii) {
        const DevicePoints dev(points, buildRadius);
        const S structure = S::build(CpuExec{}, dev.set());
        const BruteForce reference = BruteForce::build(CpuExec{}, dev.set());
        ResultCheck check(StructureName<S>::value);
        for (size_t q = 0; q < centers.size() && !check.enough(); ++q)
            for (Float r : radii)
                check.compare(pointsWithin(structure.view(), centers[q], r),
                              pointsWithin(reference.view(), centers[q], r), centers[q],
                              queryLabel(q, r));
        check.expectSomeFound(!points.empty());
    }
};

TYPED_TEST_SUITE(PointQueryTest, IndexedStructures);

TYPED_TEST(PointQueryTest, RandomPoints) {
    const auto points = randomPoints(3000, 1);
    const Float r = 0.05f;
    this->expectSameAsBruteForce(points, r, queryPoints(points, r, 2),
                                 {r, 0.5f * r, 0.999f * r, 3 * r, 0.f, 1e-7f});
}

TYPED_TEST(PointQueryTest, ClusteredPointsInATinyRegion) {
    const auto points = clusteredPoints(3000, 3, Vec3f(0.3f, 0.6f, 0.2f), 1e-4f);
    std::vector<Vec3f> centers = queryPoints(points, 1e-4f, 4);
    centers.push_back(Vec3f(0.3f, 0.6f, 0.2f));
    // Build radius: as for photons in a caustic (large against the cluster) and tiny.
    for (Float build : {0.05f, 1e-6f})
        this->expectSameAsBruteForce(points, build, centers, {build, 5e-5f, 2e-4f, 1e-7f});
}

TYPED_TEST(PointQueryTest, PointsOnCellBoundaries) {
    // Build radius 0.5: cell size 1 = the lattice spacing, so every point lies on cell faces,
    // and queries of radius 1 at a node have neighbours exactly on their sphere.
    const auto points = latticePoints(6, 1.0f);
    std::vector<Vec3f> centers = points;
    for (const Vec3f& p : latticePoints(6, 1.0f)) centers.push_back(p + Vec3f(0.5f, 0.5f, 0.5f));
    this->expectSameAsBruteForce(points, 0.5f, centers, {1.0f, 0.5f, 1.5f, 0.f, std::sqrt(3.f)});
}

TYPED_TEST(PointQueryTest, EmptySet) {
    this->expectSameAsBruteForce({}, 0.1f, randomPoints(20, 5), {0.1f, 1e6f});
}

TYPED_TEST(PointQueryTest, OnePoint) {
    const std::vector<Vec3f> one{Vec3f(0.25f, -3.0f, 7.5f)};
    std::vector<Vec3f> centers = queryPoints(one, 0.1f, 6);
    for (Float build : {0.1f, 0.f, 1e6f})
        this->expectSameAsBruteForce(one, build, centers, {0.1f, 0.f, 1e-7f, 1e6f});
}

TYPED_TEST(PointQueryTest, CoincidentPoints) {
    std::vector<Vec3f> points(500, Vec3f(0.5f, 0.5f, 0.5f));
    const auto more = randomPoints(500, 7);
    points.insert(points.end(), more.begin(), more.end());
    this->expectSameAsBruteForce(points, 0.02f, queryPoints(points, 0.02f, 8), {0.02f, 0.f});
}

TYPED_TEST(PointQueryTest, HugeRadiusCoversEverything) {
    const auto points = randomPoints(1000, 9, -50, 50);
    const std::vector<Vec3f> centers{Vec3f(0, 0, 0), Vec3f(1e3f, -1e3f, 0), Vec3f(50, 50, 50)};
    for (Float build : {1e5f, 0.5f}) {  // built for the huge radius, and for a small one
        this->expectSameAsBruteForce(points, build, centers, {1e5f});
        const DevicePoints dev(points, build);
        EXPECT_EQ(pointsWithin(TypeParam::build(CpuExec{}, dev.set()).view(), Vec3f(0, 0, 0), 1e5f)
                      .size(),
                  points.size());
    }
}

TYPED_TEST(PointQueryTest, TinyRadiusFindsNothingOrTheCoincidentPoint) {
    const auto points = randomPoints(2000, 10);
    const DevicePoints dev(points, 1e-7f);
    const TypeParam structure = TypeParam::build(CpuExec{}, dev.set());
    for (size_t i = 0; i < 100; ++i) {
        const auto found = pointsWithin(structure.view(), points[i], 1e-7f);
        ASSERT_EQ(found.size(), 1u);
        EXPECT_EQ(found[0], uint32_t(i));
        EXPECT_TRUE(pointsWithin(structure.view(), points[i] + Vec3f(1e-3f, 0, 0), 1e-7f).empty());
    }
    this->expectSameAsBruteForce(points, 1e-7f, queryPoints(points, 1e-7f, 11), {1e-7f, 0.f});
}

}  // namespace
}  // namespace caustica::test
