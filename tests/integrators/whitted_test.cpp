// whitted_test.cpp — the Whitted integrator (integrators/whitted) against analytic cases and the
// path tracer:
//  - a diffuse plane lit by a point light, seen through a perfect mirror and a metal one: the
//    mirrored radiance times the conductor's reflectance;
//  - an emitter seen through a glass slab at normal incidence: (1 - F)² Σ_k F^2k over the
//    internal reflections max_depth allows, (1 - F) / (1 + F) unbounded, with hide_emitters too;
//    a slab of very high index whose reflection tree overflows the stack keeps the expectation;
//  - the path tracer with the same max_depth on a scene whose only light paths are specular
//    chains ending in direct light (area and point light): equal within statistical error, and
//    the test rejects whitted with one segment less;
//  - white furnace: glass and mirror spheres in a constant environment;
//  - bit-identical samples with 1 and 2 threads.
// Resume and the command line: tests/e2e/whitted_cli_test.cpp.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/integrators/pass_driver.h"
#include "caustica/scene/fresnel.h"
#include "integrators/sample_stats.h"
#include "scene/scene_builder.h"

namespace caustica::test {
namespace {

uint32_t addRect(Scene& scene, Vec3f o, Vec3f u, Vec3f v, uint32_t bsdf) {
    RectMesh r(o, u, v);
    const uint32_t shape = addMesh(scene, r.positions, r.triangles);
    scene.shapes[shape].bsdf = bsdf;
    return shape;
}

/// An orthographic camera at the origin looking along +z, `halfExtent` wide either side.
void orthographicCamera(Scene& scene, int size, Float halfExtent) {
    scene.camera.type = CameraType::Orthographic;
    scene.camera.width = scene.film.width = size;
    scene.camera.height = scene.film.height = size;
    scene.camera.tanHalfX = scene.camera.tanHalfY = halfExtent;
}

WhittedSettings whitted(int maxDepth, bool hide = false, int rrDepth = 5) {
    WhittedSettings s;
    s.maxDepth = maxDepth;
    s.rrDepth = rrDepth;
    s.hideEmitters = hide;
    return s;
}

SamplePass renderWhitted(const Scene& scene, const Accel& accel, const WhittedSettings& s, int spp,
                         uint64_t seed) {
    SamplePass pass(scene.film.width, scene.film.height, spp);
    makeWhittedPass<CpuExec>(scene, accel, s)->render(seed, 0, pass);
    return pass;
}

/// Mean of every sample of every pixel, per channel.
Spectrum passMean(const SamplePass& pass) {
    double sum[3] = {0, 0, 0};
    for (const PixelSample& s : pass.samples)
        for (int c = 0; c < 3; ++c) sum[c] += s.L[c];
    const double n = double(pass.samples.size());
    return Spectrum(Float(sum[0] / n), Float(sum[1] / n), Float(sum[2] / n));
}

void expectNear(Spectrum got, Spectrum want, double relative, const char* what) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], want[c], relative * std::abs(want[c])) << what << ", channel " << c;
}

// The camera looks along +z at a mirror tilted 45° about x (it reflects +z into +y), which shows
// a white diffuse plane at y = 2 facing it; a point light 1 below that plane lights it at normal
// incidence: the plane's radiance is ρ/π · I / 1². The view is 0.01 wide, so every pixel sees
// the same point to 1e-4.
Scene mirrorScene(const Bsdf& mirror, Spectrum intensity) {
    Scene scene;
    Bsdf plane;
    plane.reflectance = Spectrum(0.5f);
    scene.bsdfs = {plane, mirror};
    addRect(scene, {-1, -1, 4}, {0, 2, 2}, {2, 0, 0},
            1);  // normal (0, 1, -1)/√2, towards the camera
    addRect(scene, {-1, 2, 4}, {2, 0, 0}, {0, 0, 2}, 0);  // normal -y
    addPointLight(scene, {0, 1, 5}, intensity);
    finalizeLights(scene);
    orthographicCamera(scene, 4, 0.005f);
    return scene;
}

TEST(Whitted, MirrorShowsTheLitPlaneTimesTheConductorsReflectance) {
    const Spectrum intensity(1, 2, 3);
    const Spectrum planeRadiance = intensity * (0.5f * kInvPi);
    Bsdf perfect;  // Mitsuba's material "none": η 0, κ 1, F = 1
    perfect.type = BsdfType::Conductor;
    perfect.eta = Spectrum(0);
    perfect.k = Spectrum(1);
    perfect.reflectance = Spectrum(0.8f, 0.6f, 0.4f);
    Bsdf gold = perfect;
    gold.eta = Spectrum(0.2f, 0.9f, 1.1f);
    gold.k = Spectrum(3.9f, 2.4f, 2.2f);
    gold.reflectance = Spectrum(1);
    const Float cos45 = std::sqrt(0.5f);
    for (const auto& [mirror, reflectance] :
         {std::pair{perfect, perfect.reflectance},
          std::pair{gold, fresnelConductor(cos45, gold.eta, gold.k)}}) {
        const Scene scene = mirrorScene(mirror, intensity);
        for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh}) {
            const Accel accel(scene, kind);
            expectNear(passMean(renderWhitted(scene, accel, whitted(-1), 4, 1)),
                       planeRadiance * reflectance, 1e-3, accelKindName(kind));
            // Three segments are needed: camera-mirror, mirror-plane, plane-light.
            EXPECT_TRUE(passMean(renderWhitted(scene, accel, whitted(2), 4, 1)).isBlack());
        }
    }
}

