// gpu_path.h — the path tracer on the GPU (plain C++ host API; the kernels are in gpu_path.cu).
//
// One pass renders K samples per pixel into a SamplePass exactly as the CPU drivers do
// (path_integrator.h, wavefront.h): the same step functions of path_kernel.h, the same random
// streams IndependentSampler(pixel, firstSampleIndex + s, seed), the same slot layout
// (pixel * K + s). The samples are computed into device memory and copied to the host pass; the
// host Film accumulates them. Images therefore match the CPU's up to floating-point rounding
// (nvcc contracts a * b + c into FMAs, g++ on x86-64 does not by default).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "caustica/accel/bvh.h"
#include "caustica/film/film.h"
#include "caustica/integrators/path/gpu_memory.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/scene/scene.h"

namespace caustica {

class GpuScene;

class GpuPathRenderer {
public:
    /// Uploads the scene and BVH and allocates device memory for passes of up to
    /// `maxSamplesPerPass` samples per pixel at the film's resolution (and, in wavefront mode,
    /// the state of min(maxPathsInFlight, pixels * K) paths). Needs the CUDA backend registered
    /// and a GPU; throws caustica::Error on any CUDA failure, out of memory included.
    GpuPathRenderer(const Scene& scene, const Bvh& bvh, const PathSettings& settings,
                    GpuPathMode mode, int maxSamplesPerPass,
                    size_t maxPathsInFlight = size_t(1) << 20);
    ~GpuPathRenderer();
    GpuPathRenderer(const GpuPathRenderer&) = delete;
    GpuPathRenderer& operator=(const GpuPathRenderer&) = delete;

    /// Renders pass.samplesPerPixel (<= maxSamplesPerPass) samples for every pixel with sample
    /// indices from `firstSampleIndex` and copies them into `pass` (whose size must be the
    /// film's). Returns the rays traced (closest hit + shadow).
    uint64_t renderPass(uint64_t seed, int firstSampleIndex, SamplePass& pass);

    GpuPathMode mode() const;
    /// Device bytes of the uploaded scene + BVH.
    size_t sceneBytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace caustica
