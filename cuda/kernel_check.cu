// kernel_check.cu — the shared kernel code compiled by nvcc for the GPU (sm_90 by default).
//
// This translation unit is what keeps host-only code out of the single-source kernels: CI builds
// it whenever nvcc is present. It instantiates the path tracer's per-sample function with the own
// BVH and the counter-based sampler inside a real megakernel (one thread = one pixel sample),
// together with camera ray generation, BVH traversal, BSDFs, lights, and the film's gather kernel.
// Launching it on a device (buffers, upload, timing) is the CUDA backend's job (issue 4).
#include "caustica/accel/bvh_traversal.h"
#include "caustica/accel/intersector.h"
#include "caustica/film/film.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/scene/camera.h"
#include "caustica/util/rng.h"

#include "kernel_check.h"

namespace caustica {

__global__ void pathMegakernel(SceneView scene, BvhIntersector accel, PathSettings settings, uint64_t seed,
                               int firstSample, int width, int height, Vec2f* positions, Spectrum* radiance,
                               uint32_t* rays) {
    const uint32_t pixel = blockIdx.x * blockDim.x + threadIdx.x;
    if (pixel >= uint32_t(width) * uint32_t(height)) return;
    const int x = int(pixel % uint32_t(width)), y = int(pixel / uint32_t(width));
    IndependentSampler sampler(pixel, uint64_t(firstSample), seed);
    Vec2f jitter = sampler.get2D();
    Vec2f pos(Float(x) + jitter.x, Float(y) + jitter.y);
    uint32_t rayCount = 0;
    Spectrum L = pathRadiance(scene, accel, sampler, sampleCameraRay(scene.camera, pos, sampler), settings, rayCount);
    positions[pixel] = pos;
    radiance[pixel] = L;
    rays[pixel] = rayCount;
}

__global__ void filmSampleWeightsKernel(FilmSplatView view) {
    const size_t pixel = size_t(blockIdx.x) * blockDim.x + threadIdx.x;
    if (pixel < size_t(view.width) * size_t(view.height)) sampleWeights(view, pixel);
}

__global__ void filmGatherKernel(FilmSplatView view) {
    const size_t pixel = size_t(blockIdx.x) * blockDim.x + threadIdx.x;
    if (pixel < size_t(view.width) * size_t(view.height)) gatherPixel(view, pixel);
}

void launchPathMegakernel(const SceneView& scene, const BvhIntersector& accel, const PathSettings& settings,
                          uint64_t seed, int firstSample, int width, int height, Vec2f* positions,
                          Spectrum* radiance, uint32_t* rays) {
    const uint32_t n = uint32_t(width) * uint32_t(height);
    const uint32_t block = 128;
    pathMegakernel<<<(n + block - 1) / block, block>>>(scene, accel, settings, seed, firstSample, width, height,
                                                       positions, radiance, rays);
}

void launchFilmSplat(const FilmSplatView& view) {
    const size_t n = size_t(view.width) * size_t(view.height);
    filmSampleWeightsKernel<<<unsigned((n + 127) / 128), 128>>>(view);
    filmGatherKernel<<<unsigned((n + 127) / 128), 128>>>(view);
}

}  // namespace caustica
