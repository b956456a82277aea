// Parallelogram meshes tested as planes (scene/parallelogram.h, accel/parallelogram_intersect.h)
// by Embree's intersector (EmbreeSceneOptions::directParallelograms) and by the own BVH
// (BvhBuildOptions::directParallelograms): detection, the lane form against the float form bit
// for bit, the plane test against the two triangles' watertight test, and both ray tracers'
// answers with and without the direct test.
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "accel/test_scenes.h"
#include "caustica/accel/bvh.h"
#include "caustica/accel/bvh_traversal.h"
#include "caustica/accel/embree_accel.h"
#include "caustica/accel/parallelogram_intersect.h"

namespace caustica {
namespace {

using test::bitsOf;

/// A few parallelograms of every size and slant, each vertex order.
Scene parallelogramScene(uint64_t seed, int count) {
    Scene scene;
    test::TestRng rng(seed);
    for (int i = 0; i < count; ++i) {
        const Vec3f corner = rng.inBox(Vec3f(-4), Vec3f(4));
        const Vec3f eu = rng.direction() * rng.uniform(0.3f, 3), ev = rng.direction() * rng.uniform(0.3f, 3);
        test::addParallelogram(scene, corner, eu, ev, i % 3);
    }
    return scene;
}

TEST(MeshParallelogram, FindsEveryVertexOrderAndPointsBackToItsCorners) {
    const Scene scene = parallelogramScene(1, 9);
    for (size_t s = 0; s < scene.shapes.size(); ++s) {
        SCOPED_TRACE("shape " + std::to_string(s));
        MeshParallelogram m;
        ASSERT_TRUE(meshParallelogram(scene, scene.shapes[s], m));
        EXPECT_EQ(m.first, scene.shapes[s].primOffset);
        EXPECT_EQ(m.second, scene.shapes[s].primOffset + 1);
        const Vec3u ta = scene.triangles[m.first], tb = scene.triangles[m.second];
        const Vec3f corners[2][3] = {{m.corner, m.corner + m.edgeU, m.corner + m.edgeV},
                                     {m.corner + m.edgeU + m.edgeV, m.corner + m.edgeU, m.corner + m.edgeV}};
        for (int h = 0; h < 2; ++h)
            for (int j = 0; j < 3; ++j) {
                const Vec3u t = h == 0 ? ta : tb;
                const Vec3f p = scene.positions[t[m.slots[h][j]]];
                EXPECT_LE(length(p - corners[h][j]), 1e-5f) << "half " << h << " corner " << j;
            }
    }
}

TEST(MeshParallelogram, RejectsWhatIsNotOne) {
    Scene scene;
    // A kite: two triangles sharing a diagonal whose other corners are not symmetric about it.
    const uint32_t kite = test::addMeshShape(scene, 0, 2);
    test::addTriangle(scene, kite, Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0));
    test::addTriangle(scene, kite, Vec3f(1, 0, 0), Vec3f(2, 2, 0), Vec3f(0, 1, 0));
    // Two triangles sharing one vertex only.
    const uint32_t apart = test::addMeshShape(scene, 2, 2);
    test::addTriangle(scene, apart, Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0));
    test::addTriangle(scene, apart, Vec3f(1, 0, 0), Vec3f(2, 0, 0), Vec3f(2, 1, 0));
    // One triangle, and three.
    const uint32_t one = test::addMeshShape(scene, 4, 1);
    test::addTriangle(scene, one, Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0));
    const uint32_t three = test::addMeshShape(scene, 5, 3);
    for (int i = 0; i < 3; ++i) test::addTriangle(scene, three, Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0));
    // A parallelogram folded along its diagonal is still symmetric about it: detected (a sphere
    // shape never is).
    test::addSphere(scene, Vec3f(0), 1);
    MeshParallelogram m;
    for (uint32_t s : {kite, apart, one, three}) EXPECT_FALSE(meshParallelogram(scene, scene.shapes[s], m)) << s;
    EXPECT_FALSE(meshParallelogram(scene, scene.shapes.back(), m));
}

