// emitter_boxes_test.cpp — EmitterBoxes (scene/emitter_boxes.h), the conservative "may this ray's
// first hit be an emitter?" test of sppm's emission check, against the full closest-hit answer of
// both intersectors (Embree and the own BVH): on random rays, rays aimed at the emitters and rays
// grazing their edges, every ray whose closest hit is an emitting shape is flagged (no false
// negative), and on rays in random directions most misses are not flagged (the test selects).
// sppm's eye path with the boxes gives bit for bit the radiance and visible point it gives when
// it traces every emission check (EmitterBoxes{}: not usable), on cornell-water and glass-caustic.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>

#include "caustica/accel/accel.h"
#include "caustica/integrators/megakernel_pass.h"
#include "caustica/integrators/sppm/sppm_kernel.h"
#include "caustica/io/scene_loader.h"
#include "caustica/scene/emitter_boxes.h"
#include "scene/scene_builder.h"

namespace caustica {
namespace {

struct Tally {
    size_t emitterHits = 0;  // closest hit on an emitting shape
    size_t flagged = 0;      // mayHitEmitter true
    size_t missed = 0;       // emitter hit but not flagged (must stay 0)
    size_t rays = 0;
};

/// Traces `ray` in full with every intersector and checks the flag against the closest hit.
void check(const Scene& scene, const Accel& accel, const EmitterBoxes& boxes, const Ray& ray, Tally& t) {
    const SceneView view = scene.view();
    const bool flag = boxes.mayHitEmitter(ray);
    accel.visit([&](const auto& intersector) {
        Hit hit;
        const bool emitter = intersector.intersect(ray, hit) && view.shapes[view.shapeOf(hit.primId)].light >= 0;
        ++t.rays;
        t.emitterHits += emitter;
        t.flagged += flag;
        if (emitter && !flag) {
            ++t.missed;
            ADD_FAILURE() << "emitter hit at t " << hit.t << " not flagged: o " << ray.o.x << " " << ray.o.y << " "
                          << ray.o.z << " d " << ray.d.x << " " << ray.d.y << " " << ray.d.z;
        }
    });
}

Vec3f uniformIn(const Bounds3f& b, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0, 1);
    const Vec3f d = b.diagonal();
    return b.lo + Vec3f(d.x * u(rng), d.y * u(rng), d.z * u(rng));
}

Vec3f uniformDirection(std::mt19937& rng) {
    std::normal_distribution<float> g;
    for (;;) {
        const Vec3f d(g(rng), g(rng), g(rng));
        if (length(d) > 1e-3f) return normalize(d);
    }
}

/// Random rays from inside the scene: in uniform directions, towards uniform points of each
/// emitter's box, and towards points on the edges of its box's faces (grazing the emitter's rim).
Tally randomRays(const Scene& scene, AccelKind kind, const EmitterBoxes& boxes, Tally* uniformOnly = nullptr) {
    const Accel accel(scene, kind);
    const Bounds3f all = scene.bounds();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0, 1);
    Tally t;
    for (int i = 0; i < 20000; ++i) {
        const Ray ray{uniformIn(all, rng), uniformDirection(rng), kInfinity};
        check(scene, accel, boxes, ray, t);
        if (uniformOnly) check(scene, accel, boxes, ray, *uniformOnly);
    }
    for (size_t s = 0; s < scene.shapes.size(); ++s) {
        if (scene.shapes[s].light < 0) continue;
        Bounds3f b;
        for (uint32_t p = 0; p < scene.view().numPrimitives(); ++p)
            if (scene.view().shapeOf(p) == s) b.extend(scene.primitiveBounds(p));
        for (int i = 0; i < 20000; ++i) {
            Vec3f target = uniformIn(b, rng);
            if (i % 2) {  // snap two coordinates to the box's faces: its edges
                const int keep = int(u(rng) * 3) % 3;
                for (int a = 0; a < 3; ++a) {
                    if (a == keep) continue;
                    float& c = a == 0 ? target.x : (a == 1 ? target.y : target.z);
                    c = u(rng) < 0.5f ? (a == 0 ? b.lo.x : (a == 1 ? b.lo.y : b.lo.z))
                                      : (a == 0 ? b.hi.x : (a == 1 ? b.hi.y : b.hi.z));
                }
            }
            const Vec3f o = uniformIn(all, rng);
            if (length(target - o) < 1e-3f) continue;
            check(scene, accel, boxes, Ray{o, target - o, kInfinity}, t);
        }
    }
    return t;
}

