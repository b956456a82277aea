// nearest_test.cpp — kNearest of every structure (BruteForce included) returns exactly the
// reference list: all points sorted by (squared distance as inBall computes it, index), cut at
// maxRadius and at k (at most kMaxNeighbors). Ordered lists, so ties must break by index:
// lattices (many equal distances), identical points, clustered points, queries far outside,
// maxRadius zero and beyond the scene, k from 0 to above the maximum.
#include <gtest/gtest.h>

#include "spatial/spatial_test_points.h"

namespace caustica::test {
namespace {

template <class S>
class NearestTest : public ::testing::Test {
protected:
    /// Builds S over `points` (build radius `buildRadius`) and compares kNearest at every
    /// center, for every k and maxRadius, with the sorted reference.
    void expectSameAsReference(const std::vector<Vec3f>& points, Float buildRadius,
                               const std::vector<Vec3f>& centers, const std::vector<uint32_t>& ks,
                               const std::vector<Float>& maxRadii) {
        const DevicePoints dev(points, buildRadius);
        const S structure = S::build(CpuExec{}, dev.set());
        int failures = 0;
        size_t nonEmpty = 0;
        for (size_t q = 0; q < centers.size() && failures < 5; ++q) {
            const auto sorted = allByDistance(points, centers[q]);
            for (Float maxRadius : maxRadii) {
                for (uint32_t k : ks) {
                    const NearestResult expected = nearestPrefix(sorted, k, maxRadius);
                    const NearestResult got = nearest(structure.view(), centers[q], k, maxRadius);
                    nonEmpty += !expected.indices.empty();
                    if (got == expected) continue;
                    ++failures;
                    ADD_FAILURE() << StructureName<S>::value << ": " << queryLabel(q, maxRadius)
                                  << " k " << k << " at (" << centers[q].x << ", " << centers[q].y
                                  << ", " << centers[q].z << "): " << got.indices.size()
                                  << " found, " << expected.indices.size() << " expected";
                }
            }
        }
        if (!points.empty()) {
            EXPECT_GT(nonEmpty, 0u) << "no query found anything: the test proves nothing";
        }
    }
};

using Structures = ::testing::Types<BruteForce, UniformGrid, UniformGridNarrowCells, HashGrid, KdTree, MultiHash, MultiHashSmallLeaves, MultiHashCoarserCells>;
TYPED_TEST_SUITE(NearestTest, Structures);

const std::vector<uint32_t> kKs{1, 2, 7, 32, 64};

TYPED_TEST(NearestTest, RandomPoints) {
    const auto points = randomPoints(3000, 81);
    std::vector<Vec3f> centers = randomPoints(150, 82, -0.2f, 1.2f);
    for (size_t i = 0; i < 50; ++i) centers.push_back(points[i]);
    // Build radius as a photon map's, and tiny (cells far smaller than the neighbourhoods).
    for (Float build : {0.03f, 1e-4f})
        this->expectSameAsReference(points, build, centers, kKs, {kUnbounded, 0.05f, 0.12f});
}

TYPED_TEST(NearestTest, LatticeTiesBreakByIndex) {
    // Queries at nodes, cell centres and edge midpoints: 6, 8 and 4 neighbours at exactly equal
    // distances; build radius 0.5 puts every point on cell boundaries.
    const auto points = latticePoints(7, 1.0f);
    std::vector<Vec3f> centers;
    for (const Vec3f& p : latticePoints(6, 1.0f)) {
        centers.push_back(p);
        centers.push_back(p + Vec3f(0.5f, 0.5f, 0.5f));
        centers.push_back(p + Vec3f(0.5f, 0, 0));
    }
    this->expectSameAsReference(points, 0.5f, centers, {1, 3, 7, 9, 27, 64},
                                {kUnbounded, 1.0f, std::sqrt(3.f) / 2, 0.f});
}

TYPED_TEST(NearestTest, IdenticalPointsAndClusters) {
    std::vector<Vec3f> points(200, Vec3f(0.5f, 0.5f, 0.5f));
    const auto cluster = clusteredPoints(1000, 83, Vec3f(0.2f, 0.7f, 0.4f), 1e-4f);
    points.insert(points.end(), cluster.begin(), cluster.end());
    const auto more = randomPoints(300, 84);
    points.insert(points.end(), more.begin(), more.end());
    std::vector<Vec3f> centers{Vec3f(0.5f, 0.5f, 0.5f), Vec3f(0.2f, 0.7f, 0.4f),
                               Vec3f(0.5f, 0.5f, 0.6f)};
    const auto near = clusteredPoints(60, 85, Vec3f(0.2f, 0.7f, 0.4f), 2e-4f);
    centers.insert(centers.end(), near.begin(), near.end());
    for (Float build : {0.02f, 1e-5f})
        this->expectSameAsReference(points, build, centers, kKs, {kUnbounded, 1e-4f, 0.f, 0.3f});
}

TYPED_TEST(NearestTest, EmptyOneAndFarQueries) {
    const auto centers = randomPoints(20, 86, -5, 5);
    this->expectSameAsReference({}, 0.1f, centers, kKs, {kUnbounded, 1.f});
    const std::vector<Vec3f> one{Vec3f(0.25f, -3.0f, 7.5f)};
    this->expectSameAsReference(one, 0.1f, centers, kKs, {kUnbounded, 1.f, 20.f});
    // Queries far outside the points' box, with and without a radius reaching them.
    const auto points = randomPoints(2000, 87);
    const std::vector<Vec3f> far{Vec3f(100, 0.5f, 0.5f), Vec3f(-50, -50, 80), Vec3f(0.5f, 0.5f, -3),
                                 Vec3f(1e6f, 1e6f, -1e6f)};
    this->expectSameAsReference(points, 0.02f, far, kKs, {kUnbounded, 100.f, 1.f, 2e6f});
}

TYPED_TEST(NearestTest, KZeroAndAboveTheMaximum) {
    const auto points = randomPoints(500, 88);
    const DevicePoints dev(points, 0.05f);
    const TypeParam structure = TypeParam::build(CpuExec{}, dev.set());
    EXPECT_TRUE(nearest(structure.view(), Vec3f(0.5f), 0, kUnbounded).indices.empty());
    const NearestResult many = nearest(structure.view(), Vec3f(0.5f), 1000, kUnbounded);
    EXPECT_EQ(many.indices.size(), kMaxNeighbors);
    EXPECT_EQ(many, nearestPrefix(allByDistance(points, Vec3f(0.5f)), 1000, kUnbounded));
    // Radius larger than the scene: the k nearest of all; radius zero at a point: that point.
    EXPECT_EQ(nearest(structure.view(), Vec3f(0.5f), 5, 1e6f),
              nearestPrefix(allByDistance(points, Vec3f(0.5f)), 5, kUnbounded));
    for (uint32_t i = 0; i < 20; ++i)
        EXPECT_EQ(nearest(structure.view(), points[i], 3, 0).indices, std::vector<uint32_t>{i});
}

}  // namespace
}  // namespace caustica::test