/// Rays at random, aimed at random points of the parallelogram's plane (inside and outside),
/// at its corners and edges exactly, and lying in its plane or parallel to it.
std::vector<Ray> raysAt(const MeshParallelogram& m, test::TestRng& rng, int n) {
    std::vector<Ray> rays;
    const Vec3f normal = normalize(cross(m.edgeU, m.edgeV));
    for (int i = 0; i < n; ++i) {
        const Vec3f o = rng.inBox(Vec3f(-8), Vec3f(8));
        Float u = rng.uniform(-0.2f, 1.2f), v = rng.uniform(-0.2f, 1.2f);
        if (i % 5 == 1) u = Float(rng.index(5)) / 4, v = Float(rng.index(5)) / 4;  // corners, edges, diagonal
        const Vec3f target = m.corner + m.edgeU * u + m.edgeV * v;
        Vec3f d = target - o;
        if (i % 11 == 3) d = d - normal * dot(d, normal);  // parallel to the plane
        Float tMax = i % 7 == 2 ? rng.uniform(0.2f, 1.5f) : kInfinity;
        Vec3f origin = o;
        if (i % 13 == 4) origin = m.corner + m.edgeU * 0.3f + m.edgeV * 0.4f, d = m.edgeU;  // in the plane
        rays.push_back(Ray{origin, d, tMax});
        if (i % 17 == 5) rays.push_back(Ray{o, rng.direction(), kInfinity});
    }
    return rays;
}

#if CA_FLOAT4_SSE
TEST(IntersectParallelogram, FourLanesGiveEachRayTheFloatFormsBits) {
    const Scene scene = parallelogramScene(2, 6);
    test::TestRng rng(3);
    size_t hits = 0, total = 0;
    for (const Shape& shape : scene.shapes) {
        MeshParallelogram m;
        ASSERT_TRUE(meshParallelogram(scene, shape, m));
        const PreparedParallelogram q = prepareParallelogram(m);
        std::vector<Ray> rays = raysAt(m, rng, 2000);
        while (rays.size() % 4 != 0) rays.push_back(rays.front());
        for (size_t i = 0; i < rays.size(); i += 4) {
            const Ray* r = &rays[i];
            const Vec3F4 o = lane::fromLanes(r[0].o, r[1].o, r[2].o, r[3].o);
            const Vec3F4 d = lane::fromLanes(r[0].d, r[1].d, r[2].d, r[3].d);
            const Float4 tMax = Float4::fromLanes(r[0].tMax, r[1].tMax, r[2].tMax, r[3].tMax);
            Float4 t4, u4, v4;
            const uint32_t bits = intersectParallelogram<Float4>(o, d, tMax, q, t4, u4, v4).bits();
            for (int k = 0; k < 4; ++k) {
                Float t, u, v;
                const bool hit = intersectParallelogram<float>(r[k].o, r[k].d, r[k].tMax, q, t, u, v);
                ASSERT_EQ(((bits >> k) & 1u) != 0, hit) << "ray " << i + k;
                ++total;
                if (!hit) continue;
                ++hits;
                EXPECT_EQ(bitsOf(t4[k]), bitsOf(t));
                EXPECT_EQ(bitsOf(u4[k]), bitsOf(u));
                EXPECT_EQ(bitsOf(v4[k]), bitsOf(v));
            }
        }
    }
    EXPECT_GT(hits, total / 4);
    EXPECT_LT(hits, total);
}
#endif

/// Whether barycentrics (b1, b2) lie within `eps` of one of their triangle's edges.
bool nearAnEdge(Float b1, Float b2, Float eps) { return b1 < eps || b2 < eps || 1 - b1 - b2 < eps; }

