// segment_query_test.cpp — forEachSphereOnSegment (seed 004: the spheres a ray segment passes
// through) of every structure returns exactly BruteForce's result: random segments of every
// length and direction, segments along the axes and of length zero, spheres on cell boundaries
// and segments tangent to them, clustered, empty, one sphere, identical spheres, radius zero,
// radii larger than the scene, rays to "infinity".
#include <gtest/gtest.h>

#include "spatial/spatial_test_points.h"

namespace caustica::test {
namespace {

/// A segment query: origin, direction (any length), tMax.
struct SegmentQuery {
    Vec3f o, d;
    Float tMax;
};

/// `n` random segments from around [lo, hi]^3: directions of random length (0.1 to 2), tMax so
/// that lengths run from tiny to across the box.
std::vector<SegmentQuery> randomSegments(size_t n, uint64_t seed, Float lo, Float hi) {
    const auto origins = randomPoints(n, seed, lo - 0.2f * (hi - lo), hi + 0.2f * (hi - lo));
    const auto dirs = randomPoints(n, seed + 1, -1, 1);
    const auto lengths = randomRadii(n, seed + 2, 0, 1);
    std::vector<SegmentQuery> q(n);
    for (size_t i = 0; i < n; ++i) {
        const Float scale = 0.1f + 1.9f * lengths[(i + 7) % n];
        const Float len = (hi - lo) * lengths[i] * lengths[i] * 1.5f;  // many short ones
        q[i] = {origins[i], dirs[i] * scale, len / max(length(dirs[i] * scale), 1e-6f)};
    }
    return q;
}

/// Segments along +-x, +-y, +-z through each of `centers` (offset sideways by `offset`, e.g.
/// to be tangent to spheres of that radius), of length 2 x `length`, and of length zero.
std::vector<SegmentQuery> axisSegments(const std::vector<Vec3f>& centers, Float offset,
                                       Float length) {
    std::vector<SegmentQuery> q;
    for (const Vec3f& c : centers) {
        for (int a = 0; a < 3; ++a) {
            Vec3f d(0), side(0);
            d[a] = 1;
            side[(a + 1) % 3] = offset;
            q.push_back({c + side - d * length, d, 2 * length});
            q.push_back({c + side + d * length, -d * 0.5f, 4 * length});  // reversed, not unit
        }
        q.push_back({c, Vec3f(0), 1.0f});                               // zero direction
        q.push_back({c, Vec3f(1, 0, 0), 0.0f});                         // tMax zero
        q.push_back({c + Vec3f(0, offset, 0), Vec3f(0, 0, 1), -1.0f});  // negative tMax
    }
    return q;
}

template <class S>
class SegmentQueryTest : public ::testing::Test {
protected:
    /// Builds S and BruteForce over spheres (points, radii or `uniformRadius`) and compares the
    /// spheres every segment meets.
    void expectSameAsBruteForce(const std::vector<Vec3f>& points, const std::vector<Float>& radii,
                                const std::vector<SegmentQuery>& segments,
                                Float uniformRadius = 0) {
        const DevicePoints dev(points, uniformRadius, radii);
        const S structure = S::build(CpuExec{}, dev.set());
        const BruteForce reference = BruteForce::build(CpuExec{}, dev.set());
        ResultCheck check(StructureName<S>::value);
        for (size_t q = 0; q < segments.size() && !check.enough(); ++q) {
            const SegmentQuery& s = segments[q];
            check.compare(spheresOnSegment(structure.view(), s.o, s.d, s.tMax),
                          spheresOnSegment(reference.view(), s.o, s.d, s.tMax), s.o,
                          queryLabel(q) + " dir (" + std::to_string(s.d.x) + ", " +
                              std::to_string(s.d.y) + ", " + std::to_string(s.d.z) + ") tMax " +
                              std::to_string(s.tMax));
        }
        check.expectSomeFound(!points.empty());
    }
};

TYPED_TEST_SUITE(SegmentQueryTest, IndexedStructures);

TYPED_TEST(SegmentQueryTest, RandomSegmentsVariedRadii) {
    const auto centers = randomPoints(2000, 61);
    const auto radii = randomRadii(centers.size(), 62, 0.001f, 0.05f);
    auto segments = randomSegments(400, 63, 0, 1);
    const auto axis = axisSegments(randomPoints(30, 64), 0.02f, 0.3f);
    segments.insert(segments.end(), axis.begin(), axis.end());
    this->expectSameAsBruteForce(centers, radii, segments);
}

TYPED_TEST(SegmentQueryTest, OneLargeSphereAmongSmallOnesAndUniformRadius) {
    auto centers = randomPoints(1500, 65);
    auto radii = randomRadii(centers.size(), 66, 0.f, 0.005f);
    centers.push_back(Vec3f(0.5f, 0.5f, 0.5f));
    radii.push_back(0.45f);
    auto segments = randomSegments(300, 67, 0, 1);
    const auto through = axisSegments({centers.begin(), centers.begin() + 20}, 0, 0.05f);
    segments.insert(segments.end(), through.begin(), through.end());  // radius 0 hits these
    this->expectSameAsBruteForce(centers, radii, segments);
    this->expectSameAsBruteForce(centers, {}, segments, 0.01f);  // one common radius
    this->expectSameAsBruteForce(centers, {}, segments, 0.f);    // radius zero: only exact hits
}

TYPED_TEST(SegmentQueryTest, SpheresOnCellBoundariesAndTangentSegments) {
    // Radius 0.5 sets cell size 1 = the lattice spacing: centres on cell corners. Segments along
    // the lattice lines pass through centres; offset by 0.5 they are tangent to the spheres.
    const auto centers = latticePoints(5, 1.0f);
    const std::vector<Float> radii(centers.size(), 0.5f);
    std::vector<Vec3f> through = latticePoints(5, 1.0f);
    for (Float offset : {0.f, 0.5f, 0.25f}) {
        const auto segments = axisSegments(through, offset, 1.0f);
        this->expectSameAsBruteForce(centers, radii, segments);
        this->expectSameAsBruteForce(centers, {}, segments, 0.f);  // points on the segments
    }
    // A segment ending exactly on a cell face and one along a face diagonal.
    this->expectSameAsBruteForce(centers, radii,
                                 {{Vec3f(0.5f, 0.5f, 0.5f), Vec3f(1, 0, 0), 1.5f},
                                  {Vec3f(0, 0, 1), Vec3f(1, 1, 0), 4.0f},
                                  {Vec3f(-1, -1, -1), Vec3f(1, 1, 1), 6.0f}});
}

TYPED_TEST(SegmentQueryTest, ClusteredSpheresInATinyRegion) {
    const Vec3f c(0.3f, 0.6f, 0.2f);
    const auto centers = clusteredPoints(2000, 68, c, 1e-3f);
    const auto radii = randomRadii(centers.size(), 69, 0.f, 2e-4f);
    auto segments = axisSegments(clusteredPoints(40, 70, c, 1e-3f), 1e-4f, 2e-3f);
    for (const SegmentQuery& s : randomSegments(100, 71, -1e-3f, 1e-3f))
        segments.push_back({s.o + c, s.d, s.tMax});
    segments.push_back({c - Vec3f(1, 1, 1), Vec3f(1, 1, 1), 2.0f});  // long, through the cluster
    this->expectSameAsBruteForce(centers, radii, segments);
}

TYPED_TEST(SegmentQueryTest, EmptyOneAndIdenticalSpheres) {
    const auto segments = randomSegments(100, 72, -1, 1);
    this->expectSameAsBruteForce({}, {}, segments, 0.1f);
    const std::vector<Vec3f> one{Vec3f(0.1f, 0.2f, 0.3f)};
    auto oneSegments = axisSegments(one, 0.05f, 0.2f);
    oneSegments.insert(oneSegments.end(), segments.begin(), segments.end());
    for (Float r : {0.f, 0.05f, 0.3f, 1e6f}) this->expectSameAsBruteForce(one, {r}, oneSegments);
    const std::vector<Vec3f> same(300, Vec3f(0.25f, 0.25f, 0.25f));
    auto sameSegments = axisSegments({Vec3f(0.25f, 0.25f, 0.25f)}, 0.01f, 0.1f);
    sameSegments.insert(sameSegments.end(), segments.begin(), segments.end());
    this->expectSameAsBruteForce(same, {}, sameSegments, 0.01f);
    this->expectSameAsBruteForce(same, {}, sameSegments, 0.f);
}

TYPED_TEST(SegmentQueryTest, HugeRadiiAndRays) {
    const auto centers = randomPoints(500, 73, -10, 10);
    const auto segments = randomSegments(50, 74, -10, 10);
    this->expectSameAsBruteForce(centers, {}, segments, 1e5f);  // every sphere meets every one
    const DevicePoints dev(centers, 1e5f);
    EXPECT_EQ(
        spheresOnSegment(TypeParam::build(CpuExec{}, dev.set()).view(), Vec3f(0), Vec3f(1, 0, 0), 1)
            .size(),
        centers.size());
    // Rays: tMax FLT_MAX and infinity (clamped to FLT_MAX), from inside and outside the box.
    std::vector<SegmentQuery> rays;
    for (const SegmentQuery& s : randomSegments(20, 75, -10, 10)) {
        rays.push_back({s.o, s.d, kInfinity});
        rays.push_back({s.o, s.d, kUnbounded});
    }
    this->expectSameAsBruteForce(centers, randomRadii(centers.size(), 76, 0.f, 1.f), rays);
}

/// A segment of length zero (tMax 0 or direction 0) finds exactly the spheres covering its
/// origin: the two predicates compute the same float expression.
TYPED_TEST(SegmentQueryTest, ZeroLengthEqualsCovering) {
    const auto centers = randomPoints(1000, 77);
    const auto radii = randomRadii(centers.size(), 78, 0.f, 0.06f);
    const DevicePoints dev(centers, 0, radii);
    const TypeParam structure = TypeParam::build(CpuExec{}, dev.set());
    size_t found = 0, q = 0;
    for (const SegmentQuery& s : randomSegments(200, 79, 0, 1)) {
        const Vec3f o = s.o * 0.02f + centers[q++] * 0.98f;  // near a centre
        const auto covering = spheresCovering(structure.view(), o);
        EXPECT_EQ(spheresOnSegment(structure.view(), o, s.d, 0), covering);
        EXPECT_EQ(spheresOnSegment(structure.view(), o, Vec3f(0), s.tMax), covering);
        found += covering.size();
    }
    EXPECT_GT(found, 0u);
}

}  // namespace
}  // namespace caustica::test
