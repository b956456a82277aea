// gpu_render_test.cpp — the path tracer on the GPU against the CPU: the same scene, seed and
// sample streams rendered by the one pass driver (pass_driver.h) instantiated for the CPU (own BVH)
// and for the GPU, in both modes. Built only with the CUDA backend (target caustica_gpu_tests, ctest gpu_render); every
// test that needs a GPU skips when cudaGetDeviceCount finds none.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "caustica/accel/accel.h"
#include "caustica/film/film.h"
#include "caustica/film/image_compare.h"
#include "caustica/accel/device_scene.h"
#include "caustica/integrators/pass_driver.h"
#include "caustica/integrators/path/gpu_memory.h"
#include "caustica/integrators/path/path_settings.h"
#include "caustica/io/scene_loader.h"
#include "caustica/parallel/backend.h"
#include "caustica/parallel/buffer.h"
#include "caustica/util/error.h"
#include "common/gpu_test_setup.h"
#include "cuda/cuda_backend.h"

namespace caustica {
namespace {

std::string scenePath(const std::string& name) {
    return std::string(CAUSTICA_SOURCE_DIR) + "/scenes/" + name + "/scene.xml";
}

class GpuRender : public ::testing::Test {
protected:
    void SetUp() override {
        test::skipWithoutGpu("GPU rendering");
    }
};

Scene smallScene(const std::string& name) {
    return loadScene(scenePath(name), {{"width", "48"}, {"height", "36"}});
}

PathSettings pathSettingsOf(const Scene& scene) {
    IntegratorParams params(scene.integrator);
    return readPathSettings(params);
}

/// Renders `spp` samples per pixel in passes of 4 through the film with `driver`.
Image render(const Scene& scene, PassDriver& driver, int spp, uint64_t seed, uint64_t& rays) {
    Film film(scene.film);
    rays = 0;
    for (int first = 0; first < spp; first += 4) {
        SamplePass pass(scene.film.width, scene.film.height, 4);
        rays += driver.render(seed, first, pass);
        film.addPass(pass);
    }
    return film.develop();
}

void expectSameImage(const std::string& name, PathMode mode) {
    const Scene scene = smallScene(name);
    const Accel accel(scene, AccelKind::Bvh);
    uint64_t cpuRays = 0, gpuRays = 0;
    const PathSettings settings = pathSettingsOf(scene);
    const Image cpu = render(scene, *makePathPass<CpuExec>(scene, accel, settings, mode), 16, 7, cpuRays);
    const Image image = render(scene, *makePathPass<GpuExec>(scene, accel, settings, mode), 16, 7, gpuRays);
    const ErrorMetrics m = compareImages(image, cpu);
    // The same random streams: equal up to rounding. FMA contraction on the GPU can flip a rare
    // roulette, edge or total-internal-reflection decision, and one flipped path through the water
    // can put a caustic sample in a dark pixel (a relMSE term in the hundreds), so the bound, far
    // below 16-spp noise, holds without the worst 1% of pixels.
    EXPECT_LT(m.relMse * (1 - m.relMseWorstShare), 1e-3)
        << name << " " << pathModeName(mode) << ": relMSE " << m.relMse << ", worst 1% share " << m.relMseWorstShare;
    const double rayRatio = double(gpuRays) / double(cpuRays);
    EXPECT_NEAR(rayRatio, 1.0, 1e-2) << gpuRays << " vs " << cpuRays;
}

TEST_F(GpuRender, CornellBoxMegakernelMatchesCpu) {
    expectSameImage("cornell-box", PathMode::Megakernel);
}
TEST_F(GpuRender, CornellBoxWavefrontMatchesCpu) {
    expectSameImage("cornell-box", PathMode::Wavefront);
}
TEST_F(GpuRender, CornellWaterMegakernelMatchesCpu) {
    expectSameImage("cornell-water", PathMode::Megakernel);
}
TEST_F(GpuRender, CornellWaterWavefrontMatchesCpu) {
    expectSameImage("cornell-water", PathMode::Wavefront);
}

TEST_F(GpuRender, WavefrontChunksDoNotChangeSamples) {
    // A pass traced in many small chunks of paths gives the same samples as one chunk.
    const Scene scene = smallScene("cornell-box");
    const Accel accel(scene, AccelKind::Bvh);
    const PathSettings settings = pathSettingsOf(scene);
    const auto whole = makePathPass<GpuExec>(scene, accel, settings, PathMode::Wavefront);
    const auto chunked = makePathPass<GpuExec>(scene, accel, settings, PathMode::Wavefront, 1000);
    SamplePass a(scene.film.width, scene.film.height, 2), b(scene.film.width, scene.film.height, 2);
    const uint64_t raysA = whole->render(3, 0, a), raysB = chunked->render(3, 0, b);
    EXPECT_EQ(raysA, raysB);
    for (size_t i = 0; i < a.samples.size(); ++i) {
        ASSERT_EQ(a.samples[i].pos.x, b.samples[i].pos.x) << i;
        ASSERT_EQ(a.samples[i].L.r, b.samples[i].L.r) << i;
    }
}

TEST_F(GpuRender, SceneUploadMatchesEstimateAndTracksPeak) {
    const Scene scene = smallScene("cornell-water");
    const Accel accel(scene, AccelKind::Bvh);
    resetCudaPeakBytes();
    const size_t before = cudaMemoryCounters().current;
    {
        DeviceScene gpuScene(scene, *accel.bvh(), Device::cuda());
        const GpuMemoryEstimate e =
            estimateGpuMemory(gpuRenderSizes(scene, *accel.bvh(), 1, PathMode::Megakernel));
        EXPECT_EQ(gpuScene.bytes(), e.scene + e.bvh);
        EXPECT_EQ(cudaMemoryCounters().current - before, gpuScene.bytes());
        EXPECT_GE(cudaMemoryCounters().peak, gpuScene.bytes());
    }
    EXPECT_EQ(cudaMemoryCounters().current, before);
}

TEST_F(GpuRender, OutOfMemoryIsAnError) {
    size_t freeBytes = 0, totalBytes = 0;
    ASSERT_TRUE(cudaMemoryInfo(freeBytes, totalBytes));
    // Far more than the device has: cudaMalloc fails, which must be a caustica::Error, after
    // which the device is still usable.
    EXPECT_THROW(Buffer<float>(Device::cuda(), totalBytes), Error);
    Buffer<float> ok(Device::cuda(), 16);
    ok.zero();
    EXPECT_EQ(ok.toHost()[3], 0.0f);
}

TEST(GpuRenderWithoutGpu, UploadFailsWithAnError) {
    registerCudaBackend();
    if (cudaDeviceCountOrZero() > 0) GTEST_SKIP() << "a GPU is present";
    const Scene scene = smallScene("cornell-box");
    const Accel accel(scene, AccelKind::Bvh);
    // No device: the first cudaMalloc fails, which must be a caustica::Error, not a crash.
    EXPECT_THROW(makePathPass<GpuExec>(scene, accel, pathSettingsOf(scene), PathMode::Megakernel), Error);
    size_t freeBytes = 1, totalBytes = 1;
    EXPECT_FALSE(cudaMemoryInfo(freeBytes, totalBytes));
    EXPECT_EQ(freeBytes, 0u);
    EXPECT_EQ(cudaDeviceDescription(), "");
}

}  // namespace
}  // namespace caustica
