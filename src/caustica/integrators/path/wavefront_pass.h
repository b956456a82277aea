// wavefront_pass.h — the path tracer in wavefront form: one kernel per stage of a bounce
// (generate, extend, shade, shadow), the queue of live paths compacted after every bounce
// ("active thread compaction"). The stages call the megakernel's step functions (path_kernel.h),
// so both modes give bit-identical images. Single source (launch.h): templates only, instantiated
// by path_pass.cpp per device.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "caustica/accel/device_scene.h"
#include "caustica/integrators/megakernel_pass.h"
#include "caustica/integrators/pass_driver.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/primitives.h"
#include "caustica/util/error.h"

namespace caustica {
namespace wavefront_detail {

/// The paths in flight, struct-of-arrays by record, indexed by path id within the chunk. Queues
/// hold path ids; flags and `selected` are indexed by position within the queue being compacted.
struct Paths {
    PathState* state;
    IndependentSampler* sampler;
    Hit* hit;
    ShadowRay* shadow;
    uint32_t* alive;      // per queue position: 0 or 1
    uint32_t* hasShadow;  // per queue position: 0 or 1
    uint32_t* selected;   // compacted queue positions
};

/// Keeps queue[q] for q in [0, count) whose flags[q] is set, in order, writing them to `out`;
/// returns how many. (Compaction of the flags, then a gather.)
template <class Exec>
uint32_t compactQueue(Exec exec, const uint32_t* flags, const uint32_t* queue, size_t count,
                      uint32_t* selected, uint32_t* out) {
    if (count == 0) return 0;
    const uint32_t kept = compactIndices(Exec::device(), Span<const uint32_t>(flags, count),
                                         Span<uint32_t>(selected, count));
    launch(exec, "wavefront.gather", kept, [=] CA_HD(size_t q) { out[q] = queue[selected[q]]; }, 256);
    return kept;
}

/// Traces the paths of pass slots [begin, begin + n) to completion; returns the rays traced.
template <class Exec, class Intersector>
uint64_t traceChunk(Exec exec, const SceneView& scene, const Intersector& accel, const PathSettings& settings,
                    uint64_t seed, int firstSample, int width, int k, size_t begin, size_t n,
                    PixelSample* samples, const Paths& w, uint32_t* live, uint32_t* next, uint32_t* shadowQueue) {
    uint64_t rays = 0;

    // ---- Generate: camera rays; the sample's film position goes straight to its pass slot.
    launch(exec, "wavefront.generate", n, [=] CA_HD(size_t i) {
        const size_t slot = begin + i;
        const CameraSample c =
            cameraSample(scene.camera, slot / size_t(k), width, uint64_t(firstSample) + slot % size_t(k), seed);
        w.sampler[i] = c.sampler;
        samples[slot].pos = c.pos;
        live[i] = uint32_t(i);
        w.alive[i] = startPath(w.state[i], c.ray, settings);
    });
    size_t liveCount = compactQueue(exec, w.alive, live, n, w.selected, next);
    std::swap(live, next);

    while (liveCount > 0) {
        const uint32_t* liveQ = live;
        // ---- Extend: closest hit of every live path's ray (`alive` holds "found" until shade).
        launch(exec, "wavefront.extend", liveCount, [=] CA_HD(size_t j) {
            const uint32_t i = liveQ[j];
            Hit hit{};
            w.alive[j] = accel.intersect(w.state[i].ray, hit);
            w.hit[i] = hit;
        });
        rays += liveCount;

        // ---- Shade: emission, NEE sample, BSDF sample, roulette (or the miss of the scene).
        launch(exec, "wavefront.shade", liveCount, [=] CA_HD(size_t j) {
            const uint32_t i = liveQ[j];
            bool shadowRay = false;
            if (w.alive[j])
                w.alive[j] = shadeHit(scene, w.state[i], w.hit[i], w.sampler[i], settings, w.shadow[i], shadowRay);
            else
                missPath(scene, w.state[i], settings);
            w.hasShadow[j] = shadowRay;
        });

        // ---- Shadow: any-hit test of the NEE samples, over the queue of paths that made one.
        const size_t shadowCount = compactQueue(exec, w.hasShadow, live, liveCount, w.selected, shadowQueue);
        const uint32_t* shadowQ = shadowQueue;
        launch(exec, "wavefront.shadow", shadowCount, [=] CA_HD(size_t q) {
            const uint32_t i = shadowQ[q];
            addShadowContribution(w.state[i], w.shadow[i], accel.occluded(w.shadow[i].ray));
        });
        rays += shadowCount;

        // ---- Compaction: the paths still alive form the next bounce's queue, in order.
        liveCount = compactQueue(exec, w.alive, live, liveCount, w.selected, next);
        std::swap(live, next);
    }

    launch(exec, "wavefront.finish", n, [=] CA_HD(size_t i) { samples[begin + i].L = w.state[i].radiance; });
    return rays;
}

}  // namespace wavefront_detail

template <class Exec>
class WavefrontPass final : public PassDriver {
public:
    /// At most `maxPathsInFlight` paths at a time: a larger pass is traced in chunks.
    WavefrontPass(const Scene& scene, const Accel& accel, const PathSettings& settings, size_t maxPathsInFlight)
        : scene_(scene, accel, Exec::device()), settings_(settings), maxPaths_(maxPathsInFlight) {
        if (maxPathsInFlight == 0) throw Error("wavefront: maxPathsInFlight must be positive");
    }

