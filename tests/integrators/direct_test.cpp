// direct_test.cpp — the direct integrator (integrators/direct) against the path tracer with
// max_depth 2, which computes the same quantity (emission seen directly or after one scattering
// event, emitter and BSDF sampling combined by the power heuristic):
//  - with one sample of each technique both draw the same random numbers in the same order, so
//    every sample must agree up to rounding, and both must trace the same rays;
//  - with other sample counts (Mitsuba's emitter_samples / bsdf_samples) the estimators differ
//    but their expectations agree: per-pixel and image-mean z-tests over independent samples,
//    which must reject the path tracer with one more bounce (so they can fail);
//  - Mitsuba 3's delta-emitter weighting (a point light counted once per emitter sample).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/integrators/pass_driver.h"
#include "caustica/scene/bsdf.h"
#include "caustica/util/error.h"
#include "integrators/sample_stats.h"
#include "scene/scene_builder.h"

namespace caustica::test {
namespace {

/// A box x, y in [-1, 1], z in [0, 4], open towards the camera (at the origin, looking along +z)
/// and through a gap above its back wall to a constant environment; lit by a ceiling area light
/// and a small spherical one (and optionally a point light). On the floor: a glass sphere (delta
/// BSDF), a plastic one (delta + smooth lobes) and a rough metal one; `smoothOnly` makes the
/// first two white (then emitter sampling alone sees everything that one bounce can).
Scene makeScene(int size, bool pointLight, bool onlyPointLight = false, bool smoothOnly = false) {
    Scene scene;
    Bsdf white, glass, metal, sides;
    glass.type = BsdfType::Dielectric;
    metal.type = BsdfType::RoughConductor;
    metal.eta = Spectrum(0.2f, 0.9f, 1.1f);
    metal.k = Spectrum(3.9f, 2.4f, 2.2f);
    metal.alphaU = metal.alphaV = 0.2f;
    sides.type = BsdfType::TwoSided;
    sides.front = sides.back = 0;
    const Bsdf plastic = makePlastic(1.5f, Spectrum(0.7f, 0.2f, 0.1f), Spectrum(1), false);
    scene.bsdfs = {white, glass, metal, sides, plastic};
    auto rect = [&](Vec3f o, Vec3f u, Vec3f v, uint32_t bsdf) {
        RectMesh r(o, u, v);
        const uint32_t shape = addMesh(scene, r.positions, r.triangles);
        scene.shapes[shape].bsdf = bsdf;
        return shape;
    };
    rect({-1, -1, 0}, {2, 0, 0}, {0, 0, 4}, 3);     // floor
    rect({-1, 1, 0}, {0, 0, 4}, {2, 0, 0}, 3);      // ceiling
    rect({-1, -1, 0}, {0, 2, 0}, {0, 0, 4}, 3);     // left wall
    rect({1, -1, 0}, {0, 0, 4}, {0, 2, 0}, 3);      // right wall
    rect({-1, -1, 4}, {2, 0, 0}, {0, 1.2f, 0}, 3);  // back wall, lower part
    if (!onlyPointLight) {
        const uint32_t panel = rect({-0.4f, 0.99f, 1.6f}, {0.8f, 0, 0}, {0, 0, 0.8f}, 0);
        addAreaLight(scene, panel, Spectrum(5, 4.5f, 4));
        const uint32_t bulb = addSphere(scene, {0.6f, 0.6f, 3.2f}, 0.15f);
        addAreaLight(scene, bulb, Spectrum(6, 6, 9));
        addConstantLight(scene, Spectrum(0.3f, 0.4f, 0.6f));
    }
    if (pointLight) addPointLight(scene, {-0.5f, 0.5f, 2.8f}, Spectrum(0.6f));
    scene.shapes[addSphere(scene, {0.35f, -0.6f, 2.4f}, 0.4f)].bsdf = smoothOnly ? 0 : 1;
    scene.shapes[addSphere(scene, {-0.45f, -0.7f, 3.0f}, 0.3f)].bsdf = smoothOnly ? 0 : 4;
    scene.shapes[addSphere(scene, {-0.2f, -0.75f, 1.8f}, 0.25f)].bsdf = 2;
    finalizeLights(scene);
    setTestCamera(scene, size, size);
    return scene;
}

/// The integrator a pass runs: direct or path, with its settings.
struct Integrator {
    bool isDirect = true;
    DirectSettings direct;
    PathSettings path;
};

Integrator direct(int emitterSamples, int bsdfSamples, bool hide = false) {
    Integrator d;
    d.direct.emitterSamples = emitterSamples;
    d.direct.bsdfSamples = bsdfSamples;
    d.direct.hideEmitters = hide;
    return d;
}

Integrator path(int maxDepth, bool hide = false) {
    Integrator d;
    d.isDirect = false;
    d.path.maxDepth = maxDepth;
    d.path.hideEmitters = hide;
    return d;
}

struct Pass {
    SamplePass samples;
    uint64_t rays = 0;
};

Pass render(const Scene& scene, const Accel& accel, const Integrator& integrator, int spp,
            uint64_t seed) {
    Pass p{SamplePass(scene.film.width, scene.film.height, spp), 0};
    p.rays = integrator.isDirect ? makeDirectPass<CpuExec>(scene, accel, integrator.direct)->render(seed, 0, p.samples)
                                 : makePathPass<CpuExec>(scene, accel, integrator.path, PathMode::Megakernel)->render(seed, 0, p.samples);
    return p;
}

TEST(Direct, OneSampleEachEqualsPathOfDepthTwoSampleBySample) {
    const Scene scene = makeScene(24, true);
    for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh}) {
        const Accel accel(scene, kind);
        for (bool hide : {false, true}) {
            const Pass a = render(scene, accel, direct(1, 1, hide), 4, 11);
            const Pass b = render(scene, accel, path(2, hide), 4, 11);
            EXPECT_EQ(a.rays, b.rays);
            size_t differing = 0;
            double total = 0;
            for (size_t i = 0; i < a.samples.samples.size(); ++i) {
                const Spectrum la = a.samples.samples[i].L, lb = b.samples.samples[i].L;
                total += double(la.r) + la.g + la.b;
                for (int c = 0; c < 3; ++c)
                    if (std::abs(la[c] - lb[c]) > 1e-5f * std::max(1.0f, std::abs(lb[c])))
                        ++differing;
            }
            EXPECT_EQ(differing, 0u) << accelKindName(kind) << " hide_emitters " << hide;
            EXPECT_GT(total, 0.0);
        }
    }
}