// A slab of glass (index 1.5, faces z = 2 and 2.5) in front of a large emitter (radiance Le at
// z = 4, facing the camera), seen at normal incidence: each face transmits 1 - F, F = 0.04, and
// each internal round trip (two more segments) adds a factor F².
Scene slabScene(Float eta, Spectrum le) {
    Scene scene;
    Bsdf white, glass;
    glass.type = BsdfType::Dielectric;
    glass.reflectance = Spectrum(1);  // specular_reflectance
    glass.etaRatio = eta;
    scene.bsdfs = {white, glass};
    addRect(scene, {-5, -5, 2}, {0, 10, 0}, {10, 0, 0}, 1);     // normal -z
    addRect(scene, {-5, -5, 2.5f}, {10, 0, 0}, {0, 10, 0}, 1);  // normal +z
    addAreaLight(scene, addRect(scene, {-5, -5, 4}, {0, 10, 0}, {10, 0, 0}, 0), le);
    finalizeLights(scene);
    orthographicCamera(scene, 4, 0.5f);
    return scene;
}

double slabTransmittance(double f, int roundTrips) {
    double sum = 0;
    for (int k = 0; k <= roundTrips; ++k) sum += std::pow(f * f, k);
    return (1 - f) * (1 - f) * sum;
}

TEST(Whitted, EmitterThroughAGlassSlabIsAttenuatedByFresnel) {
    const Spectrum le(1, 2, 4);
    const Scene scene = slabScene(1.5f, le);
    const Accel accel(scene, AccelKind::Bvh);
    const double f = std::pow(0.5 / 2.5, 2);
    // Roulette off (rr_depth 1000): every term of the series is traced, none is left to chance.
    for (bool hide : {false, true}) {  // the emitter is not seen directly: hide_emitters keeps it
        for (int depth : {3, 4, 5, 7}) {
            const double t = slabTransmittance(f, (depth - 3) / 2);
            expectNear(passMean(renderWhitted(scene, accel, whitted(depth, hide, 1000), 2, 1)),
                       le * Float(t), 2e-6, "max_depth");
        }
        // Unbounded and without roulette: the whole geometric series, (1 - F) / (1 + F).
        expectNear(passMean(renderWhitted(scene, accel, whitted(-1, hide, 1000), 2, 1)),
                   le * Float((1 - f) / (1 + f)), 2e-6, "unbounded");
    }
    EXPECT_TRUE(passMean(renderWhitted(scene, accel, whitted(2), 2, 1)).isBlack());
}

// Index 20 reflects F = 0.82 at each face: the internal reflections go on long after the
// stack's kWhittedStackSize pending rays are used up; from there one lobe per hit is chosen at
// random, which must keep the expectation (the series summed to max_depth 61, no roulette).
TEST(Whitted, StackOverflowChoosesOneLobeAndKeepsTheExpectation) {
    const Spectrum le(1);
    const Scene scene = slabScene(20, le);
    const Accel accel(scene, AccelKind::Bvh);
    const double f = std::pow(19.0 / 21.0, 2);
    const SamplePass pass = renderWhitted(scene, accel, whitted(61, false, 1000), 256, 3);
    const PixelStats stats = statsOf(pass);
    const double want = slabTransmittance(f, 29);
    const double z = (stats.imageMean - want) / std::sqrt(stats.imageVarOfMean);
    std::printf("slab of index 20: whitted %.5f, analytic %.5f, z %.2f\n", stats.imageMean, want,
                z);
    EXPECT_GT(stats.imageVarOfMean, 0) << "the stack must have overflowed (random lobe choices)";
    EXPECT_LT(std::abs(z), 4);
}

