// Accel (backend selection, visit) and self-intersection of spawned rays on both backends.
#include <string>

#include <gtest/gtest.h>

#include "accel/test_scenes.h"
#include "caustica/accel/accel.h"
#include "caustica/scene/interaction.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

TEST(AccelKind, ParsesNamesAndRejectsOthers) {
    EXPECT_EQ(parseAccelKind("bvh"), AccelKind::Bvh);
    EXPECT_EQ(parseAccelKind("embree"), AccelKind::Embree);
    EXPECT_STREQ(accelKindName(AccelKind::Bvh), "bvh");
    EXPECT_STREQ(accelKindName(AccelKind::Embree), "embree");
    EXPECT_THROW(parseAccelKind("optix"), Error);
    EXPECT_THROW(parseAccelKind(""), Error);
    try {
        parseAccelKind("kdtree");
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("kdtree"), std::string::npos);
    }
}

class AccelBackends : public ::testing::TestWithParam<AccelKind> {};

TEST_P(AccelBackends, VisitAnswersLikeBruteForce) {
    const Scene scene = test::makeRandomScene(test::sceneOf(500, 50, 1));
    const Accel accel(scene, GetParam());
    EXPECT_EQ(accel.kind(), GetParam());
    EXPECT_EQ(accel.bvh() != nullptr, GetParam() == AccelKind::Bvh);
    const std::vector<Ray> rays = test::makeRandomRays(scene, 1000, 3);
    const int agree = accel.visit([&](const auto& it) {
        int n = 0;
        for (const Ray& ray : rays) {
            Hit ref, got;
            const bool refHit = test::bruteForceIntersect(scene.view(), ray, ref);
            n += it.intersect(ray, got) == refHit && it.occluded(ray) == refHit &&
                 (!refHit || std::fabs(got.t - ref.t) <= 1e-4f * ref.t);
        }
        return n;
    });
    EXPECT_GE(agree, 995);
}

TEST_P(AccelBackends, EmptySceneWorks) {
    const Scene scene;
    const Accel accel(scene, GetParam());
    Hit hit;
    const Ray ray{{0, 0, 0}, {1, 0, 0}, kInfinity};
    EXPECT_FALSE(accel.visit([&](const auto& it) { return it.intersect(ray, hit); }));
    EXPECT_FALSE(accel.visit([&](const auto& it) { return it.occluded(ray); }));
}

/// Rays spawned from hit points must not hit the primitive they start on, in either hemisphere;
/// shadow rays between two mutually visible hit points must not be blocked by either end.
void checkSpawnedRays(const Scene& scene, AccelKind kind, uint32_t numRays, uint64_t seed) {
    const Accel accel(scene, kind);
    const SceneView view = scene.view();
    test::TestRng rng(seed);
    const Bounds3f b = scene.bounds();
    const Vec3f margin = b.diagonal() * 0.5f;
    uint32_t bounces = 0, shadowRays = 0;
    accel.visit([&](const auto& it) {
        for (uint32_t i = 0; i < numRays; ++i) {
            const Vec3f o = rng.inBox(b.lo - margin, b.hi + margin);
            const Vec3f target =
                test::pointOnPrimitive(scene, rng.index(scene.numPrimitives()), rng);
            const Ray ray{o, target - o, kInfinity};
            Hit hit;
            if (!it.intersect(ray, hit)) continue;
            const SurfaceInteraction si = computeInteraction(view, ray, hit);
            const bool isSphere = hit.primId >= view.numTriangles();
            for (int side = 0; side < 2; ++side) {
                // side 0: back towards the ray's origin (reflection); 1: through (transmission).
                Vec3f dir = rng.direction() * rng.uniform(0.01f, 100.0f);
                const Float towardOrigin = dot(-ray.d, si.ng) > 0 ? 1.0f : -1.0f;
                const Float sign = side == 0 ? towardOrigin : -towardOrigin;
                const Float cosine = dot(dir, si.ng) * sign / length(dir);
                if (cosine < 0) dir = -dir;
                if (std::fabs(cosine) < 0.1f && isSphere) continue;  // keep chords long
                const Ray spawned = spawnRay(si.p, si.ng, dir);
                Hit next;
                ++bounces;
                if (!it.intersect(spawned, next)) continue;
                if (next.primId == hit.primId) {
                    // Only a sphere can be hit again legitimately: on its far side, going inward.
                    ASSERT_TRUE(isSphere) << "triangle " << hit.primId << " re-hit at t=" << next.t;
                    ASSERT_GT(next.t * length(dir),
                              0.1f * view.spheres[hit.primId - view.numTriangles()].radius);
                    continue;
                }
                // Shadow ray between the two hit points: the segment was free, so not occluded
                // unless a third primitive grazes the slightly shifted segment.
                const SurfaceInteraction end = computeInteraction(view, spawned, next);
                const Ray shadow = spawnRayTo(si.p, si.ng, end.p, end.ng);
                ++shadowRays;
                Hit blocker;
                if (it.occluded(shadow) && it.intersect(shadow, blocker)) {
                    ASSERT_NE(blocker.primId, hit.primId) << "shadow ray re-hits its origin";
                    ASSERT_NE(blocker.primId, next.primId) << "shadow ray hits its target";
                }
            }
        }
    });
    EXPECT_GT(bounces, numRays / 2);
    EXPECT_GT(shadowRays, numRays / 10);
}

TEST_P(AccelBackends, NoSelfIntersectionOnLargeMesh) {
    // 80,000 triangles spanning 2000 units: vertex coordinates up to 1e3.
    checkSpawnedRays(test::makeTerrain(200, 1000, Vec3f(0, 0, 0), 40), GetParam(), 3000, 41);
}

TEST_P(AccelBackends, NoSelfIntersectionFarFromTheOrigin) {
    // A small bumpy terrain and a sphere around (1500, -1200, 1800).
    Scene scene = test::makeTerrain(60, 10, Vec3f(1500, -1200, 1800), 2);
    test::addSphere(scene, Vec3f(1500, -1195, 1800), 3);
    test::addSphere(scene, Vec3f(1504, -1196, 1797), 0.5f);
    checkSpawnedRays(scene, GetParam(), 3000, 42);
}

INSTANTIATE_TEST_SUITE_P(Backends, AccelBackends,
                         ::testing::Values(AccelKind::Bvh, AccelKind::Embree),
                         [](const auto& info) { return std::string(accelKindName(info.param)); });

}  // namespace
}  // namespace caustica
