// Embree reads the Scene's own index and vertex arrays (rtcSetSharedGeometryBuffer) instead of
// copies, and sharing them changes none of its answers.
#include <cmath>
#include <cstring>
#include <vector>

#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include "accel/test_scenes.h"
#include "caustica/accel/bvh.h"
#include "caustica/accel/intersector.h"
#include "caustica/accel/embree_accel.h"

namespace caustica {
namespace {

const void* embreeBuffer(const EmbreeScene& embree, RTCBufferType type) {
    RTCGeometry geom = rtcGetGeometry(embree.intersector().scene, 0);
    return rtcGetGeometryBufferData(geom, type, 0);
}

/// A bumpy 48 x 48 quad terrain (4608 triangles) with a sphere above it.
Scene terrainScene() {
    Scene scene = test::makeTerrain(48, 4, Vec3f(0.5f, -1, 0.25f), 0.6f);
    test::addSphere(scene, {0, 1.5f, 0}, 0.75f);
    return scene;
}

/// The same scene with its positions in a vector without spare capacity.
Scene withExactPositions(const Scene& scene) {
    Scene exact = scene;
    exact.positions = std::vector<Vec3f>(scene.positions.begin(), scene.positions.end());
    return exact;
}

bool sameBits(Float a, Float b) { return std::memcmp(&a, &b, sizeof(Float)) == 0; }

TEST(EmbreeSharedBuffers, GeometryReadsTheScenesArrays) {
    Scene scene = terrainScene();
    reserveVertexPadding(scene);
    ASSERT_TRUE(sharesVertexArray(scene.positions));
    const EmbreeScene embree(scene);
    EXPECT_TRUE(embree.sharesVertices());
    EXPECT_EQ(embreeBuffer(embree, RTC_BUFFER_TYPE_VERTEX), scene.positions.data());
    EXPECT_EQ(embreeBuffer(embree, RTC_BUFFER_TYPE_INDEX), scene.triangles.data());
}

TEST(EmbreeSharedBuffers, CopiesVerticesWithoutSpareCapacity) {
    const Scene scene = withExactPositions(terrainScene());
    if (scene.positions.capacity() != scene.positions.size())
        GTEST_SKIP() << "this standard library over-allocates a range-constructed vector";
    EXPECT_FALSE(sharesVertexArray(scene.positions));
    const EmbreeScene embree(scene);
    EXPECT_FALSE(embree.sharesVertices());
    const void* vertices = embreeBuffer(embree, RTC_BUFFER_TYPE_VERTEX);
    ASSERT_NE(vertices, scene.positions.data());
    EXPECT_EQ(std::memcmp(vertices, scene.positions.data(), scene.positions.size() * sizeof(Vec3f)), 0);
    EXPECT_EQ(embreeBuffer(embree, RTC_BUFFER_TYPE_INDEX), scene.triangles.data());
}

/// Shared and copied vertices give bit-identical hits; both agree with the own BVH on every ray
/// (the same primitive, or a tie at the same distance where a ray meets a shared edge).
TEST(EmbreeSharedBuffers, HitsEqualTheCopiedScenesAndTheOwnBvhs) {
    Scene shared = terrainScene();
    reserveVertexPadding(shared);
    const Scene copied = withExactPositions(shared);
    const EmbreeScene a(shared), b(copied);
    ASSERT_TRUE(a.sharesVertices());
    const Bvh bvh = buildBvh(shared);
    const BvhIntersector own{bvh.view(), shared.view()};
    const EmbreeIntersector ia = a.intersector(), ib = b.intersector();
    uint32_t hits = 0;
    for (const Ray& ray : test::makeRandomRays(shared, 4000, 20)) {
        Hit ha, hb, hc;
        const bool gotA = ia.intersect(ray, ha), gotB = ib.intersect(ray, hb), gotC = own.intersect(ray, hc);
        ASSERT_EQ(gotA, gotB);
        ASSERT_EQ(ia.occluded(ray), ib.occluded(ray));
        ASSERT_EQ(ia.occluded(ray), own.occluded(ray));
        ASSERT_EQ(gotA, gotC);
        if (!gotA) continue;
        ++hits;
        EXPECT_EQ(ha.primId, hb.primId);
        EXPECT_TRUE(sameBits(ha.t, hb.t) && sameBits(ha.b1, hb.b1) && sameBits(ha.b2, hb.b2));
        EXPECT_NEAR(ha.t, hc.t, 1e-4f * ha.t);
        if (ha.primId != hc.primId) {
            EXPECT_NEAR(test::primitiveT(shared.view(), hc.primId, ray), ha.t, 1e-4f * ha.t);
        }
    }
    EXPECT_GT(hits, 1000u);
}

}  // namespace
}  // namespace caustica
