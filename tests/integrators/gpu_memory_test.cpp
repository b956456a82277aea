// gpu_memory_test.cpp — the GPU memory estimate is a pure function of sizes: checked on the CPU.
#include <gtest/gtest.h>

#include "accel/test_scenes.h"
#include "caustica/accel/bvh.h"
#include "caustica/film/film.h"
#include "caustica/integrators/path/gpu_memory.h"
#include "caustica/integrators/pass_driver.h"
#include "caustica/scene/scene.h"
#include "caustica/util/error.h"

namespace caustica {
namespace {

GpuRenderSizes someSizes() {
    GpuRenderSizes s;
    s.positions = 300;
    s.normals = 300;
    s.uvs = 0;
    s.triangles = 100;
    s.triangleShape = 100;
    s.spheres = 2;
    s.shapes = 5;
    s.bsdfs = 4;
    s.lights = 1;
    s.lightCdf = 2;
    s.bvhNodes = 40;
    s.bvhPrimIndices = 102;
    s.bvhPrims = 102;
    s.width = 64;
    s.height = 48;
    s.samplesPerPass = 4;
    return s;
}

TEST(GpuMemory, SceneAndBvhAreTheirArrays) {
    const GpuRenderSizes s = someSizes();
    const GpuMemoryEstimate e = estimateGpuMemory(s);
    EXPECT_EQ(e.scene, 600 * sizeof(Vec3f) + 100 * sizeof(Vec3u) + 100 * sizeof(uint32_t) +
                           2 * sizeof(Sphere) + 5 * sizeof(Shape) + 4 * sizeof(Bsdf) +
                           sizeof(Light) + 2 * sizeof(float));
    EXPECT_EQ(e.bvh, 40 * sizeof(BvhNode) + 102 * sizeof(uint32_t) + 102 * sizeof(BvhPrimitive));
    EXPECT_EQ(e.samplePass, size_t(64 * 48 * 4) * sizeof(PixelSample));
    EXPECT_EQ(e.total(), e.scene + e.bvh + e.pathState + e.samplePass + e.scratch);
}

TEST(GpuMemory, MegakernelHasOnePathPerSample) {
    const GpuMemoryEstimate e = estimateGpuMemory(someSizes());
    EXPECT_EQ(e.pathsInFlight, size_t(64 * 48 * 4));
    EXPECT_EQ(e.pathState, e.pathsInFlight * sizeof(uint32_t));
}

TEST(GpuMemory, WavefrontIsBoundedByPathsInFlight) {
    GpuRenderSizes s = someSizes();
    s.mode = PathMode::Wavefront;
    s.maxPathsInFlight = 1000;
    const GpuMemoryEstimate small = estimateGpuMemory(s);
    EXPECT_EQ(small.pathsInFlight, 1000u);
    EXPECT_EQ(small.pathState, 1000 * wavefrontBytesPerPath());
    s.maxPathsInFlight = size_t(1) << 30;  // more than the pass: the pass bounds it
    const GpuMemoryEstimate whole = estimateGpuMemory(s);
    EXPECT_EQ(whole.pathsInFlight, size_t(64 * 48 * 4));
    EXPECT_GT(whole.total(), small.total());
}

TEST(GpuMemory, GrowsLinearlyWithSamplesPerPass) {
    GpuRenderSizes s = someSizes();
    const size_t one = estimateGpuMemory(s).samplePass;
    s.samplesPerPass = 8;
    EXPECT_EQ(estimateGpuMemory(s).samplePass, 2 * one);
}

TEST(GpuMemory, SizesComeFromTheScene) {
    Scene scene;
    scene.positions.resize(3);
    scene.triangles.resize(1);
    scene.triangleShape.resize(1);
    scene.shapes.resize(1);
    scene.film.width = 10;
    scene.film.height = 5;
    Bvh bvh;
    bvh.nodes.resize(1);
    bvh.primIndices.resize(1);
    const GpuRenderSizes s = gpuRenderSizes(scene, bvh, 3, PathMode::Wavefront, 7);
    EXPECT_EQ(s.positions, 3u);
    EXPECT_EQ(s.triangles, 1u);
    EXPECT_EQ(s.bvhNodes, 1u);
    EXPECT_EQ(s.width, 10);
    EXPECT_EQ(s.height, 5);
    EXPECT_EQ(s.samplesPerPass, 3);
    EXPECT_EQ(s.maxPathsInFlight, 7u);
    EXPECT_EQ(estimateGpuMemory(s).pathsInFlight, 7u);
}

// The BVH's share must be what DeviceScene uploads, parent links included: the same four arrays
// BvhStats::memoryBytes counts (the GPU test compares the estimate with the upload byte for byte).
TEST(GpuMemory, BvhShareIsEveryUploadedArray) {
    const Scene scene = test::makeRandomScene(test::sceneOf(500, 20, 5));
    const Bvh bvh = buildBvh(scene);
    ASSERT_FALSE(bvh.parents.empty());
    const GpuRenderSizes s = gpuRenderSizes(scene, bvh, 1, PathMode::Megakernel);
    EXPECT_EQ(s.bvhParents, bvh.parents.size());
    EXPECT_EQ(estimateGpuMemory(s).bvh, bvh.stats.memoryBytes);
}

TEST(GpuMemory, ModeNamesAndBytes) {
    EXPECT_EQ(parsePathMode("wavefront"), PathMode::Wavefront);
    EXPECT_EQ(parsePathMode("megakernel"), PathMode::Megakernel);
    EXPECT_THROW(parsePathMode("fast"), Error);
    EXPECT_STREQ(pathModeName(PathMode::Wavefront), "wavefront");
    EXPECT_EQ(formatBytes(512), "512 B");
    EXPECT_EQ(formatBytes(size_t(3) << 20), "3.0 MiB");
    EXPECT_EQ(formatBytes(size_t(3) << 29), "1.50 GiB");
}

}  // namespace
}  // namespace caustica
