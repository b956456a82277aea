// gpu_render_test.cpp — the path tracer on the GPU against the CPU: the same scene, seed and
// sample streams rendered by renderPathPass (CPU, own BVH) and by GpuPathRenderer in both GPU
// modes. Built only with the CUDA backend (target caustica_gpu_tests, ctest gpu_render); every
// test that needs a GPU skips when cudaGetDeviceCount finds none.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "caustica/accel/accel.h"
#include "caustica/film/film.h"
#include "caustica/film/image_compare.h"
#include "caustica/integrators/path/gpu_memory.h"
#include "caustica/integrators/path/path_integrator.h"
#include "caustica/integrators/render_loop.h"
#include "caustica/io/scene_loader.h"
#include "caustica/parallel/backend.h"
#include "caustica/parallel/buffer.h"
#include "caustica/util/error.h"
#include "common/gpu_test_setup.h"
#include "cuda/cuda_backend.h"
#include "cuda/gpu_path.h"
#include "cuda/gpu_scene.h"

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

/// Renders `spp` samples per pixel in passes of 4 through the film, on the CPU or the GPU.
Image render(const Scene& scene, const Accel& accel, GpuPathRenderer* gpu, int spp,
             uint64_t seed, uint64_t& rays) {
    Film film(scene.film);
    RenderBudget budget;
    budget.samplesPerPixel = spp;
    budget.samplesPerPass = 4;
    const PathSettings settings = pathSettingsFrom(scene.integrator);
    RenderStats stats = runRenderLoop(film, budget, [&](int first, int, SamplePass& pass) {
        if (gpu) return gpu->renderPass(seed, first, pass);
        return renderPathPass(scene, accel, settings, seed, first, pass);
    });
    rays = stats.rays;
    return film.develop();
}

void expectSameImage(const std::string& name, GpuPathMode mode) {
    const Scene scene = smallScene(name);
    const Accel accel(scene, AccelKind::Bvh);
    uint64_t cpuRays = 0, gpuRays = 0;
    const Image cpu = render(scene, accel, nullptr, 16, 7, cpuRays);
    GpuPathRenderer gpu(scene, *accel.bvh(), pathSettingsFrom(scene.integrator), mode, 4);
    const Image image = render(scene, accel, &gpu, 16, 7, gpuRays);
    const ErrorMetrics m = compareImages(image, cpu);
    // The same random streams: equal up to rounding. FMA contraction on the GPU can flip a rare
    // roulette, edge or total-internal-reflection decision, and one flipped path through the water
    // can put a caustic sample in a dark pixel (a relMSE term in the hundreds), so the bound, far
    // below 16-spp noise, holds without the worst 1% of pixels.
    EXPECT_LT(m.relMse * (1 - m.relMseWorstShare), 1e-3)
        << name << " " << gpuPathModeName(mode) << ": relMSE " << m.relMse << ", worst 1% share " << m.relMseWorstShare;
    const double rayRatio = double(gpuRays) / double(cpuRays);
    EXPECT_NEAR(rayRatio, 1.0, 1e-2) << gpuRays << " vs " << cpuRays;
}

TEST_F(GpuRender, CornellBoxMegakernelMatchesCpu) {
    expectSameImage("cornell-box", GpuPathMode::Megakernel);
}
TEST_F(GpuRender, CornellBoxWavefrontMatchesCpu) {
    expectSameImage("cornell-box", GpuPathMode::Wavefront);
}
TEST_F(GpuRender, CornellWaterMegakernelMatchesCpu) {
    expectSameImage("cornell-water", GpuPathMode::Megakernel);
}
TEST_F(GpuRender, CornellWaterWavefrontMatchesCpu) {
    expectSameImage("cornell-water", GpuPathMode::Wavefront);
}

TEST_F(GpuRender, WavefrontChunksDoNotChangeSamples) {
    // A pass traced in many small chunks of paths gives the same samples as one chunk.
    const Scene scene = smallScene("cornell-box");
    const Accel accel(scene, AccelKind::Bvh);
    const PathSettings settings = pathSettingsFrom(scene.integrator);
    GpuPathRenderer whole(scene, *accel.bvh(), settings, GpuPathMode::Wavefront, 2);
    GpuPathRenderer chunked(scene, *accel.bvh(), settings, GpuPathMode::Wavefront, 2, 1000);
    SamplePass a(scene.film.width, scene.film.height, 2), b(scene.film.width, scene.film.height, 2);
    const uint64_t raysA = whole.renderPass(3, 0, a), raysB = chunked.renderPass(3, 0, b);
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
        GpuScene gpuScene(scene, *accel.bvh());
        const GpuMemoryEstimate e =
            estimateGpuMemory(gpuRenderSizes(scene, *accel.bvh(), 1, GpuPathMode::Megakernel));
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
    EXPECT_THROW(GpuPathRenderer(scene, *accel.bvh(), pathSettingsFrom(scene.integrator),
                                 GpuPathMode::Megakernel, 1),
                 Error);
    size_t freeBytes = 1, totalBytes = 1;
    EXPECT_FALSE(cudaMemoryInfo(freeBytes, totalBytes));
    EXPECT_EQ(freeBytes, 0u);
    EXPECT_EQ(cudaDeviceDescription(), "");
}

}  // namespace
}  // namespace caustica
