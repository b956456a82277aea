// gpu_path.cu — the path tracer's kernels on the GPU: the megakernel (one thread per pixel
// sample) and the wavefront (one kernel per bounce stage over compacted queues of live paths).
// Both launch the step functions of caustica/integrators/path/path_kernel.h through
// parallelForCuda, so every launch is named and timed by KernelStats when it is enabled.
#include "cuda/gpu_path.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "caustica/accel/intersector.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/kernel_stats.h"
#include "caustica/parallel/primitives.h"
#include "caustica/scene/camera.h"
#include "caustica/util/error.h"
#include "caustica/util/rng.h"
#include "cuda/gpu_scene.h"
#include "cuda/parallel_for_cuda.h"

namespace caustica {
// Kernel launchers are free functions with external linkage: nvcc's extended lambdas must not be
// defined in private member functions.
namespace gpu_kernels {

/// One thread per (pixel, sample): the CPU's renderPathPass, slot by slot.
void megakernelPass(const SceneView& scene, const BvhIntersector& accel,
                    const PathSettings& settings, uint64_t seed, int firstSample, int width, int k,
                    size_t n, PixelSample* samples, uint32_t* rays) {
    const SceneView sv = scene;
    const BvhIntersector bi = accel;
    const PathSettings ps = settings;
    parallelForCuda("gpu.path.megakernel", n, [=] __device__(size_t slot) {
        const size_t pixel = slot / size_t(k);
        const int s = int(slot % size_t(k));
        const int x = int(pixel % size_t(width)), y = int(pixel / size_t(width));
        IndependentSampler sampler(pixel, uint64_t(firstSample + s), seed);
        const Vec2f jitter = sampler.get2D();
        const Vec2f pos(Float(x) + jitter.x, Float(y) + jitter.y);
        uint32_t rayCount = 0;
        const Ray ray = sampleCameraRay(sv.camera, pos, sampler);
        const Spectrum L = pathRadiance(sv, bi, sampler, ray, ps, rayCount);
        samples[slot] = PixelSample{pos, L};
        rays[slot] = rayCount;
    }, 128);
}

/// The device state of the paths in flight (the CPU wavefront's WavefrontPaths).
struct WavefrontState {
    PathState* state;
    IndependentSampler* sampler;
    Hit* hit;
    ShadowRay* shadow;
    uint32_t* alive;
    uint32_t* hasShadow;
    uint32_t* selected;
};

/// Keeps queue[q] for q in [0, count) whose flags[q] is set, in order, writing them to `out`.
uint32_t compactQueue(const uint32_t* flags, const uint32_t* queue, size_t count,
                      uint32_t* selected, uint32_t* out) {
    if (count == 0) return 0;
    uint32_t kept = 0;
    {
        KernelTimer timer("gpu.wavefront.compact");
        kept = compactIndices(Device::cuda(), Span<const uint32_t>(flags, count),
                              Span<uint32_t>(selected, count));
    }
    const uint32_t* sel = selected;
    parallelForCuda("gpu.wavefront.gather", kept,
                    [=] __device__(size_t q) { out[q] = queue[sel[q]]; });
    return kept;
}

/// Traces pass slots [begin, begin + n) to completion; the CPU's traceChunk with device queues.
uint64_t wavefrontChunk(const SceneView& scene, const BvhIntersector& accel,
                        const PathSettings& settings, uint64_t seed, int firstSample, int width,
                        int k, size_t begin, size_t n, PixelSample* samples,
                        const WavefrontState& w, uint32_t* queueA, uint32_t* queueB,
                        uint32_t* shadowQueue) {
    const SceneView sv = scene;
    const BvhIntersector bi = accel;
    const PathSettings ps = settings;
    const WavefrontState ws = w;
    uint64_t rays = 0;
    uint32_t* live = queueA;
    uint32_t* next = queueB;

    parallelForCuda("gpu.wavefront.generate", n, [=] __device__(size_t i) {
        const size_t slot = begin + i, pixel = slot / size_t(k), s = slot % size_t(k);
        const int x = int(pixel % size_t(width)), y = int(pixel / size_t(width));
        IndependentSampler sampler(pixel, uint64_t(firstSample) + s, seed);
        const Vec2f jitter = sampler.get2D();
        const Vec2f pos(Float(x) + jitter.x, Float(y) + jitter.y);
        const Ray ray = sampleCameraRay(sv.camera, pos, sampler);  // may draw a lens sample
        ws.sampler[i] = sampler;
        samples[slot].pos = pos;
        live[i] = uint32_t(i);
        ws.alive[i] = startPath(ws.state[i], ray, ps);
    });
    size_t liveCount = compactQueue(ws.alive, live, n, ws.selected, next);
    std::swap(live, next);

    while (liveCount > 0) {
        const uint32_t* liveQ = live;
        parallelForCuda("gpu.wavefront.extend", liveCount, [=] __device__(size_t j) {
            const uint32_t i = liveQ[j];
            Hit hit{};
            ws.alive[j] = bi.intersect(ws.state[i].ray, hit);
            ws.hit[i] = hit;
        });
        rays += liveCount;

        parallelForCuda("gpu.wavefront.shade", liveCount, [=] __device__(size_t j) {
            const uint32_t i = liveQ[j];
            bool shadowRay = false;
            IndependentSampler sampler = ws.sampler[i];
            if (ws.alive[j])
                ws.alive[j] = shadeHit(sv, ws.state[i], ws.hit[i], sampler, ps, ws.shadow[i], shadowRay);
            else
                missPath(sv, ws.state[i], ps);
            ws.sampler[i] = sampler;
            ws.hasShadow[j] = shadowRay;
        });

        const size_t shadowCount = compactQueue(ws.hasShadow, live, liveCount, ws.selected, shadowQueue);
        const uint32_t* shadowQ = shadowQueue;
        parallelForCuda("gpu.wavefront.shadow", shadowCount, [=] __device__(size_t q) {
            const uint32_t i = shadowQ[q];
            addShadowContribution(ws.state[i], ws.shadow[i], bi.occluded(ws.shadow[i].ray));
        });
        rays += shadowCount;

        liveCount = compactQueue(ws.alive, live, liveCount, ws.selected, next);
        std::swap(live, next);
    }

    parallelForCuda("gpu.wavefront.finish", n, [=] __device__(size_t i) {
        samples[begin + i].L = ws.state[i].radiance;
    });
    return rays;
}

}  // namespace gpu_kernels

struct GpuPathRenderer::Impl {
    GpuScene scene;
    PathSettings settings;
    GpuPathMode mode;
    int width, height, maxK;
    size_t chunk = 0;
    Buffer<PixelSample> samples;
    Buffer<uint32_t> rays;  // megakernel: per slot
    // Wavefront state (chunk paths).
    Buffer<PathState> state;
    Buffer<IndependentSampler> sampler;
    Buffer<Hit> hit;
    Buffer<ShadowRay> shadow;
    Buffer<uint32_t> queueA, queueB, shadowQueue, alive, hasShadow, selected;