TEST(IntersectParallelogram, AgreesWithItsTwoTrianglesWatertightTest) {
    const Scene scene = parallelogramScene(4, 6);
    const SceneView view = scene.view();
    test::TestRng rng(5);
    size_t hits = 0, nearEdges = 0, total = 0;
    for (const Shape& shape : scene.shapes) {
        MeshParallelogram m;
        ASSERT_TRUE(meshParallelogram(scene, shape, m));
        const PreparedParallelogram q = prepareParallelogram(m);
        for (const Ray& ray : raysAt(m, rng, 3000)) {
            ++total;
            Hit ref;
            for (uint32_t id : {m.first, m.second}) intersectPrimitive(view, id, ray, ref);
            Float t, u, v;
            const bool hit = intersectParallelogram<float>(ray.o, ray.d, ray.tMax, q, t, u, v);
            // A ray lying in the plane: neither test's answer means anything (a measure-zero set
            // that spawned rays, offset off their surface, never form).
            const Vec3f n = normalize(q.normal);
            if (std::fabs(dot(ray.o - m.corner, n)) <= 1e-5f && std::fabs(dot(normalize(ray.d), n)) <= 1e-6f) continue;
            Hit got;
            if (hit) got.t = t, parallelogramHitTriangle(m, u, v, got.primId, got.b1, got.b2);
            const bool close = (ref.valid() && nearAnEdge(ref.b1, ref.b2, 1e-4f)) ||
                               (hit && nearAnEdge(got.b1, got.b2, 1e-4f));
            if (hit != ref.valid() || (hit && got.primId != ref.primId)) {
                EXPECT_TRUE(close) << "plane test " << hit << " (u " << u << ", v " << v << "), triangles "
                                   << ref.valid() << " (b " << ref.b1 << ", " << ref.b2 << ")";
                ++nearEdges;
                continue;
            }
            if (!hit) continue;
            ++hits;
            // Both tests round; a grazing ray (the plane nearly along it) magnifies that by
            // 1 / cos θ in t and in the hit point.
            const Float grazing = 1 / std::fabs(dot(normalize(ray.d), n));
            EXPECT_NEAR(t, ref.t, 1e-6f * ref.t * (1 + grazing));
            EXPECT_NEAR(got.b1, ref.b1, 1e-5f * (1 + grazing));
            EXPECT_NEAR(got.b2, ref.b2, 1e-5f * (1 + grazing));
            // The barycentrics put the point where the plane test found it.
            const Vec3u tri = scene.triangles[got.primId];
            const Vec3f p = scene.positions[tri.x] * (1 - got.b1 - got.b2) + scene.positions[tri.y] * got.b1 +
                            scene.positions[tri.z] * got.b2;
            EXPECT_LE(length(p - (ray.o + ray.d * t)), 1e-4f * (1 + length(ray.d) * t));
        }
    }
    EXPECT_GT(hits, total / 4);
    // Only rays at an edge may differ: raysAt aims a fifth of them at the quarter points, three
    // quarters of which lie on an edge or the diagonal.
    EXPECT_LT(nearEdges, total / 10);
}

/// Hits of one ray on the same primitive from a plane test (a) and a triangle test (b): t and
/// barycentrics within the rounding both tests allow, magnified by 1 / cos θ for a grazing ray
/// (see AgreesWithItsTwoTrianglesWatertightTest).
void expectCloseHits(const Scene& scene, const Ray& ray, const Hit& ha, const Hit& hb) {
    Float grazing = 0;
    if (ha.primId < scene.triangles.size()) {
        const Vec3u tri = scene.triangles[ha.primId];
        const Vec3f p0 = scene.positions[tri.x];
        const Vec3f n = normalize(cross(scene.positions[tri.y] - p0, scene.positions[tri.z] - p0));
        grazing = 1 / std::fabs(dot(normalize(ray.d), n));
    }
    EXPECT_NEAR(ha.t, hb.t, 1e-6f * hb.t * (1 + grazing));
    EXPECT_NEAR(ha.b1, hb.b1, 1e-5f * (1 + grazing));
    EXPECT_NEAR(ha.b2, hb.b2, 1e-5f * (1 + grazing));
}

/// Triangles, parallelograms, and `spheres` spheres (one: the packets' sphere lanes; more: the
/// per-ray direct tests, under directPrimitives = their count).
Scene mixedScene(uint64_t seed, uint32_t spheres, int parallelograms) {
    Scene scene = test::makeRandomScene(test::sceneOf(400, spheres, seed));
    test::TestRng rng(seed + 7);
    for (int i = 0; i < parallelograms; ++i)
        test::addParallelogram(scene, rng.inBox(Vec3f(-5), Vec3f(5)), rng.direction() * rng.uniform(0.5f, 4),
                               rng.direction() * rng.uniform(0.5f, 4), i % 3);
    return scene;
}

TEST(EmbreeDirectParallelograms, TakesUpToTheLimitAndLeavesTheirTrianglesOut) {
    const Scene scene = mixedScene(6, 1, 5);
    EXPECT_EQ(EmbreeScene(scene).directParallelogramCount(), 5u);
    EmbreeSceneOptions few;
    few.directParallelograms = 4;  // more than the limit: all stay in Embree
    EXPECT_EQ(EmbreeScene(scene, few).directParallelogramCount(), 0u);
    // A ray straight at one parallelogram's middle from in front hits it (scene triangle ids).
    const EmbreeScene embree(scene);
    const EmbreeIntersector it = embree.intersector();
    MeshParallelogram m;
    ASSERT_TRUE(meshParallelogram(scene, scene.shapes.back(), m));
    const Vec3f n = normalize(cross(m.edgeU, m.edgeV));
    const Vec3f middle = m.corner + m.edgeU * 0.25f + m.edgeV * 0.25f;
    Hit hit;
    ASSERT_TRUE(it.intersect(Ray{middle + n * 1e-3f, -n, kInfinity}, hit));
    EXPECT_EQ(hit.primId, m.first);
    EXPECT_NEAR(hit.t, 1e-3f, 1e-6f);
}

