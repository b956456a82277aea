// The wavefront driver and the megakernel run the same step functions (path_kernel.h): on a small
// scene built in code (diffuse box open to an environment, area and point lights, glass and metal
// spheres) every sample of a pass must be bit-identical between the two, for both ray-tracing
// backends, for the max_depth / rr_depth / hide_emitters variants, for any chunking of the pass
// and any thread count, and both must count the same rays; and so on a box lit only by
// rectangles, where the CPU wavefront shades diffuse vertices four at a time.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <cstring>
#include <vector>

#include "caustica/accel/accel.h"
#include "caustica/integrators/pass_driver.h"
#include "integrators/path_settings_variants.h"
#include "integrators/rectangle_lit_scene.h"
#include "scene/scene_builder.h"

namespace caustica::test {
namespace {

/// A box x, y in [-1, 1], z in [0, 4], open towards the camera (at the origin, looking along +z)
/// and through a hole in its back wall, lit by a ceiling area light, a point light and a constant
/// environment; a glass and a metal sphere stand on the floor.
Scene makeTestScene(int size) {
    Scene scene;
    Bsdf white, red, glass, metal, sides;
    red.reflectance = Spectrum(0.6f, 0.1f, 0.1f);
    glass.type = BsdfType::Dielectric;
    metal.type = BsdfType::Conductor;
    metal.eta = Spectrum(0.2f, 0.9f, 1.1f);
    metal.k = Spectrum(3.9f, 2.4f, 2.2f);
    sides.type = BsdfType::TwoSided;
    sides.front = sides.back = 0;
    scene.bsdfs = {white, red, glass, metal, sides};
    auto rect = [&](Vec3f o, Vec3f u, Vec3f v, uint32_t bsdf) {
        RectMesh r(o, u, v);
        uint32_t shape = addMesh(scene, r.positions, r.triangles);
        scene.shapes[shape].bsdf = bsdf;
        return shape;
    };
    rect({-1, -1, 0}, {2, 0, 0}, {0, 0, 4}, 4);                   // floor
    rect({-1, 1, 0}, {0, 0, 4}, {2, 0, 0}, 4);                    // ceiling
    rect({-1, -1, 0}, {0, 2, 0}, {0, 0, 4}, 1);                   // left wall (red, one-sided)
    rect({1, -1, 0}, {0, 0, 4}, {0, 2, 0}, 4);                    // right wall
    rect({-1, -1, 4}, {2, 0, 0}, {0, 1.2f, 0}, 4);                // back wall, lower part
    const uint32_t light = rect({-0.3f, 0.99f, 1.7f}, {0.6f, 0, 0}, {0, 0, 0.6f}, 4);
    addAreaLight(scene, light, Spectrum(8, 7, 6));
    scene.shapes[addSphere(scene, {0.35f, -0.6f, 2.4f}, 0.4f)].bsdf = 2;
    scene.shapes[addSphere(scene, {-0.45f, -0.7f, 3.0f}, 0.3f)].bsdf = 3;
    addPointLight(scene, {0.5f, 0.5f, 3.0f}, Spectrum(0.5f));
    addConstantLight(scene, Spectrum(0.3f, 0.4f, 0.6f));
    finalizeLights(scene);
    setTestCamera(scene, size, size);
    return scene;
}

struct PassResult {
    std::vector<PixelSample> samples;
    uint64_t rays = 0;
};

PassResult render(const Scene& scene, const Accel& accel, const PathSettings& settings,
                  bool wavefront, size_t chunk = kWavefrontMaxPaths, int threads = 0) {
    SamplePass pass(scene.film.width, scene.film.height, 3);
    PassResult r;
    auto run = [&] {
        const auto driver = makePathPass<CpuExec>(scene, accel, settings,
                                         wavefront ? PathMode::Wavefront : PathMode::Megakernel, chunk);
        r.rays = driver->render(17, 5, pass);
    };
    if (threads > 0) {
        tbb::task_arena(threads).execute(run);
    } else {
        run();
    }
    r.samples = pass.samples;
    return r;
}

bool sameBits(const PassResult& a, const PassResult& b) {
    const size_t bytes = a.samples.size() * sizeof(PixelSample);
    return a.samples.size() == b.samples.size() &&
           std::memcmp(a.samples.data(), b.samples.data(), bytes) == 0;
}

double totalRadiance(const PassResult& r) {
    double sum = 0;
    for (const PixelSample& s : r.samples) sum += double(s.L.r) + s.L.g + s.L.b;
    return sum;
}

/// Every sample of the wavefront equals the megakernel's, for both backends and every settings
/// variant, and so does the number of rays.
void expectEverySampleOfTheMegakernel(const Scene& scene) {
    for (AccelKind kind : {AccelKind::Embree, AccelKind::Bvh}) {
        const Accel accel(scene, kind);
        for (const PathSettings& settings : pathSettingsVariants()) {
            PassResult mega = render(scene, accel, settings, false);
            PassResult wave = render(scene, accel, settings, true);
            EXPECT_TRUE(sameBits(mega, wave)) << accelKindName(kind) << " max_depth "
                                              << settings.maxDepth << " rr_depth "
                                              << settings.rrDepth;
            EXPECT_EQ(mega.rays, wave.rays);
            if (settings.maxDepth == 0) {
                EXPECT_EQ(totalRadiance(wave), 0.0);
                EXPECT_EQ(wave.rays, 0u);
            } else {
                EXPECT_GT(totalRadiance(wave), 0.0);
            }
        }
    }
}

TEST(Wavefront, EverySampleEqualsTheMegakernels) { expectEverySampleOfTheMegakernel(makeTestScene(20)); }

TEST(Wavefront, ChunkingAndThreadCountDoNotChangeTheSamples) {
    const Scene scene = makeTestScene(16);
    const Accel accel(scene, AccelKind::Bvh);
    const PathSettings settings;
    PassResult whole = render(scene, accel, settings, true, kWavefrontMaxPaths, 1);
    for (size_t chunk : {size_t(1), size_t(37), size_t(256)}) {
        PassResult chunked = render(scene, accel, settings, true, chunk, 2);
        EXPECT_TRUE(sameBits(whole, chunked)) << "chunk " << chunk;
        EXPECT_EQ(whole.rays, chunked.rays);
    }
    EXPECT_TRUE(sameBits(whole, render(scene, accel, settings, true, kWavefrontMaxPaths, 2)));
}

TEST(Wavefront, ManyChunksOnTwoThreadsEqualTheMegakernel) {
    // More samples than one CPU chunk holds: chunks traced by both threads at once.
    const Scene scene = makeTestScene(48);
    const Accel accel(scene, AccelKind::Embree);
    const PathSettings settings;
    PassResult mega = render(scene, accel, settings, false, kWavefrontMaxPaths, 2);
    PassResult wave = render(scene, accel, settings, true, kWavefrontMaxPaths, 2);
    EXPECT_TRUE(sameBits(mega, wave));
    EXPECT_EQ(mega.rays, wave.rays);
}

TEST(Wavefront, ShadingFourPathsAtATimeKeepsEverySample) {
    // Lights that are all rectangles: a CPU thread's shade stage takes the diffuse vertices four
    // at a time (shade_lanes.h); the megakernel shades every path alone.
    // Twosided walls too (the lanes resolve them as the scalar path does).
    for (const bool twoSided : {false, true}) {
        SCOPED_TRACE(twoSided ? "twosided walls" : "one-sided walls");
        const Scene scene = makeRectangleLitScene(20, twoSided);
        expectEverySampleOfTheMegakernel(scene);
        const Accel accel(scene, AccelKind::Embree);
        const PathSettings settings;
        EXPECT_TRUE(sameBits(render(scene, accel, settings, false), render(scene, accel, settings, true, 37, 2)))
            << "chunks of 37 paths on two threads";
    }
}

TEST(Wavefront, ReportsItsMemoryPerPath) {
    EXPECT_GE(wavefrontBytesPerPath(), sizeof(PathState) + sizeof(ShadowRay));
    EXPECT_LE(wavefrontBytesPerPath(), 256u);
}

}  // namespace
}  // namespace caustica::test