TEST(Direct, SampleCountsConvergeToPathOfDepthTwo) {
    const Scene scene = makeScene(16, false);
    const Accel accel(scene, AccelKind::Embree);
    constexpr int kSpp = 1024;
    const PixelStats reference = statsOf(render(scene, accel, path(2), kSpp, 1).samples);
    // Without BSDF samples, light reflected or refracted by a delta lobe is never found (as in
    // Mitsuba): that variant is checked on the scene without delta BSDFs.
    const Scene smooth = makeScene(16, false, false, true);
    const Accel smoothAccel(smooth, AccelKind::Embree);
    const PixelStats smoothReference =
        statsOf(render(smooth, smoothAccel, path(2), kSpp, 1).samples);
    for (auto [ne, nb] : {std::pair{3, 0}, std::pair{0, 2}, std::pair{2, 5}, std::pair{4, 1}}) {
        const bool emitterOnly = nb == 0;
        const Agreement r =
            compare(statsOf(render(emitterOnly ? smooth : scene, emitterOnly ? smoothAccel : accel,
                                   direct(ne, nb), kSpp, 2)
                                .samples),
                    emitterOnly ? smoothReference : reference);
        std::printf(
            "direct(%d, %d) vs path(2): image z %.2f, |z| > 4 in %.3f%% of pixel channels\n", ne,
            nb, r.imageZ, 100 * r.fractionAbove4);
        EXPECT_LT(std::abs(r.imageZ), kMaxImageZ)
            << "emitter_samples " << ne << " bsdf_samples " << nb;
        EXPECT_LE(r.fractionAbove4, kMaxFractionAbove4)
            << "emitter_samples " << ne << " bsdf_samples " << nb;
    }
    // The same statistics reject a different integral: one bounce more.
    const Agreement wrong = compare(statsOf(render(scene, accel, direct(2, 5), kSpp, 3).samples),
                                    statsOf(render(scene, accel, path(3), kSpp, 4).samples));
    std::printf("direct(2, 5) vs path(3): image z %.2f, |z| > 4 in %.3f%% of pixel channels\n",
                wrong.imageZ, 100 * wrong.fractionAbove4);
    EXPECT_GT(std::abs(wrong.imageZ), kMaxImageZ);
    EXPECT_GT(wrong.fractionAbove4, kMaxFractionAbove4);
}

// Mitsuba 3.9.1's direct.cpp gives a delta emitter's sample MIS weight 1 without dividing by
// emitter_samples: with n emitter samples a point light counts n times (checked with Mitsuba).
// Lit by a point light alone (BSDF samples never reach it), 3 emitter samples give 3x the image.
TEST(Direct, PointLightCountsOncePerEmitterSampleAsMitsuba) {
    const Scene scene = makeScene(16, true, true);
    const Accel accel(scene, AccelKind::Bvh);
    const Pass one = render(scene, accel, direct(1, 1), 2, 5);
    const Pass three = render(scene, accel, direct(3, 1), 2, 5);
    double sumOne = 0;
    size_t differing = 0;
    for (size_t i = 0; i < one.samples.samples.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const Float a = one.samples.samples[i].L[c], b = three.samples.samples[i].L[c];
            sumOne += a;
            if (std::abs(3 * a - b) > 1e-5f * std::max(1.0f, b)) ++differing;
        }
    EXPECT_GT(sumOne, 0.0);
    EXPECT_EQ(differing, 0u);
}

TEST(Direct, RaysPerSampleAndSettings) {
    const Scene scene = makeScene(8, true);
    const Accel accel(scene, AccelKind::Bvh);
    const Pass p = render(scene, accel, direct(2, 3), 2, 5);
    EXPECT_GT(p.rays, uint64_t(8 * 8 * 2));  // at least one camera ray per sample
    EXPECT_LE(p.rays, uint64_t(8 * 8 * 2 * (1 + 2 + 3)));
}

}  // namespace
}  // namespace caustica::test