    Impl(const Scene& s, const Bvh& bvh, const PathSettings& ps, GpuPathMode m, int k,
         size_t maxPathsInFlight)
        : scene(s, bvh), settings(ps), mode(m), width(s.film.width), height(s.film.height),
          maxK(k) {
        if (k <= 0) throw Error("GPU path tracer: samples per pass must be positive");
        if (maxPathsInFlight == 0) throw Error("GPU wavefront: maxPathsInFlight must be positive");
        const Device gpu = Device::cuda();
        const size_t total = size_t(width) * size_t(height) * size_t(k);
        samples = Buffer<PixelSample>(gpu, total);
        if (mode == GpuPathMode::Megakernel) {
            rays = Buffer<uint32_t>(gpu, total);
            return;
        }
        chunk = std::min({maxPathsInFlight, total, size_t(0xffffffffu)});
        state = Buffer<PathState>(gpu, chunk);
        sampler = Buffer<IndependentSampler>(gpu, chunk);
        hit = Buffer<Hit>(gpu, chunk);
        shadow = Buffer<ShadowRay>(gpu, chunk);
        for (Buffer<uint32_t>* b : {&queueA, &queueB, &shadowQueue, &alive, &hasShadow, &selected})
            *b = Buffer<uint32_t>(gpu, chunk);
    }
};

GpuPathRenderer::GpuPathRenderer(const Scene& scene, const Bvh& bvh, const PathSettings& settings,
                                 GpuPathMode mode, int maxSamplesPerPass, size_t maxPathsInFlight)
    : impl_(std::make_unique<Impl>(scene, bvh, settings, mode, maxSamplesPerPass,
                                   maxPathsInFlight)) {}

GpuPathRenderer::~GpuPathRenderer() = default;

GpuPathMode GpuPathRenderer::mode() const {
    return impl_->mode;
}

size_t GpuPathRenderer::sceneBytes() const {
    return impl_->scene.bytes();
}

uint64_t GpuPathRenderer::renderPass(uint64_t seed, int firstSampleIndex, SamplePass& pass) {
    Impl& m = *impl_;
    if (pass.width != m.width || pass.height != m.height || pass.samplesPerPixel <= 0 ||
        pass.samplesPerPixel > m.maxK) {
        throw Error("GPU path tracer: a pass of " + std::to_string(pass.width) + "x" +
                    std::to_string(pass.height) + "x" + std::to_string(pass.samplesPerPixel) +
                    " samples does not fit buffers for " + std::to_string(m.width) + "x" +
                    std::to_string(m.height) + "x" + std::to_string(m.maxK));
    }
    const int k = pass.samplesPerPixel;
    const size_t total = pass.samples.size();
    if (total == 0) return 0;
    uint64_t rays = 0;
    const BvhIntersector accel = m.scene.intersector();
    if (m.mode == GpuPathMode::Megakernel) {
        gpu_kernels::megakernelPass(m.scene.view(), accel, m.settings, seed, firstSampleIndex,
                                    m.width, k, total, m.samples.data(), m.rays.data());
        std::vector<uint32_t> counts(total);
        {
            KernelTimer timer("gpu.download");
            m.rays.copyToHost(Span<uint32_t>(counts.data(), total));
        }
        for (uint32_t c : counts) rays += c;
    } else {
        const gpu_kernels::WavefrontState w{m.state.data(), m.sampler.data(), m.hit.data(),
                                            m.shadow.data(), m.alive.data(), m.hasShadow.data(),
                                            m.selected.data()};
        for (size_t begin = 0; begin < total; begin += m.chunk) {
            const size_t n = std::min(m.chunk, total - begin);
            rays += gpu_kernels::wavefrontChunk(m.scene.view(), accel, m.settings, seed,
                                                firstSampleIndex, m.width, k, begin, n,
                                                m.samples.data(), w, m.queueA.data(),
                                                m.queueB.data(), m.shadowQueue.data());
        }
    }
    KernelTimer timer("gpu.download");
    m.samples.copyToHost(pass.span());  // cudaMemcpy waits for the kernels; errors surface here
    return rays;
}

}  // namespace caustica
