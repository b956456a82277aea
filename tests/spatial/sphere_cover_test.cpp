// sphere_cover_test.cpp — forEachSphereCovering (SPPM's visible points with their radii, each
// photon depositing into every sphere that covers it) of every structure returns exactly
// BruteForce's result: varied radii, one large sphere among small ones, zero radii, uniform
// radius, spheres on cell boundaries, empty set, one sphere.
#include <gtest/gtest.h>

#include "spatial/spatial_test_points.h"

namespace caustica::test {
namespace {

template <class S>
class SphereCoverTest : public ::testing::Test {
protected:
    /// Builds S and BruteForce over spheres (points, radii) and compares the spheres covering
    /// every x in `xs`.
    void expectSameAsBruteForce(const std::vector<Vec3f>& points, const std::vector<Float>& radii,
                                const std::vector<Vec3f>& xs, Float uniformRadius = 0) {
        const DevicePoints dev(points, uniformRadius, radii);
        const S structure = S::build(CpuExec{}, dev.set());
        const BruteForce reference = BruteForce::build(CpuExec{}, dev.set());
        ResultCheck check(StructureName<S>::value);
        for (size_t q = 0; q < xs.size() && !check.enough(); ++q)
            check.compare(spheresCovering(structure.view(), xs[q]),
                          spheresCovering(reference.view(), xs[q]), xs[q], queryLabel(q));
        check.expectSomeFound(!points.empty());
    }
};

TYPED_TEST_SUITE(SphereCoverTest, IndexedStructures);

TYPED_TEST(SphereCoverTest, VariedRadii) {
    const auto centers = randomPoints(3000, 21);
    const auto radii = randomRadii(centers.size(), 22, 0.001f, 0.08f);
    std::vector<Vec3f> xs = randomPoints(2000, 23, -0.1f, 1.1f);
    for (size_t i = 0; i < 300; ++i) {  // on the sphere's surface (up to rounding) and centre
        xs.push_back(centers[i] + Vec3f(radii[i], 0, 0));
        xs.push_back(centers[i] - Vec3f(0, radii[i], 0));
        xs.push_back(centers[i]);
    }
    this->expectSameAsBruteForce(centers, radii, xs);
}

TYPED_TEST(SphereCoverTest, OneLargeSphereAmongSmallOnes) {
    auto centers = randomPoints(2000, 24);
    auto radii = randomRadii(centers.size(), 25, 0.f, 0.01f);
    centers.push_back(Vec3f(0.5f, 0.5f, 0.5f));
    radii.push_back(0.4f);
    radii[7] = 0;  // a zero radius covers its centre only
    std::vector<Vec3f> xs = randomPoints(2000, 26, -0.1f, 1.1f);
    xs.push_back(centers[7]);
    this->expectSameAsBruteForce(centers, radii, xs);
}

TYPED_TEST(SphereCoverTest, UniformRadiusWithoutPerPointRadii) {
    const auto centers = clusteredPoints(2000, 27, Vec3f(-2, 3, 1), 0.01f);
    this->expectSameAsBruteForce(centers, {}, clusteredPoints(2000, 28, Vec3f(-2, 3, 1), 0.02f),
                                 0.004f);
}

TYPED_TEST(SphereCoverTest, SpheresOnCellBoundaries) {
    // Radii 0.5 and 0.25: the largest sets cell size 1 = the lattice spacing.
    const auto centers = latticePoints(5, 1.0f);
    std::vector<Float> radii(centers.size(), 0.5f);
    for (size_t i = 0; i < radii.size(); i += 2) radii[i] = 0.25f;
    std::vector<Vec3f> xs;
    for (const Vec3f& c : centers) {
        xs.push_back(c + Vec3f(0.5f, 0, 0));
        xs.push_back(c + Vec3f(0.25f, 0.25f, 0.25f));
        xs.push_back(c + Vec3f(0, 0, -0.25f));
    }
    this->expectSameAsBruteForce(centers, radii, xs);
}

TYPED_TEST(SphereCoverTest, EmptySetAndOneSphere) {
    this->expectSameAsBruteForce({}, {}, randomPoints(20, 29));
    const std::vector<Vec3f> one{Vec3f(1, 2, 3)};
    std::vector<Vec3f> xs = randomPoints(500, 30, 0.5f, 3.5f);
    xs.push_back(Vec3f(1, 2, 3));
    for (Float r : {0.f, 1e-7f, 0.3f, 1e6f}) this->expectSameAsBruteForce(one, {r}, xs);
}

TYPED_TEST(SphereCoverTest, HugeRadiiCoverEverythingTinyOnesNothing) {
    const auto centers = randomPoints(1000, 31, -10, 10);
    const auto xs = randomPoints(100, 32, -10, 10);
    this->expectSameAsBruteForce(centers, std::vector<Float>(centers.size(), 1e5f), xs);
    const DevicePoints huge(centers, 1e5f);
    EXPECT_EQ(spheresCovering(TypeParam::build(CpuExec{}, huge.set()).view(), xs[0]).size(),
              centers.size());
    const DevicePoints tiny(centers, 1e-7f);
    const TypeParam structure = TypeParam::build(CpuExec{}, tiny.set());
    for (size_t q = 0; q < xs.size(); ++q)
        EXPECT_TRUE(spheresCovering(structure.view(), xs[q]).empty());
    EXPECT_EQ(spheresCovering(structure.view(), centers[3]), std::vector<uint32_t>{3});
}

}  // namespace
}  // namespace caustica::test
