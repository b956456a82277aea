// cylinder_intersect_test.cpp — the analytic open cylinder: intersectCylinder against a
// double-precision solution, open ends and tMax, and the own BVH and Embree against brute force
// on scenes mixing triangles, spheres and cylinders.
#include <gtest/gtest.h>

#include <cmath>

#include "accel/cylinder_reference.h"
#include "accel/test_scenes.h"
#include "caustica/accel/bvh_traversal.h"
#include "caustica/accel/embree_accel.h"
#include "caustica/accel/intersector.h"
#include "caustica/accel/primitive_intersect.h"
#include "scene/scene_builder.h"

namespace caustica {
namespace {

using test::makeCylinder;

bool hitCyl(const Cylinder& c, Vec3f o, Vec3f d, Float tMax, Float& t) {
    return intersectCylinder(o, d, tMax, c.base, c.axis, c.radius, c.length, t);
}

/// The nearest valid t in (0, tMax) in double precision, or -1.
double referenceT(const Cylinder& c, Vec3f o, Vec3f d, double tMax) {
    const test::CylinderRoots roots(c, o, d);
    for (int i = 0; i < roots.count; ++i) {
        const double t = roots.t[i], h = roots.height(i);
        if (t > 0 && t < tMax && h >= 0 && h <= c.length) return t;
    }
    return -1;
}

TEST(CylinderIntersect, SideHitFromOutside) {
    const Cylinder c = makeCylinder({0, 0, 0}, {0, 0, 1}, 1, 2);
    Float t;
    ASSERT_TRUE(hitCyl(c, {3, 0, 1}, {-1, 0, 0}, kInfinity, t));
    EXPECT_FLOAT_EQ(t, 2);
    ASSERT_TRUE(hitCyl(c, {3, 0, 1}, {-2, 0, 0}, kInfinity, t));  // non-unit direction
    EXPECT_FLOAT_EQ(t, 1);
    EXPECT_FALSE(hitCyl(c, {3, 0, 1}, {-1, 0, 0}, 2, t));  // open interval: t < tMax
}

TEST(CylinderIntersect, OpenEndsAndInside) {
    const Cylinder c = makeCylinder({0, 0, 0}, {0, 0, 1}, 1, 2);
    Float t;
    EXPECT_FALSE(hitCyl(c, {0, 0, 5}, {0, 0, -1}, kInfinity, t));   // along the axis: no caps
    EXPECT_FALSE(hitCyl(c, {3, 0, 2.5f}, {-1, 0, 0}, kInfinity, t));  // above the top
    ASSERT_TRUE(hitCyl(c, {0, 0, 1}, {1, 0, 0}, kInfinity, t));     // from inside: far wall
    EXPECT_FLOAT_EQ(t, 1);
    // Entering through the open top and hitting the inner wall.
    ASSERT_TRUE(hitCyl(c, {0, 0, 3}, {1, 0, -1}, kInfinity, t));
    EXPECT_NEAR(t, 1.0, 1e-6);
    // Grazing past the near wall above the top, hitting the far wall's inside.
    ASSERT_TRUE(hitCyl(c, {-3, 0, 2.6f}, {1, 0, -0.25f}, kInfinity, t));
    EXPECT_NEAR(t, 4.0, 1e-5);
}

TEST(CylinderIntersect, MatchesDoublePrecisionOnRandomRays) {
    test::TestRng rng(9);
    int hits = 0;
    for (int i = 0; i < 20000; ++i) {
        const Cylinder c = makeCylinder(rng.inBox(Vec3f(-1), Vec3f(1)), rng.direction(),
                                        rng.uniform(0.1f, 2), rng.uniform(0.1f, 3));
        const Vec3f o = rng.inBox(Vec3f(-4), Vec3f(4));
        const Vec3f target = c.base + c.axis * (c.length * rng.uniform(-0.2f, 1.2f)) +
                             rng.direction() * c.radius;
        const Vec3f d = (target - o) * rng.uniform(0.3f, 3);
        const Float tMax = rng.uniform() < 0.2f ? rng.uniform(0, 2) : kInfinity;
        const double ref = referenceT(c, o, d, tMax);
        Float t = -1;
        const bool h = hitCyl(c, o, d, tMax, t);
        // Rays within rounding of an end rim or a tangent may differ; allow a few.
        if (h != (ref > 0)) continue;
        if (h) {
            ++hits;
            EXPECT_NEAR(t, ref, 1e-4 * ref) << i;
        }
    }
    EXPECT_GT(hits, 10000);
}

/// Triangles and spheres from makeRandomScene plus `n` random cylinders (one shape each).
Scene mixedScene(uint32_t tris, uint32_t spheres, uint32_t cylinders, uint64_t seed) {
    Scene scene = test::makeRandomScene(test::sceneOf(tris, spheres, seed));
    test::TestRng rng(seed + 100);
    for (uint32_t i = 0; i < cylinders; ++i)
        test::addCylinder(scene, rng.inBox(Vec3f(-5), Vec3f(5)), rng.direction(),
                          rng.uniform(0.05f, 0.8f), rng.uniform(0.2f, 3));
    return scene;
}

/// Random rays, a third of them aimed at points on the cylinders.
std::vector<Ray> mixedRays(const Scene& scene, uint32_t n, uint64_t seed) {
    std::vector<Ray> rays = test::makeRandomRays(scene, n, seed);
    test::TestRng rng(seed + 1);
    for (uint32_t i = 0; i < n / 3 && !scene.cylinders.empty(); ++i) {
        const Cylinder& c = scene.cylinders[rng.index(uint32_t(scene.cylinders.size()))];
        const Float phi = 2 * kPi * rng.uniform();
        const Vec3f target = c.base + c.axis * (c.length * rng.uniform()) +
                             (c.xAxis * std::cos(phi) + cross(c.axis, c.xAxis) * std::sin(phi)) *
                                 c.radius;
        Ray r;
        r.o = rng.inBox(Vec3f(-8), Vec3f(8));
        r.d = target - r.o;
        if (rng.uniform() < 0.5f) r.tMax = 1 - 1e-4f;
        rays[i] = r;
    }
    return rays;
}

TEST(CylinderIntersect, BvhAndEmbreeMatchBruteForce) {
    const Scene scene = mixedScene(400, 40, 60, 3);
    const SceneView view = scene.view();
    ASSERT_EQ(view.numPrimitives(), 500u);
    const Bvh bvh = buildBvh(scene);
    const BvhIntersector own{bvh.view(), view};
    const EmbreeScene embree(scene);
    const EmbreeIntersector emb = embree.intersector();
    int agreeOwn = 0, agreeEmbree = 0, cylinderHits = 0;
    const std::vector<Ray> rays = mixedRays(scene, 3000, 4);
    for (const Ray& ray : rays) {
        Hit ref, a, b;
        const bool refHit = test::bruteForceIntersect(view, ray, ref);
        cylinderHits += refHit && ref.primId >= view.firstCylinder();
        const bool ha = own.intersect(ray, a), hb = emb.intersect(ray, b);
        agreeOwn += ha == refHit && own.occluded(ray) == refHit &&
                    (!refHit || (a.primId == ref.primId && a.t == ref.t));
        agreeEmbree += hb == refHit && emb.occluded(ray) == refHit &&
                       (!refHit || (b.primId == ref.primId && std::fabs(b.t - ref.t) <= 1e-5f * ref.t));
    }
    EXPECT_GT(cylinderHits, 500);
    EXPECT_GE(agreeOwn, 2995);     // ties between primitives at the same t may differ
    EXPECT_GE(agreeEmbree, 2985);  // Embree's own triangle test rounds differently
}

TEST(CylinderIntersect, BoundsContainTheSurface) {
    test::TestRng rng(5);
    for (int i = 0; i < 200; ++i) {
        const Cylinder c = makeCylinder(rng.inBox(Vec3f(-2), Vec3f(2)), rng.direction(),
                                        rng.uniform(0.1f, 2), rng.uniform(0.1f, 3));
        const Bounds3f b = cylinderBounds(c);
        for (int k = 0; k < 50; ++k) {
            const Float phi = 2 * kPi * rng.uniform();
            const Vec3f p = c.base + c.axis * (c.length * rng.uniform()) +
                            (c.xAxis * std::cos(phi) + cross(c.axis, c.xAxis) * std::sin(phi)) *
                                c.radius;
            for (int a = 0; a < 3; ++a) {
                EXPECT_GE(p[a], b.lo[a] - 1e-5f);
                EXPECT_LE(p[a], b.hi[a] + 1e-5f);
            }
        }
    }
}

}  // namespace
}  // namespace caustica
