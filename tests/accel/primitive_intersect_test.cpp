// Unit tests of the ray–triangle and ray–sphere tests in primitive_intersect.h.
#include <cmath>

#include <gtest/gtest.h>

#include "accel/test_scenes.h"
#include "caustica/accel/primitive_intersect.h"

namespace caustica {
namespace {

// The triangle (0,0,0), (1,0,0), (0,1,0) in the z = 0 plane.
const Vec3f kP0(0, 0, 0), kP1(1, 0, 0), kP2(0, 1, 0);

bool hitTri(Vec3f o, Vec3f d, Float tMax, Float& t, Float& b1, Float& b2) {
    return intersectTriangle(o, d, tMax, kP0, kP1, kP2, t, b1, b2);
}

TEST(TriangleIntersect, HitReturnsDistanceAndBarycentrics) {
    Float t, b1, b2;
    ASSERT_TRUE(hitTri({0.2f, 0.3f, 2}, {0, 0, -1}, kInfinity, t, b1, b2));
    EXPECT_FLOAT_EQ(t, 2);
    EXPECT_FLOAT_EQ(b1, 0.2f);  // weight of vertex 1 = (1,0,0)
    EXPECT_FLOAT_EQ(b2, 0.3f);  // weight of vertex 2 = (0,1,0)
}

TEST(TriangleIntersect, BothSidesAreHit) {
    Float t, b1, b2;
    ASSERT_TRUE(hitTri({0.25f, 0.25f, -3}, {0, 0, 1}, kInfinity, t, b1, b2));
    EXPECT_FLOAT_EQ(t, 3);
}

TEST(TriangleIntersect, Misses) {
    Float t = -7, b1, b2;
    EXPECT_FALSE(hitTri({0.8f, 0.8f, 1}, {0, 0, -1}, kInfinity, t, b1, b2));   // outside u+v<=1
    EXPECT_FALSE(hitTri({-0.1f, 0.5f, 1}, {0, 0, -1}, kInfinity, t, b1, b2));  // u < 0
    EXPECT_FALSE(hitTri({0.2f, 0.2f, 1}, {0, 0, 1}, kInfinity, t, b1, b2));    // behind
    EXPECT_FALSE(hitTri({0.2f, 0.2f, 1}, {1, 0, 0}, kInfinity, t, b1, b2));    // parallel
    EXPECT_FALSE(hitTri({0.2f, 0.2f, 0}, {1, 0, 0}, kInfinity, t, b1, b2));    // in the plane
    EXPECT_FALSE(hitTri({0.2f, 0.2f, 0}, {0, 0, 1}, kInfinity, t, b1, b2));    // starts on it: t=0
    EXPECT_EQ(t, -7);  // outputs untouched on a miss
}

TEST(TriangleIntersect, EdgesAndVerticesAreInside) {
    Float t, b1, b2;
    EXPECT_TRUE(hitTri({0.5f, 0.5f, 1}, {0, 0, -1}, kInfinity, t, b1, b2));  // hypotenuse
    EXPECT_TRUE(hitTri({0.5f, 0, 1}, {0, 0, -1}, kInfinity, t, b1, b2));     // edge v = 0
    EXPECT_TRUE(hitTri({0, 0, 1}, {0, 0, -1}, kInfinity, t, b1, b2));        // vertex 0
    EXPECT_TRUE(hitTri({1, 0, 1}, {0, 0, -1}, kInfinity, t, b1, b2));        // vertex 1
    EXPECT_FLOAT_EQ(b1, 1);
}

TEST(TriangleIntersect, SharedEdgeOfAQuadIsNotACrack) {
    // Quad (0,0)-(1,1) split along its diagonal; rays crossing the diagonal hit one of the halves.
    const Vec3f a(0, 0, 0), b(1, 0, 0), c(1, 1, 0), d(0, 1, 0);
    test::TestRng rng(3);
    for (int i = 0; i < 2000; ++i) {
        const Float s = rng.uniform();
        const Vec3f target(s, s, 0), o = Vec3f(rng.uniform(-3, 3), rng.uniform(-3, 3), 1.7f);
        Float t, b1, b2;
        const bool h1 = intersectTriangle(o, target - o, kInfinity, a, b, c, t, b1, b2);
        const bool h2 = intersectTriangle(o, target - o, kInfinity, a, c, d, t, b1, b2);
        EXPECT_TRUE(h1 || h2) << "crack at s=" << s;
    }
}

TEST(TriangleIntersect, SharedEdgeOfATiltedQuadIsNotACrack) {
    // Nearly planar quads in random orientations with awkward coordinates, split along the
    // diagonal a-c (both windings; vertex 0 of each half off the diagonal, as in meshes), and rays
    // from one side aimed exactly at float points of the diagonal: the watertight test evaluates
    // the diagonal's edge function identically (up to sign) in both halves, so one of them is
    // always hit. Moeller-Trumbore on edges from vertex 0 (the earlier test) lost 699 of these.
    test::TestRng rng(11);
    int misses = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vec3f center = rng.inBox(Vec3f(-50, -50, -50), Vec3f(50, 50, 50));
        const Vec3f u = normalize(rng.direction()) * rng.uniform(0.01f, 3.0f);
        const Vec3f v = normalize(cross(u, rng.direction())) * rng.uniform(0.01f, 3.0f);
        const Vec3f a = center - u - v, b = center + u - v, c = center + u + v, d = center - u + v;
        const Float s = rng.uniform();
        const Vec3f target = a + (c - a) * s;
        const Vec3f n = normalize(cross(u, v));
        // From above the quad, at least 5 degrees off its plane.
        const Vec3f dir = normalize(normalize(rng.direction()) * 0.9f - n * 1.0f);
        const Vec3f o = target - dir * rng.uniform(0.5f, 20.0f);
        Float t, b1, b2;
        const bool flipped = i % 2 == 1;
        const bool h1 = flipped ? intersectTriangle(o, target - o, kInfinity, b, a, c, t, b1, b2)
                                : intersectTriangle(o, target - o, kInfinity, b, c, a, t, b1, b2);
        const bool h2 = flipped ? intersectTriangle(o, target - o, kInfinity, d, c, a, t, b1, b2)
                                : intersectTriangle(o, target - o, kInfinity, d, a, c, t, b1, b2);
        misses += !(h1 || h2);
    }
    EXPECT_EQ(misses, 0);
}

TEST(TriangleIntersect, RaysThroughAVertexHitItsFan) {
    // A fan of six triangles around an awkward vertex (their vertex 2): rays aimed exactly at it
    // (where every edge function through it is ~0 and the double-precision redo decides) hit the
    // fan. Moeller-Trumbore (the earlier test) let 747 of these through.
    test::TestRng rng(12);
    int misses = 0;
    for (int i = 0; i < 5000; ++i) {
        const Vec3f center = rng.inBox(Vec3f(-20, -20, -20), Vec3f(20, 20, 20));
        const Vec3f n = normalize(rng.direction());
        const Vec3f u = normalize(cross(n, rng.direction())), v = cross(n, u);
        Vec3f rim[6];
        for (int k = 0; k < 6; ++k) {
            const Float phi = Float(k) * 2 * kPi / 6 + rng.uniform(-0.2f, 0.2f);
            rim[k] = center + (u * std::cos(phi) + v * std::sin(phi)) * rng.uniform(0.1f, 2.0f) +
                     n * rng.uniform(-0.002f, 0.002f);  // slopes < 1.2 degrees
        }
        const Vec3f dir = normalize(normalize(rng.direction()) * 0.9f - n * 1.0f);
        const Vec3f o = center - dir * rng.uniform(0.5f, 20.0f);
        bool hit = false;
        for (int k = 0; k < 6; ++k) {
            Float t, b1, b2;
            hit |= intersectTriangle(o, center - o, kInfinity, rim[k], rim[(k + 1) % 6], center, t,
                                     b1, b2);
        }
        misses += !hit;
    }
    EXPECT_EQ(misses, 0);
}

TEST(TriangleIntersect, TMaxIsAnOpenBound) {
    Float t, b1, b2;
    EXPECT_FALSE(hitTri({0.2f, 0.2f, 2}, {0, 0, -1}, 2.0f, t, b1, b2));
    EXPECT_TRUE(hitTri({0.2f, 0.2f, 2}, {0, 0, -1}, std::nextafter(2.0f, 3.0f), t, b1, b2));
    EXPECT_FALSE(hitTri({0.2f, 0.2f, 2}, {0, 0, -1}, 1.5f, t, b1, b2));
}

TEST(TriangleIntersect, NonUnitDirectionScalesT) {
    Float t, b1, b2;
    ASSERT_TRUE(hitTri({0.1f, 0.6f, 4}, {0, 0, -8}, kInfinity, t, b1, b2));
    EXPECT_FLOAT_EQ(t, 0.5f);
    EXPECT_FLOAT_EQ(b1, 0.1f);
    EXPECT_FLOAT_EQ(b2, 0.6f);
    // A shadow ray to a point behind the triangle is blocked before t = 1 - 1e-4.
    const Vec3f o(0.3f, 0.3f, 1), target(0.3f, 0.3f, -1);
    EXPECT_TRUE(hitTri(o, target - o, 1 - 1e-4f, t, b1, b2));
    EXPECT_FLOAT_EQ(t, 0.5f);
}

TEST(TriangleIntersect, ZeroAreaTrianglesAreNeverHit) {
    Float t, b1, b2;
    const Vec3f p(0.5f, 0.5f, 0);
    EXPECT_FALSE(
        intersectTriangle({0.5f, 0.5f, 1}, {0, 0, -1}, kInfinity, p, p, p, t, b1, b2));
    EXPECT_FALSE(intersectTriangle({0, 0, 1}, {0, 0, -1}, kInfinity, kP0, kP1, kP1, t, b1, b2));
    EXPECT_FALSE(intersectTriangle({0.5f, 0, 1}, {0, 0, -1}, kInfinity, kP0, kP1, kP0, t, b1, b2));
    // Collinear vertices, the ray through the segment they span.
    EXPECT_FALSE(intersectTriangle({0.25f, 0, 1}, {0, 0, -1}, kInfinity, kP0, {0.5f, 0, 0}, kP1,
                                   t, b1, b2));
}

TEST(SphereIntersect, HitFromOutsideGivesNearRoot) {
    Float t;
    ASSERT_TRUE(intersectSphere({0, 0, -5}, {0, 0, 1}, kInfinity, {0, 0, 0}, 1, t));
    EXPECT_FLOAT_EQ(t, 4);
    ASSERT_TRUE(intersectSphere({0, 0, -5}, {0, 0, 2}, kInfinity, {0, 0, 0}, 1, t));  // non-unit
    EXPECT_FLOAT_EQ(t, 2);
}

TEST(SphereIntersect, OriginInsideGivesFarRoot) {
    Float t;
    ASSERT_TRUE(intersectSphere({0, 0.5f, 0}, {0, 1, 0}, kInfinity, {0, 0, 0}, 2, t));
    EXPECT_FLOAT_EQ(t, 1.5f);
    ASSERT_TRUE(intersectSphere({0, 0.5f, 0}, {0, -1, 0}, kInfinity, {0, 0, 0}, 2, t));
    EXPECT_FLOAT_EQ(t, 2.5f);
}

TEST(SphereIntersect, MissesBehindAndBeyondTMax) {
    Float t = -7;
    EXPECT_FALSE(intersectSphere({0, 0, -5}, {0, 1, 0}, kInfinity, {0, 0, 0}, 1, t));  // aside
    EXPECT_FALSE(intersectSphere({0, 0, 5}, {0, 0, 1}, kInfinity, {0, 0, 0}, 1, t));   // behind
    EXPECT_FALSE(intersectSphere({0, 0, -5}, {0, 0, 1}, 4.0f, {0, 0, 0}, 1, t));       // open tMax
    EXPECT_FALSE(intersectSphere({0, 1.0001f, -5}, {0, 0, 1}, kInfinity, {0, 0, 0}, 1, t));
    EXPECT_FALSE(intersectSphere({0, 0, -5}, {0, 0, 0}, kInfinity, {0, 0, 0}, 1, t));  // d = 0
    EXPECT_EQ(t, -7);
    EXPECT_TRUE(
        intersectSphere({0, 0, -5}, {0, 0, 1}, std::nextafter(4.0f, 5.0f), {0, 0, 0}, 1, t));
}

TEST(SphereIntersect, PreciseForSmallFarSpheres) {
    // A sphere of radius 0.1 about 1.7e4 units away. The textbook discriminant b^2 - ac cancels
    // catastrophically here (b^2 ~ 3e8 carries no digits of r^2 = 0.01); the robust form hits every
    // ray aimed inside the silhouette, with t within a few ulps of a double-precision reference.
    const Vec3f c(1e4f, 1e4f, 1e4f);
    const Float r = 0.1f;
    const Vec3f o(0, 0, 0);
    test::TestRng rng(11);
    for (int i = 0; i < 200; ++i) {
        const Vec3f target = c + Vec3f(rng.uniform(-0.7f, 0.7f), rng.uniform(-0.7f, 0.7f), 0) * r;
        const Vec3f d = normalize(target - o);
        Float t;
        ASSERT_TRUE(intersectSphere(o, d, kInfinity, c, r, t)) << i;
        const double fx = double(o.x) - c.x, fy = double(o.y) - c.y, fz = double(o.z) - c.z;
        const double a = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
        const double b = fx * d.x + fy * d.y + fz * d.z;
        const double cc = fx * fx + fy * fy + fz * fz - double(r) * r;
        const double tRef = (-b - std::sqrt(b * b - a * cc)) / a;
        const double ulp = std::nextafter(float(tRef), kInfinity) - float(tRef);
        EXPECT_NEAR(t, tRef, 4 * ulp) << i;
    }
}

TEST(IntersectPrimitive, UpdatesOnlyWhenCloser) {
    Scene scene;
    const uint32_t mesh = test::addMeshShape(scene, 0, 1);
    test::addTriangle(scene, mesh, {-1, -1, 0}, {1, -1, 0}, {-1, 1, 0});
    test::addSphere(scene, {0, 0, 5}, 1);
    const SceneView view = scene.view();
    const Ray ray{{-0.5f, -0.5f, 10}, {0, 0, -1}, kInfinity};
    Hit hit;
    ASSERT_TRUE(intersectPrimitive(view, 1, ray, hit));  // sphere first
    EXPECT_EQ(hit.primId, 1u);
    EXPECT_GT(hit.t, 0);
    Hit sphereHit = hit;
    EXPECT_FALSE(intersectPrimitive(view, 0, ray, hit));  // triangle farther: no update
    EXPECT_EQ(hit.primId, sphereHit.primId);
    EXPECT_EQ(hit.t, sphereHit.t);

    Hit fresh;
    ASSERT_TRUE(intersectPrimitive(view, 0, ray, fresh));
    EXPECT_EQ(fresh.primId, 0u);
    EXPECT_FLOAT_EQ(fresh.t, 10);
    EXPECT_FLOAT_EQ(fresh.b1, 0.25f);
    EXPECT_FLOAT_EQ(fresh.b2, 0.25f);

    Ray shortRay = ray;
    shortRay.tMax = 2;  // stops before both
    Hit none;
    EXPECT_FALSE(intersectPrimitive(view, 0, shortRay, none));
    EXPECT_FALSE(intersectPrimitive(view, 1, shortRay, none));
    EXPECT_FALSE(none.valid());
}

}  // namespace
}  // namespace caustica