/// Embree with the parallelograms tested directly against Embree with all of them as triangles:
/// the same hits (primitive, t, barycentrics, occlusion) except for rays at an edge.
TEST(EmbreeDirectParallelograms, AnswerAsTheirTrianglesInEmbree) {
    for (uint32_t spheres : {0u, 1u, 3u}) {
        SCOPED_TRACE(std::to_string(spheres) + " spheres");
        const Scene scene = mixedScene(8 + spheres, spheres, 12);
        EmbreeSceneOptions direct, triangles;
        direct.directPrimitives = spheres;
        triangles.directPrimitives = spheres;
        triangles.directParallelograms = 0;
        const EmbreeScene a(scene, direct), b(scene, triangles);
        ASSERT_EQ(a.directParallelogramCount(), 12u);
        ASSERT_EQ(b.directParallelogramCount(), 0u);
        const EmbreeIntersector ia = a.intersector(), ib = b.intersector();
        const std::vector<Ray> rays = test::makeRandomRays(scene, 4000, 9 + spheres);
        size_t hits = 0, differ = 0;
        for (const Ray& ray : rays) {
            Hit ha, hb;
            const bool fa = ia.intersect(ray, ha), fb = ib.intersect(ray, hb);
            const bool sameHit = fa == fb && (!fa || ha.primId == hb.primId);
            if (!sameHit || ia.occluded(ray) != ib.occluded(ray)) {
                const bool edge = (fa && ha.primId < scene.triangles.size() && nearAnEdge(ha.b1, ha.b2, 1e-4f)) ||
                                  (fb && hb.primId < scene.triangles.size() && nearAnEdge(hb.b1, hb.b2, 1e-4f));
                EXPECT_TRUE(edge) << "different answers away from any edge";
                ++differ;
                continue;
            }
            if (!fa) continue;
            ++hits;
            expectCloseHits(scene, ray, ha, hb);
        }
        EXPECT_GT(hits, rays.size() / 4);
        EXPECT_LT(differ, rays.size() / 200);
    }
}

TEST(BvhDirectParallelograms, TakesUpToTheLimitAndLeavesTheirTrianglesOut) {
    const Scene scene = mixedScene(6, 1, 5);
    const Bvh bvh = buildBvh(scene);
    ASSERT_EQ(bvh.quads.size(), 5u);
    EXPECT_EQ(bvh.stats.directParallelograms, 5u);
    EXPECT_EQ(bvh.primIndices.size(), size_t(scene.numPrimitives()) - 10);
    for (const ParallelogramPlane& q : bvh.quads)
        for (uint32_t id : bvh.primIndices) ASSERT_TRUE(id != q.mesh.first && id != q.mesh.second);
    BvhBuildOptions few;
    few.directParallelograms = 4;  // more than the limit: all stay in the tree
    const Bvh all = buildBvh(scene, few);
    EXPECT_TRUE(all.quads.empty());
    EXPECT_EQ(all.primIndices.size(), size_t(scene.numPrimitives()));
}

TEST(BvhDirectParallelograms, ASceneOfParallelogramsAloneNeedsNoTree) {
    Scene scene;
    test::addParallelogram(scene, Vec3f(-1, -1, 0), Vec3f(2, 0, 0), Vec3f(0, 2, 0));
    test::addParallelogram(scene, Vec3f(-1, -1, 2), Vec3f(2, 0, 0), Vec3f(0, 2, 0));
    const Bvh bvh = buildBvh(scene);
    EXPECT_TRUE(bvh.nodes.empty());
    ASSERT_EQ(bvh.quads.size(), 2u);
    Hit hit;
    ASSERT_TRUE(bvhIntersect(bvh.view(), scene.view(), Ray{Vec3f(0.3f, 0.2f, 5), Vec3f(0, 0, -1), kInfinity}, hit));
    EXPECT_FLOAT_EQ(hit.t, 3);
    EXPECT_TRUE(hit.primId == 2 || hit.primId == 3);  // the nearer one, at z = 2
    EXPECT_TRUE(bvhOccluded(bvh.view(), scene.view(), Ray{Vec3f(0.3f, 0.2f, 5), Vec3f(0, 0, -1), 3.5f}));
    EXPECT_FALSE(bvhOccluded(bvh.view(), scene.view(), Ray{Vec3f(0.3f, 0.2f, 5), Vec3f(0, 0, -1), 2.5f}));
    EXPECT_FALSE(bvhIntersect(bvh.view(), scene.view(), Ray{Vec3f(3, 0, 5), Vec3f(0, 0, -1), kInfinity}, hit));
}

