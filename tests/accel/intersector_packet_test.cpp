// Packet queries (intersectPacket / occludedPacket, intersector.h) against the single-ray queries of
// the same intersector: Embree's rtcIntersect16/8/4 and rtcOccluded16/8/4, and the own BVH's loop.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "accel/test_scenes.h"
#include "caustica/accel/intersector.h"

namespace caustica {
namespace {

using test::bitsOf;

/// Triangles, spheres and cylinders (Embree's user geometry: more than directPrimitives).
Scene mixedScene(uint64_t seed) {
    Scene scene = test::makeRandomScene(test::sceneOf(1500, 200, seed));
    test::TestRng rng(seed + 100);
    for (int i = 0; i < 40; ++i)
        test::addCylinder(scene, rng.inBox(Vec3f(-5), Vec3f(5)), rng.direction(), rng.uniform(0.05f, 0.8f),
                          rng.uniform(0.2f, 3));
    return scene;
}

/// Random rays (hits, misses, shadow rays, cut-offs) and the edge cases: tMax 0, a negative and a
/// NaN tMax, a zero direction, tMax exactly at a hit's t (open interval) and just beyond it.
std::vector<Ray> packetRays(const Scene& scene, const EmbreeIntersector& single, uint32_t n, uint64_t seed) {
    std::vector<Ray> rays = test::makeRandomRays(scene, n, seed);
    const size_t random = rays.size();
    for (size_t i = 0; i < random; i += 7) {
        Ray r = rays[i];
        Hit hit;
        if (single.intersect(Ray{r.o, r.d, kInfinity}, hit)) {
            rays.push_back(Ray{r.o, r.d, hit.t});
            rays.push_back(Ray{r.o, r.d, hit.t * (1 + 1e-6f)});
        }
        r.tMax = (i % 3 == 0) ? 0.0f : (i % 3 == 1) ? -1.0f : std::nanf("");
        rays.push_back(r);
        rays.push_back(Ray{r.o, Vec3f(0), kInfinity});
    }
    test::TestRng rng(seed);  // shuffle the edge cases in among the random rays
    for (size_t i = rays.size(); i > 1; --i) std::swap(rays[i - 1], rays[rng.index(uint32_t(i))]);
    return rays;
}

/// Every packet answer equals the single-ray answer bit for bit: hit or miss, t, primitive,
/// barycentrics, occlusion. Packets of every size 1..16 in turn, so every lane count occurs,
/// the last packet partial. `coherent`: the closest-hit queries carry the coherence hint.
template <class I>
void expectPacketsEqualSingleRays(const I& accel, const std::vector<Ray>& rays, bool coherent = false) {
    size_t hits = 0, misses = 0;
    for (size_t first = 0, size = 1; first < rays.size(); first += size, size = size % 16 + 1) {
        const int m = int(std::min(size, rays.size() - first));
        const Ray* ptrs[16];
        Hit got[16];
        Hit* hitPtrs[16];
        uint32_t found[16], occluded[16];
        for (int k = 0; k < m; ++k) {
            ptrs[k] = &rays[first + k];
            got[k].t = -7;  // must be overwritten, also on a miss
            hitPtrs[k] = &got[k];
        }
        intersectPacket(accel, m, ptrs, hitPtrs, found, coherent);
        occludedPacket(accel, m, ptrs, occluded);
        for (int k = 0; k < m; ++k) {
            const Ray& ray = rays[first + k];
            SCOPED_TRACE("ray " + std::to_string(first + k) + " tMax " + std::to_string(ray.tMax));
            Hit ref{};
            const bool refFound = accel.intersect(ray, ref);
            ASSERT_EQ(found[k] != 0, refFound);
            EXPECT_EQ(bitsOf(got[k].t), bitsOf(ref.t));
            EXPECT_EQ(got[k].primId, ref.primId);
            EXPECT_EQ(bitsOf(got[k].b1), bitsOf(ref.b1));
            EXPECT_EQ(bitsOf(got[k].b2), bitsOf(ref.b2));
            EXPECT_EQ(occluded[k] != 0, accel.occluded(ray));
            (refFound ? hits : misses) += 1;
        }
    }
    EXPECT_GT(hits, rays.size() / 5);
    EXPECT_GT(misses, rays.size() / 10);
}

/// Embree's scene of `scene` under the instruction-set cap `isa`.
EmbreeScene embreeWithIsa(const Scene& scene, EmbreeIsa isa) {
    EmbreeSceneOptions options;
    options.isa = isa;
    return EmbreeScene(scene, options);
}

/// `it` answering packets of `width` rays per Embree call.
EmbreeIntersector withPacketWidth(EmbreeIntersector it, int width) {
    it.packetWidth = width;
    return it;
}

// With the cap `auto` chooses on this CPU (AVX2 on AMD Zen 3; elsewhere without AVX-512, or where
// AVX-512 lowers the clock, SSE4.2, which is also tested) Embree's packets answer as its single
// rays, to the bit: what makes the wavefront's image the megakernel's (embree_isa.h; Embree's AVX2
// kernels did not on an Intel CPU capped at AVX2).
TEST(IntersectorPacket, EmbreePacketsOfEveryWidthEqualSingleRays) {
    const Scene scene = mixedScene(11);
    for (EmbreeIsa isa : {EmbreeIsa::Auto, EmbreeIsa::Sse42}) {
        SCOPED_TRACE(embreeIsaName(isa));
        const EmbreeScene embree = embreeWithIsa(scene, isa);
        const EmbreeIntersector native = embree.intersector();
        const std::vector<Ray> rays = packetRays(scene, native, 3000, 12);
        // Every width up to the native one (16 on an AVX-512 CPU); 1 is the single-ray fallback.
        EXPECT_LE(native.packetWidth, embree.nativePacketWidth());
        for (int width : {16, 8, 4, 1}) {
            if (width > embree.nativePacketWidth()) continue;
            SCOPED_TRACE("packet width " + std::to_string(width));
            const EmbreeIntersector it = withPacketWidth(native, width);
            expectPacketsEqualSingleRays(it, rays);
            SCOPED_TRACE("coherent");
            expectPacketsEqualSingleRays(it, rays, true);
        }
    }
}

/// Bundles of rays as a camera sends them (one origin, directions a few degrees apart: what the
/// wavefront marks coherent), where Embree's coherent mode traverses a packet as one: the same
/// answers as single rays, also with Embree's widest kernels (16-ray packets on a CPU with
/// AVX-512, where `auto` may choose them).
TEST(IntersectorPacket, EmbreeCoherentCameraBundlesEqualSingleRays) {
    const Scene scene = mixedScene(15);
    test::TestRng rng(16);
    std::vector<Ray> rays;
    for (int bundle = 0; bundle < 200; ++bundle) {
        const Vec3f origin = rng.inBox(Vec3f(-8), Vec3f(8));
        const Vec3f axis = rng.direction();
        for (int k = 0; k < 16; ++k)
            rays.push_back(Ray{origin, normalize(axis + rng.direction() * 0.05f), kInfinity});
    }
    for (EmbreeIsa isa : {EmbreeIsa::Auto, EmbreeIsa::Widest}) {
        SCOPED_TRACE(embreeIsaName(isa));
        const EmbreeScene embree = embreeWithIsa(scene, isa);
        const EmbreeIntersector native = embree.intersector();
        for (int width : {16, 8, 4}) {
            if (width > embree.nativePacketWidth()) continue;
            SCOPED_TRACE("packet width " + std::to_string(width));
            const EmbreeIntersector it = withPacketWidth(native, width);
            expectPacketsEqualSingleRays(it, rays, true);
        }
    }
}

TEST(IntersectorPacket, EmbreeSpheresAloneInPackets) {
    // Only user geometry: every lane that hits goes through the sphere callbacks with N > 1.
    const Scene scene = test::makeRandomScene(test::sceneOf(0, 300, 13));
    const EmbreeScene embree(scene);
    expectPacketsEqualSingleRays(embree.intersector(), packetRays(scene, embree.intersector(), 2000, 14));
}

/// One sphere or one cylinder is tested directly before each Embree query
/// (EmbreeSceneOptions::directPrimitives) instead of being Embree's user geometry: the same
/// answers to the bit, single rays and packets of every width, coherent or not. The primitive is
/// large, so that many rays hit it, and beside triangles or alone.
TEST(IntersectorPacket, DirectSphereOrCylinderAnswersAsUserGeometry) {
    Scene withSphere = test::makeRandomScene(test::sceneOf(1500, 0, 21));
    test::addSphere(withSphere, {0.5f, -0.3f, 0.2f}, 2.5f);
    Scene withCylinder = test::makeRandomScene(test::sceneOf(1500, 0, 22));
    test::addCylinder(withCylinder, {-1, -0.5f, 0.3f}, normalize(Vec3f(0.3f, 1, -0.2f)), 2, 3);
    Scene sphereAlone;
    test::addSphere(sphereAlone, {1, 2, 3}, 1.5f);
    const std::pair<const char*, const Scene*> scenes[] = {{"sphere and triangles", &withSphere},
                                                            {"cylinder and triangles", &withCylinder},
                                                            {"sphere alone", &sphereAlone}};
    for (const auto& [name, scene] : scenes) {
        SCOPED_TRACE(name);
        const EmbreeScene direct(*scene);
        EmbreeSceneOptions userOptions;
        userOptions.directPrimitives = 0;
        const EmbreeScene user(*scene, userOptions);
        ASSERT_TRUE(direct.intersector().hasDirectPrimitives());
        ASSERT_FALSE(user.intersector().hasDirectPrimitives());
        const std::vector<Ray> rays = packetRays(*scene, user.intersector(), 3000, 25);
        size_t onPrimitive = 0;
        for (const Ray& ray : rays) {
            Hit got, ref;
            const bool gotFound = direct.intersector().intersect(ray, got);
            ASSERT_EQ(gotFound, user.intersector().intersect(ray, ref));
            EXPECT_EQ(bitsOf(got.t), bitsOf(ref.t));
            EXPECT_EQ(got.primId, ref.primId);
            EXPECT_EQ(bitsOf(got.b1), bitsOf(ref.b1));
            EXPECT_EQ(bitsOf(got.b2), bitsOf(ref.b2));
            EXPECT_EQ(direct.intersector().occluded(ray), user.intersector().occluded(ray));
            onPrimitive += gotFound && got.primId >= scene->triangles.size();
        }
        EXPECT_GT(onPrimitive, 40u);  // not a vacuous comparison
        for (int width : {16, 8, 4, 1}) {
            if (width > direct.nativePacketWidth()) continue;
            SCOPED_TRACE("packet width " + std::to_string(width));
            expectPacketsEqualSingleRays(withPacketWidth(direct.intersector(), width), rays);
            expectPacketsEqualSingleRays(withPacketWidth(direct.intersector(), width), rays, true);
        }
    }
}

/// Parallelogram meshes tested directly (EmbreeSceneOptions::directParallelograms, four lanes at a
/// time in packets) beside triangles and no sphere, one sphere (its lanes) or three (tested ray by
/// ray): packets of every width answer as single rays, to the bit. Alone (no triangle left in
/// Embree) too.
TEST(IntersectorPacket, DirectParallelogramsInPacketsEqualSingleRays) {
    for (uint32_t spheres : {0u, 1u, 3u, 99u}) {
        SCOPED_TRACE(std::to_string(spheres) + " spheres");
        Scene scene = spheres == 99 ? Scene{} : test::makeRandomScene(test::sceneOf(800, spheres, 31 + spheres));
        test::TestRng rng(41 + spheres);
        for (int i = 0; i < 10; ++i)
            test::addParallelogram(scene, rng.inBox(Vec3f(-5), Vec3f(5)), rng.direction() * rng.uniform(1, 5),
                                   rng.direction() * rng.uniform(1, 5), i % 3);
        EmbreeSceneOptions options;
        options.directPrimitives = spheres == 99 ? 0 : spheres;
        const EmbreeScene embree(scene, options);
        ASSERT_EQ(embree.directParallelogramCount(), 10u);
        const std::vector<Ray> rays = packetRays(scene, embree.intersector(), 3000, 43);
        size_t onParallelogram = 0;
        for (const Ray& ray : rays) {
            Hit hit;
            if (embree.intersector().intersect(ray, hit))
                onParallelogram += hit.primId >= scene.triangles.size() - 20 && hit.primId < scene.triangles.size();
        }
        EXPECT_GT(onParallelogram, 100u);  // not a vacuous comparison
        for (int width : {16, 8, 4, 1}) {
            if (width > embree.nativePacketWidth()) continue;
            SCOPED_TRACE("packet width " + std::to_string(width));
            expectPacketsEqualSingleRays(withPacketWidth(embree.intersector(), width), rays);
            expectPacketsEqualSingleRays(withPacketWidth(embree.intersector(), width), rays, true);
        }
    }
}

TEST(IntersectorPacket, EmptyEmbreeSceneAnswersMissesInPackets) {
    const Scene scene;
    const EmbreeScene embree(scene);
    const Ray ray{{0, 0, 0}, {0, 0, 1}, kInfinity};
    const Ray* rays[3] = {&ray, &ray, &ray};
    Hit hits[3];
    Hit* hitPtrs[3] = {&hits[0], &hits[1], &hits[2]};
    uint32_t found[3] = {1, 1, 1}, occluded[3] = {1, 1, 1};
    intersectPacket(embree.intersector(), 3, rays, hitPtrs, found);
    occludedPacket(embree.intersector(), 3, rays, occluded);
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(found[k], 0u);
        EXPECT_EQ(occluded[k], 0u);
        EXPECT_FALSE(hits[k].valid());
    }
}

TEST(IntersectorPacket, OwnBvhPacketIsItsSingleRayLoop) {
    static_assert(rayPacketSize<BvhIntersector>() == 1);
    static_assert(rayPacketSize<EmbreeIntersector>() == 16);
    const Scene scene = mixedScene(15);
    const EmbreeScene embree(scene);  // only to make the edge-case rays
    const Bvh bvh = buildBvh(scene);
    const BvhIntersector it{bvh.view(), scene.view()};
    const std::vector<Ray> rays = packetRays(scene, embree.intersector(), 1000, 16);
    // A packet of one, as the wavefront stages call it.
    for (size_t i = 0; i < rays.size(); ++i) {
        const Ray* ptr = &rays[i];
        Hit got, ref{};
        Hit* hitPtr = &got;
        uint32_t found = 7, occluded = 7;
        intersectPacket(it, 1, &ptr, &hitPtr, &found);
        occludedPacket(it, 1, &ptr, &occluded);
        const bool refFound = it.intersect(rays[i], ref);
        ASSERT_EQ(found, uint32_t(refFound));
        EXPECT_EQ(bitsOf(got.t), bitsOf(ref.t));
        EXPECT_EQ(got.primId, ref.primId);
        EXPECT_EQ(occluded, uint32_t(it.occluded(rays[i])));
    }
}

}  // namespace
}  // namespace caustica
