// direct_check.cu — the direct integrator's per-sample function (integrators/direct/
// direct_kernel.h) compiled by nvcc for the GPU with warnings as errors, as kernel_check.cu does
// for the path tracer: instantiated with the own BVH and the counter-based sampler in a
// megakernel (one thread per pixel), so host-only code cannot creep into it. Nothing renders
// with it yet (`caustica render --device cuda` runs the path integrator only).
#include "cuda/direct_check.h"

#include "caustica/scene/camera.h"
#include "caustica/util/rng.h"

namespace caustica {

__global__ void directMegakernel(SceneView scene, BvhIntersector accel, DirectSettings settings,
                                 uint64_t seed, int firstSample, int width, int height,
                                 PixelSample* samples, uint32_t* rays) {
    const uint32_t pixel = blockIdx.x * blockDim.x + threadIdx.x;
    if (pixel >= uint32_t(width) * uint32_t(height)) return;
    const int x = int(pixel % uint32_t(width)), y = int(pixel / uint32_t(width));
    IndependentSampler sampler(pixel, uint64_t(firstSample), seed);
    const Vec2f jitter = sampler.get2D();
    const Vec2f pos(Float(x) + jitter.x, Float(y) + jitter.y);
    const Ray ray = sampleCameraRay(scene.camera, pos, sampler);
    uint32_t rayCount = 0;
    const Spectrum L = directRadiance(scene, accel, sampler, ray, settings, rayCount);
    samples[pixel] = PixelSample{pos, L};
    rays[pixel] = rayCount;
}

void launchDirectMegakernel(const SceneView& scene, const BvhIntersector& accel,
                            const DirectSettings& settings, uint64_t seed, int firstSample,
                            int width, int height, PixelSample* samples, uint32_t* rays) {
    const uint32_t n = uint32_t(width) * uint32_t(height);
    const uint32_t block = 128;
    directMegakernel<<<(n + block - 1) / block, block>>>(scene, accel, settings, seed, firstSample,
                                                         width, height, samples, rays);
}

}  // namespace caustica