/// One traversal of the own BVH with the parallelograms tested as planes against the same tree
/// with all of them as triangles: the same hits (primitive, t, barycentrics, occlusion) except
/// for rays at an edge; and where the nearest hit is a parallelogram, Embree's intersector (which
/// tests them the same way) gives the same bits.
template <BvhTraversal Traversal>
void checkBvhAgainstItsTriangles() {
    for (uint32_t spheres : {0u, 1u, 3u}) {
        SCOPED_TRACE(std::to_string(spheres) + " spheres");
        const Scene scene = mixedScene(8 + spheres, spheres, 12);
        BvhBuildOptions direct, triangles;
        direct.directParallelograms = 12;
        triangles.directParallelograms = 0;
        const Bvh a = buildBvh(scene, direct), b = buildBvh(scene, triangles);
        ASSERT_EQ(a.quads.size(), 12u);
        ASSERT_TRUE(b.quads.empty());
        EmbreeSceneOptions embreeOptions;
        embreeOptions.directPrimitives = spheres;
        const EmbreeScene embree(scene, embreeOptions);
        const EmbreeIntersector ie = embree.intersector();
        const std::vector<Ray> rays = test::makeRandomRays(scene, 4000, 9 + spheres);
        size_t hits = 0, quadHits = 0, differ = 0;
        for (const Ray& ray : rays) {
            Hit ha, hb;
            const bool fa = bvhIntersect<Traversal>(a.view(), scene.view(), ray, ha);
            const bool fb = bvhIntersect<Traversal>(b.view(), scene.view(), ray, hb);
            const bool oa = bvhOccluded<Traversal>(a.view(), scene.view(), ray);
            const bool sameHit = fa == fb && (!fa || ha.primId == hb.primId);
            if (!sameHit || oa != bvhOccluded<Traversal>(b.view(), scene.view(), ray)) {
                const bool edge = (fa && ha.primId < scene.triangles.size() && nearAnEdge(ha.b1, ha.b2, 1e-4f)) ||
                                  (fb && hb.primId < scene.triangles.size() && nearAnEdge(hb.b1, hb.b2, 1e-4f));
                EXPECT_TRUE(edge) << "different answers away from any edge";
                ++differ;
                continue;
            }
            EXPECT_EQ(oa, fa);  // something blocks the ray exactly when it has a closest hit
            if (!fa) continue;
            ++hits;
            bool onQuad = false;
            for (const ParallelogramPlane& q : a.quads) onQuad = onQuad || ha.primId == q.mesh.first || ha.primId == q.mesh.second;
            if (onQuad) {
                ++quadHits;
                Hit he;
                ASSERT_TRUE(ie.intersect(ray, he));
                EXPECT_EQ(he.primId, ha.primId);
                EXPECT_EQ(bitsOf(he.t), bitsOf(ha.t));
                EXPECT_EQ(bitsOf(he.b1), bitsOf(ha.b1));
                EXPECT_EQ(bitsOf(he.b2), bitsOf(ha.b2));
            }
            expectCloseHits(scene, ray, ha, hb);
        }
        EXPECT_GT(hits, rays.size() / 4);
        EXPECT_GT(quadHits, rays.size() / 40);
        EXPECT_LT(differ, rays.size() / 200);
    }
}

TEST(BvhDirectParallelograms, AnswerAsTheirTrianglesInTheTree) { checkBvhAgainstItsTriangles<BvhTraversal::Stack>(); }
TEST(BvhDirectParallelograms, AnswerAsTheirTrianglesShortStack) {
    checkBvhAgainstItsTriangles<BvhTraversal::ShortStack>();
}
TEST(BvhDirectParallelograms, AnswerAsTheirTrianglesStackless) {
    checkBvhAgainstItsTriangles<BvhTraversal::Stackless>();
}

}  // namespace
}  // namespace caustica