    uint64_t render(uint64_t seed, int firstSampleIndex, SamplePass& pass) override {
        const size_t total = pass.samples.size();
        // Path ids within a chunk are 32-bit queue entries.
        const size_t chunk = std::min({maxPaths_, total, size_t(0xffffffffu)});
        if (chunk == 0) return 0;
        allocate(chunk, total);
        PixelSample* out = Exec::kind == DeviceKind::Cpu ? pass.samples.data() : samples_.data();
        const wavefront_detail::Paths w{state_.data(),  sampler_.data(),   hit_.data(),     shadow_.data(),
                                        alive_.data(), hasShadow_.data(), selected_.data()};
        uint64_t rays = 0;
        scene_.visit(Exec{}, [&](const auto& intersector) {
            for (size_t begin = 0; begin < total; begin += chunk)
                rays += wavefront_detail::traceChunk(Exec{}, scene_.view(), intersector, settings_, seed,
                                                     firstSampleIndex, pass.width, pass.samplesPerPixel, begin,
                                                     std::min(chunk, total - begin), out, w, queueA_.data(),
                                                     queueB_.data(), shadowQueue_.data());
        });
        if constexpr (Exec::kind != DeviceKind::Cpu) samples_.copyToHost(pass.span());
        return rays;
    }
    size_t sceneBytes() const override { return scene_.bytes(); }

private:
    void allocate(size_t chunk, size_t total) {
        const Device d = Exec::device();
        if constexpr (Exec::kind != DeviceKind::Cpu)
            if (samples_.size() < total) samples_ = Buffer<PixelSample>(d, total);
        if (state_.size() >= chunk) return;
        state_ = Buffer<PathState>(d, chunk);
        sampler_ = Buffer<IndependentSampler>(d, chunk);
        hit_ = Buffer<Hit>(d, chunk);
        shadow_ = Buffer<ShadowRay>(d, chunk);
        for (Buffer<uint32_t>* b : {&queueA_, &queueB_, &shadowQueue_, &alive_, &hasShadow_, &selected_})
            *b = Buffer<uint32_t>(d, chunk);
    }

    DeviceScene scene_;
    PathSettings settings_;
    size_t maxPaths_;
    Buffer<PixelSample> samples_;  // a GPU's
    Buffer<PathState> state_;
    Buffer<IndependentSampler> sampler_;
    Buffer<Hit> hit_;
    Buffer<ShadowRay> shadow_;
    Buffer<uint32_t> queueA_, queueB_, shadowQueue_, alive_, hasShadow_, selected_;
};

}  // namespace caustica