TEST(EmitterBoxes, CornellWaterNeverMissesTheLightAndSelects) {
    const Scene scene = loadScene(std::string(CAUSTICA_SOURCE_DIR) + "/scenes/cornell-water/scene.xml",
                                  {{"width", "16"}, {"height", "16"}});
    const EmitterBoxes boxes = buildEmitterBoxes(scene);
    ASSERT_TRUE(boxes.usable);
    EXPECT_EQ(boxes.count, 1u);
    for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh}) {
        Tally uniform;
        const Tally t = randomRays(scene, kind, boxes, &uniform);
        EXPECT_EQ(t.missed, 0u);
        EXPECT_GT(t.emitterHits, 1000u);  // the aimed rays do reach the light
        // Rays in uniform directions: the small ceiling light's box is met by few of them.
        EXPECT_LT(uniform.flagged, uniform.rays / 10);
        EXPECT_GE(uniform.flagged, uniform.emitterHits);
    }
}

TEST(EmitterBoxes, SpheresCylindersAndMeshesAmongBlockers) {
    Scene scene;
    const test::RectMesh quad(Vec3f(-1, 2, -1), Vec3f(2, 0, 0), Vec3f(0, 0, 2));
    test::addAreaLight(scene, test::addMesh(scene, quad.positions, quad.triangles), Spectrum(1.0f));
    test::addAreaLight(scene, test::addSphere(scene, Vec3f(2, 0, 0), 0.3f), Spectrum(2.0f));
    test::addAreaLight(scene, test::addCylinder(scene, Vec3f(-2, -1, 0), Vec3f(0.3f, 1, 0.2f), 0.2f, 1.5f), Spectrum(3.0f));
    test::addSphere(scene, Vec3f(0, 0.5f, 0), 0.7f);  // blockers, not emitting
    const test::RectMesh floor(Vec3f(-4, -2, -4), Vec3f(8, 0, 0), Vec3f(0, 0, 8));
    test::addMesh(scene, floor.positions, floor.triangles);
    finalizeLights(scene);
    const EmitterBoxes boxes = buildEmitterBoxes(scene);
    ASSERT_TRUE(boxes.usable);
    EXPECT_EQ(boxes.count, 3u);
    for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh}) {
        const Tally t = randomRays(scene, kind, boxes);
        EXPECT_EQ(t.missed, 0u);
        EXPECT_GT(t.emitterHits, 10000u);
        EXPECT_LT(t.flagged, t.rays);  // some rays pass every box
    }
}

TEST(EmitterBoxes, RaysPassingEveryBoxAreNotFlagged) {
    Scene scene;
    test::addAreaLight(scene, test::addSphere(scene, Vec3f(0, 0, 0), 1.0f), Spectrum(1.0f));
    finalizeLights(scene);
    const EmitterBoxes boxes = buildEmitterBoxes(scene);
    ASSERT_TRUE(boxes.usable);
    EXPECT_TRUE(boxes.mayHitEmitter(Ray{Vec3f(0, 0, -5), Vec3f(0, 0, 1), kInfinity}));
    EXPECT_FALSE(boxes.mayHitEmitter(Ray{Vec3f(0, 0, -5), Vec3f(0, 0, -1), kInfinity}));     // away from it
    EXPECT_FALSE(boxes.mayHitEmitter(Ray{Vec3f(0, 1.1f, -5), Vec3f(0, 0, 1), kInfinity}));   // parallel, above
    EXPECT_FALSE(boxes.mayHitEmitter(Ray{Vec3f(0, 0, -5), Vec3f(0, 0, 1), 3.5f}));           // ends before it
    EXPECT_TRUE(boxes.mayHitEmitter(Ray{Vec3f(0, 0, 0), Vec3f(1, 0, 0), kInfinity}));        // starts inside
}