// Specular chains ending in direct light only: the camera looks through a large glass slab
// (z = 1 and 1.3) at a diffuse wall (z = 4) lit by an area light (z = 3, facing the wall, its
// back to the camera, black so that it reflects nothing) and a point light. The wall sees only
// the slab's back face, whose reflections towards the wall hit the wall or the back of the
// light; so every path of at most 5 segments that carries light is camera → slab chain → wall →
// light, which both integrators compute.
Scene specularDirectScene(int size) {
    Scene scene;
    Bsdf wall, glass, black;
    wall.reflectance = Spectrum(0.7f, 0.6f, 0.5f);
    glass.type = BsdfType::Dielectric;
    glass.reflectance = Spectrum(1);  // specular_reflectance
    black.reflectance = Spectrum(0);
    scene.bsdfs = {wall, glass, black};
    addRect(scene, {-10, -10, 1}, {0, 20, 0}, {20, 0, 0}, 1);     // normal -z
    addRect(scene, {-10, -10, 1.3f}, {20, 0, 0}, {0, 20, 0}, 1);  // normal +z
    addRect(scene, {-3, -3, 4}, {0, 6, 0}, {6, 0, 0}, 0);         // normal -z
    addAreaLight(scene, addRect(scene, {0.5f, 0.5f, 3}, {0.6f, 0, 0}, {0, 0.6f, 0}, 2),
                 Spectrum(8, 7, 6));
    addPointLight(scene, {-0.8f, -0.5f, 3.5f}, Spectrum(0.5f));
    finalizeLights(scene);
    scene.camera.width = scene.film.width = size;
    scene.camera.height = scene.film.height = size;
    scene.camera.tanHalfX = scene.camera.tanHalfY = 0.5f;
    return scene;
}

TEST(Whitted, EqualsThePathTracerOnSpecularChainsEndingInDirectLight) {
    const Scene scene = specularDirectScene(16);
    const Accel accel(scene, AccelKind::Embree);
    constexpr int kSpp = 256;
    PathSettings path;
    path.maxDepth = 5;
    SamplePass reference(scene.film.width, scene.film.height, kSpp);
    makePathPass<CpuExec>(scene, accel, path, PathMode::Megakernel)->render(1, 0, reference);
    const PixelStats pathStats = statsOf(reference);
    const Agreement same =
        compare(statsOf(renderWhitted(scene, accel, whitted(5), kSpp, 2)), pathStats);
    std::printf("whitted(5) vs path(5): image z %.2f, |z| > 4 in %.3f%% of pixel channels\n",
                same.imageZ, 100 * same.fractionAbove4);
    EXPECT_LT(std::abs(same.imageZ), kMaxImageZ);
    EXPECT_LE(same.fractionAbove4, kMaxFractionAbove4);
    // Without the segment to the light the wall is dark: the same statistics reject it.
    const Agreement wrong =
        compare(statsOf(renderWhitted(scene, accel, whitted(3), kSpp, 2)), pathStats);
    EXPECT_GT(std::abs(wrong.imageZ), kMaxImageZ);
    EXPECT_GT(wrong.fractionAbove4, kMaxFractionAbove4);
}

// White furnace: in a constant environment a glass sphere and a perfect mirror sphere neither gain
// nor lose light (every branch ends in the environment; Fresnel splits and the η² radiance
// scaling in and out cancel), unbounded with roulette from depth 5.
TEST(Whitted, FurnaceGlassAndMirrorSpheresNeitherGainNorLose) {
    Bsdf glass, mirror;
    glass.type = BsdfType::Dielectric;
    glass.reflectance = Spectrum(1);
    mirror.type = BsdfType::Conductor;
    mirror.eta = Spectrum(0);
    mirror.k = Spectrum(1);
    mirror.reflectance = Spectrum(1);
    for (const Bsdf& b : {glass, mirror}) {
        Scene scene;
        scene.bsdfs = {b};
        addSphere(scene, {0, 0, 5}, 1);
        addConstantLight(scene, Spectrum(0.5f));
        finalizeLights(scene);
        orthographicCamera(scene, 8, 0.9f);
        const Accel accel(scene, AccelKind::Bvh);
        const PixelStats stats = statsOf(renderWhitted(scene, accel, whitted(-1), 64, 5));
        EXPECT_NEAR(stats.imageMean, 0.5, 4 * std::sqrt(stats.imageVarOfMean) + 1e-5)
            << (b.type == BsdfType::Dielectric ? "glass" : "mirror");
    }
}

TEST(Whitted, OneAndTwoThreadsGiveBitIdenticalSamples) {
    const Scene scene = specularDirectScene(24);
    const Accel accel(scene, AccelKind::Bvh);
    auto run = [&](int threads) {
        tbb::task_arena arena(threads);
        return arena.execute([&] { return renderWhitted(scene, accel, whitted(-1), 4, 9); });
    };
    const SamplePass one = run(1), two = run(2);
    ASSERT_EQ(one.samples.size(), two.samples.size());
    size_t differing = 0;
    for (size_t i = 0; i < one.samples.size(); ++i)
        for (int c = 0; c < 3; ++c) differing += one.samples[i].L[c] != two.samples[i].L[c];
    EXPECT_EQ(differing, 0u);
    EXPECT_FALSE(passMean(one).isBlack());
}

}  // namespace
}  // namespace caustica::test