TEST(EmitterBoxes, NotUsableWhenMissesFindEmissionOrEmittersAreMany) {
    Scene env;
    test::addAreaLight(env, test::addSphere(env, Vec3f(0), 1.0f), Spectrum(1.0f));
    test::addConstantLight(env, Spectrum(0.5f));
    finalizeLights(env);
    EXPECT_FALSE(buildEmitterBoxes(env).usable);
    EXPECT_TRUE(buildEmitterBoxes(env).mayHitEmitter(Ray{Vec3f(0, 5, 0), Vec3f(0, 1, 0), kInfinity}));

    Scene many;
    for (uint32_t k = 0; k <= EmitterBoxes::kMaxBoxes; ++k)
        test::addAreaLight(many, test::addSphere(many, Vec3f(Float(3 * k), 0, 0), 1.0f), Spectrum(1.0f));
    finalizeLights(many);
    EXPECT_FALSE(buildEmitterBoxes(many).usable);

    Scene none;  // a point light only: no ray can hit an emitter
    test::addSphere(none, Vec3f(0), 1.0f);
    test::addPointLight(none, Vec3f(0, 3, 0), Spectrum(1.0f));
    finalizeLights(none);
    const EmitterBoxes boxes = buildEmitterBoxes(none);
    EXPECT_TRUE(boxes.usable);
    EXPECT_EQ(boxes.count, 0u);
    EXPECT_FALSE(boxes.mayHitEmitter(Ray{Vec3f(0, 5, 0), Vec3f(0, -1, 0), kInfinity}));
}

/// Every pixel's eye path (a few iterations' streams) with and without the boxes.
void expectSameEyePaths(const std::string& name, int res) {
    const Scene scene = loadScene(std::string(CAUSTICA_SOURCE_DIR) + "/scenes/" + name + "/scene.xml",
                                  {{"width", std::to_string(res)}, {"height", std::to_string(res)}});
    const SceneView view = scene.view();
    const EmitterBoxes boxes = buildEmitterBoxes(scene);
    ASSERT_TRUE(boxes.usable) << name;
    PathSettings settings;
    settings.maxDepth = 16;
    for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh}) {
        const Accel accel(scene, kind);
        size_t points = 0, fewerRays = 0;
        accel.visit([&](const auto& intersector) {
            for (uint64_t it = 0; it < 2; ++it)
                for (size_t pixel = 0; pixel < size_t(res) * size_t(res); ++pixel) {
                    CameraSample a = cameraSample(view.camera, pixel, res, it, 1);
                    CameraSample b = a;
                    SppmVisiblePoint va, vb;
                    bool ha = false, hb = false;
                    uint32_t ra = 0, rb = 0;
                    const Spectrum la = sppmEyePath(view, intersector, a.sampler, a.ray, settings, 16, Float(0.1),
                                                    EmitterBoxes{}, va, ha, ra);
                    const Spectrum lb =
                        sppmEyePath(view, intersector, b.sampler, b.ray, settings, 16, Float(0.1), boxes, vb, hb, rb);
                    ASSERT_EQ(std::memcmp(&la, &lb, sizeof(Spectrum)), 0) << name << " pixel " << pixel;
                    ASSERT_EQ(ha, hb) << name << " pixel " << pixel;
                    if (ha) {
                        ASSERT_EQ(std::memcmp(&va.si.p, &vb.si.p, sizeof(Vec3f)), 0);
                        ASSERT_EQ(std::memcmp(&va.beta, &vb.beta, sizeof(Spectrum)), 0);
                        ASSERT_EQ(va.depth, vb.depth);
                        ++points;
                    }
                    EXPECT_LE(rb, ra);
                    fewerRays += rb < ra;
                }
        });
        EXPECT_GT(points, size_t(res) * size_t(res));  // most pixels of both iterations
        EXPECT_GT(fewerRays, points / 2) << name;       // most emission checks skipped
    }
}

TEST(EmitterBoxes, SppmEyePathsEqualThoseThatTraceEveryEmissionCheck) {
    expectSameEyePaths("cornell-water", 48);
    expectSameEyePaths("glass-caustic", 48);
}

}  // namespace
}  // namespace caustica
