// wavefront_pass.h — the path tracer in wavefront form: one kernel per stage of a bounce
// (generate, extend, shade, shadow), the queue of live paths compacted after every bounce
// ("active thread compaction"). The stages call the megakernel's step functions (path_kernel.h),
// so both modes give bit-identical images. Single source (launch.h): templates only, instantiated
// by path_pass.cpp per device.
//
// A pass is traced in chunks of paths. How chunks and stages meet the device is its
// WavefrontSchedule: a GPU traces one large chunk at a time, each stage a grid over the chunk's
// queue; a CPU traces one small chunk per thread at once, each stage a serial loop over the
// chunk (SerialExec), so that the chunk's path state stays in that core's L2 cache between
// stages and no stage waits for the other threads. The stage code is the same for both; a CPU
// thread's shade stage takes four paths at a time through the same shadeVertex where their
// vertices allow it (shade_lanes.h), with the same bits.
//
// AOVs (shareFirstHits) are written from the first extend stage's hits of the camera rays, so a
// render with AOVs traces each camera ray once, as the megakernel's does.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "caustica/accel/device_scene.h"
#include "caustica/integrators/aov/aov_kernel.h"
#include "caustica/integrators/aov/aov_pass.h"
#include "caustica/integrators/megakernel_pass.h"
#include "caustica/integrators/pass_driver.h"
#include "caustica/integrators/path/path_kernel.h"
#include "caustica/integrators/path/shade_lanes.h"
#include "caustica/parallel/buffer.h"
#include "caustica/parallel/compact.h"
#include "caustica/integrators/hit_prefetch.h"
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

/// The AOVs of the chunk's camera rays (aov_kernel.h), written to their pass slots: for queue
/// entries [0, count) of `queue` (null: path ids 0, 1, ...), whose camera rays the first extend
/// stage traced (`traced`, hits and found flags in w.hit and w.alive) or, where no path traces a
/// segment (max_depth 0), traced here. The megakernel's AOVs (FirstHitIntersector) bit for bit.
template <class Exec, class Intersector>
void aovStage(Exec exec, const SceneView& scene, const Intersector& accel, const megakernel_detail::AovOutput& aovs,
              size_t begin, const PixelSample* samples, const Paths& w, const uint32_t* queue, size_t count,
              bool traced) {
    launch(exec, "wavefront.aov", count, [=] CA_HD(size_t j) {
        const uint32_t i = queue ? queue[j] : uint32_t(j);
        const size_t slot = begin + i;
        Hit hit{};
        if (!traced)
            accel.intersect(w.state[i].ray, hit);
        else if (w.alive[j])
            hit = w.hit[i];
        aovs.positions[slot] = samples[slot].pos;
        aovValues(scene, w.state[i].ray, hit, aovs.layout, aovs.values + slot * size_t(aovs.layout.channels));
    });
}

/// The shade stage's prefetch at queue position j: the hit data of the paths `prefetch` (and twice
/// as many) entries ahead (0: none).
CA_HD_INLINE void prefetchAhead(const SceneView& scene, const Paths& w, const uint32_t* liveQ, size_t liveCount,
                                size_t j, size_t prefetch) {
    if (prefetch == 0) return;
    if (j + 2 * prefetch < liveCount) prefetchTriangle(scene, w.hit[liveQ[j + 2 * prefetch]]);
    if (j + prefetch < liveCount) prefetchVertices(scene, w.hit[liveQ[j + prefetch]]);
}

/// The shade stage of path i at queue position j: shadeHit where its ray hit (w.alive[j]), the
/// miss of the scene where not; w.alive[j] and w.hasShadow[j] say what follows.
CA_HD_INLINE void shadeEntry(const SceneView& scene, const PathSettings& settings, const Paths& w, uint32_t i,
                             size_t j) {
    bool shadowRay = false;
    if (w.alive[j])
        w.alive[j] = shadeHit(scene, w.state[i], w.hit[i], w.sampler[i], settings, w.shadow[i], shadowRay);
    else
        missPath(scene, w.state[i], settings);
    w.hasShadow[j] = shadowRay;
}

#if CA_FLOAT4_SSE
/// The shade stage on one host thread with four paths at a time: the entries whose vertex a lane
/// vertex can take (diffuseQuadEligible) are gathered four by four and shaded by
/// shadeDiffuseQuad4, the others (and the last gathered, fewer than four) by shadeEntry. Each
/// path is shaded once, with its own sampler, so the order does not change any path's bits.
inline void shadeStageByFour(const SceneView& scene, const PathSettings& settings, const Paths& w,
                             const uint32_t* liveQ, size_t liveCount, size_t prefetch) {
    size_t gathered[4];
    int count = 0;
    for (size_t j = 0; j < liveCount; ++j) {
        prefetchAhead(scene, w, liveQ, liveCount, j, prefetch);
        const uint32_t i = liveQ[j];
        if (!(w.alive[j] && diffuseQuadEligible(scene, w.state[i], w.hit[i], settings))) {
            shadeEntry(scene, settings, w, i, j);
            continue;
        }
        gathered[count++] = j;
        if (count < 4) continue;
        count = 0;
        PathState* paths[4];
        const Hit* hits[4];
        IndependentSampler* samplers[4];
        ShadowRay* shadows[4];
        bool hasShadow[4];
        for (int k = 0; k < 4; ++k) {
            const uint32_t id = liveQ[gathered[k]];
            paths[k] = &w.state[id];
            hits[k] = &w.hit[id];
            samplers[k] = &w.sampler[id];
            shadows[k] = &w.shadow[id];
        }
        const uint32_t alive = shadeDiffuseQuad4(scene, paths, hits, samplers, settings, shadows, hasShadow);
        for (int k = 0; k < 4; ++k) {
            w.alive[gathered[k]] = (alive >> k) & 1u;
            w.hasShadow[gathered[k]] = hasShadow[k];
        }
    }
    for (int k = 0; k < count; ++k) shadeEntry(scene, settings, w, liveQ[gathered[k]], gathered[k]);
}
#endif

/// Traces the paths of pass slots [begin, begin + n) to completion; returns the rays traced.
/// `aovs.values` non-null: also writes the AOVs of their camera rays (aovStage).
/// `prefetch` > 0: the shade stage prefetches the hit data of the paths that many (and twice as
/// many) queue entries ahead (a CPU's; 0 on a GPU, where it would only add loads).
template <class Exec, class Intersector>
uint64_t traceChunk(Exec exec, const SceneView& scene, const Intersector& accel, const PathSettings& settings,
                    uint64_t seed, int firstSample, int width, int k, size_t begin, size_t n,
                    PixelSample* samples, const Paths& w, uint32_t* live, uint32_t* next, uint32_t* shadowQueue,
                    const megakernel_detail::AovOutput& aovs, size_t prefetch) {
    uint64_t rays = 0;
    constexpr size_t kPacket = size_t(rayPacketSize<Intersector>());
    const auto packetCount = [](size_t n) { return (n + kPacket - 1) / kPacket; };

    // ---- Generate: camera rays; the sample's film position goes straight to its pass slot.
    launch(exec, "wavefront.generate", n, [=] CA_HD(size_t i) {
        const size_t slot = begin + i;
        const DivMod ps = divMod(slot, uint64_t(k));  // pixel, sample within the pass
        const CameraSample c = cameraSample(scene.camera, ps.quot, width, uint64_t(firstSample) + ps.rem, seed);
        w.sampler[i] = c.sampler;
        samples[slot].pos = c.pos;
        live[i] = uint32_t(i);
        w.alive[i] = startPath(w.state[i], c.ray, settings);
    });
    size_t liveCount = compactQueue(exec, w.alive, live, n, w.selected, next);
    std::swap(live, next);
    if (aovs.values != nullptr && liveCount == 0)  // no segment traced (max_depth 0)
        aovStage(exec, scene, accel, aovs, begin, samples, w, nullptr, n, false);
    bool firstBounce = true;
#if CA_FLOAT4_SSE
    const bool quadLights = std::is_same_v<Exec, SerialExec> && allLightsAreQuads(scene);
#endif

    while (liveCount > 0) {
        const uint32_t* liveQ = live;
        // ---- Extend: closest hit of every live path's ray (`alive` holds "found" until shade), a
        // packet of queue entries per call (Embree's packet queries on a CPU; one ray on a GPU).
        // The first extend stage traces camera rays, neighbouring samples side by side: coherent
        // packets (intersectPacket). Their shadow rays are not marked: Embree's coherent mode made
        // them slower (more instructions on every bundled scene, callgrind).
        const bool cameraRays = firstBounce;
        launch(exec, "wavefront.extend", packetCount(liveCount), [=] CA_HD(size_t p) {
            const size_t j0 = p * kPacket;
            const int m = int(min(kPacket, liveCount - j0));
            const Ray* rays[kPacket];
            Hit* hits[kPacket];
            for (int k = 0; k < m; ++k) {
                const uint32_t i = liveQ[j0 + k];
                rays[k] = &w.state[i].ray;
                hits[k] = &w.hit[i];
            }
            intersectPacket(accel, m, rays, hits, w.alive + j0, cameraRays);
        });
        rays += liveCount;
        // ---- AOVs of the camera rays, from their hits (every path is in the first queue).
        if (aovs.values != nullptr && firstBounce) aovStage(exec, scene, accel, aovs, begin, samples, w, liveQ, liveCount, true);
        firstBounce = false;

        // ---- Shade: emission, NEE sample, BSDF sample, roulette (or the miss of the scene).
        // A CPU thread shades four paths at a time where it can (shadeStageByFour), the same
        // shadeVertex over lanes; a GPU runs one path per thread.
        bool shadedByFour = false;
#if CA_FLOAT4_SSE
        if constexpr (std::is_same_v<Exec, SerialExec>) {
            if (quadLights) {
                shadeStageByFour(scene, settings, w, liveQ, liveCount, prefetch);
                shadedByFour = true;
            }
        }
#endif
        if (!shadedByFour) {
            launch(exec, "wavefront.shade", liveCount, [=] CA_HD(size_t j) {
                prefetchAhead(scene, w, liveQ, liveCount, j, prefetch);
                shadeEntry(scene, settings, w, liveQ[j], j);
            });
        }

        // ---- Shadow: any-hit test of the NEE samples, over the queue of paths that made one.
        const size_t shadowCount = compactQueue(exec, w.hasShadow, live, liveCount, w.selected, shadowQueue);
        const uint32_t* shadowQ = shadowQueue;
        launch(exec, "wavefront.shadow", packetCount(shadowCount), [=] CA_HD(size_t p) {
            const size_t q0 = p * kPacket;
            const int m = int(min(kPacket, shadowCount - q0));
            const Ray* rays[kPacket];
            for (int k = 0; k < m; ++k) rays[k] = &w.shadow[shadowQ[q0 + k]].ray;
            uint32_t occluded[kPacket] = {};  // (set for k < m; zeroed to keep g++ -Wmaybe-uninitialized quiet)
            occludedPacket(accel, m, rays, occluded);
            for (int k = 0; k < m; ++k) {
                const uint32_t i = shadowQ[q0 + k];
                addShadowContribution(w.state[i], w.shadow[i], occluded[k] != 0);
            }
        });
        rays += shadowCount;

        // ---- Compaction: the paths still alive form the next bounce's queue, in order.
        liveCount = compactQueue(exec, w.alive, live, liveCount, w.selected, next);
        std::swap(live, next);
    }

    launch(exec, "wavefront.finish", n, [=] CA_HD(size_t i) { samples[begin + i].L = w.state[i].radiance; });
    return rays;
}

/// How a device runs the wavefront (see the file comment): which launches the stages use, how
/// many chunks are traced at once (`slots`), the paths per chunk and the shade stage's prefetch
/// distance. Tuned per device; the images do not depend on any of it.
template <class Exec>
struct WavefrontSchedule {  // a GPU: one chunk as large as allowed, stages as grids
    using StageExec = Exec;
    static size_t slots() { return 1; }
    static size_t chunk(size_t maxPathsInFlight) { return maxPathsInFlight; }
    static constexpr size_t prefetch = 0;
};

template <>
struct WavefrontSchedule<CpuExec> {  // a CPU: one small chunk per thread, stages as serial loops
    using StageExec = SerialExec;
    static size_t slots() { return cpuThreadCount(); }
    /// About 300 bytes per path (state, sampler, hit, shadow ray, queues): 1024 paths take a
    /// third of a core's L2 cache (1 MiB here), leaving the rest to the scene; 1024 beat 2048 and
    /// 4096 on cornell-water (docs/PERFORMANCE.md, 2026-11-26).
    static size_t chunk(size_t maxPathsInFlight) {
        return std::min<size_t>(1024, std::max<size_t>(1, maxPathsInFlight / slots()));
    }
    static constexpr size_t prefetch = 8;
};

/// The buffers of `slots` chunks of `chunk` paths each; slot s owns entries [s·chunk, (s+1)·chunk).
template <class Exec>
struct ChunkBuffers {
    Buffer<PathState> state;
    Buffer<IndependentSampler> sampler;
    Buffer<Hit> hit;
    Buffer<ShadowRay> shadow;
    Buffer<uint32_t> queueA, queueB, shadowQueue, alive, hasShadow, selected;

    void reserve(size_t paths) {
        if (state.size() >= paths) return;
        const Device d = Exec::device();
        state = Buffer<PathState>(d, paths);
        sampler = Buffer<IndependentSampler>(d, paths);
        hit = Buffer<Hit>(d, paths);
        shadow = Buffer<ShadowRay>(d, paths);
        for (Buffer<uint32_t>* b : {&queueA, &queueB, &shadowQueue, &alive, &hasShadow, &selected})
            *b = Buffer<uint32_t>(d, paths);
    }
    Paths slot(size_t s, size_t chunk) {
        const size_t o = s * chunk;
        return Paths{state.data() + o, sampler.data() + o,   hit.data() + o,     shadow.data() + o,
                     alive.data() + o, hasShadow.data() + o, selected.data() + o};
    }
};

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
        using Schedule = wavefront_detail::WavefrontSchedule<Exec>;
        const size_t total = pass.samples.size();
        if (total == 0) return 0;
        // Path ids within a chunk are 32-bit queue entries.
        const size_t chunk = std::min({Schedule::chunk(maxPaths_), total, size_t(0xffffffffu)});
        const size_t chunks = (total + chunk - 1) / chunk;
        const size_t slots = std::min(Schedule::slots(), chunks);
        if constexpr (Exec::kind != DeviceKind::Cpu)
            if (samples_.size() < total) samples_ = Buffer<PixelSample>(Exec::device(), total);
        buffers_.reserve(slots * chunk);
        PixelSample* out = Exec::kind == DeviceKind::Cpu ? pass.samples.data() : samples_.data();
        megakernel_detail::AovOutput aovOut{aovLayout_};
        if (aovs_) {
            if (aovs_->slots() != total || aovs_->channels != aovLayout_.channels)
                throw Error("internal: the AOV pass does not match the sample pass");
            aovTarget_.bind(*aovs_, aovOut.positions, aovOut.values);
        }
        std::atomic<size_t> nextChunk{0};  // chunks are handed to the slots as they free up
        std::atomic<uint64_t> rays{0};
        scene_.visit(Exec{}, [&](const auto& intersector) {
            const auto traceSlot = [&](size_t s) {
                const wavefront_detail::Paths w = buffers_.slot(s, chunk);
                const size_t o = s * chunk;
                for (size_t c; (c = nextChunk.fetch_add(1)) < chunks;) {
                    const size_t begin = c * chunk;
                    rays += wavefront_detail::traceChunk(
                        typename Schedule::StageExec{}, scene_.view(), intersector, settings_, seed,
                        firstSampleIndex, pass.width, pass.samplesPerPixel, begin, std::min(chunk, total - begin),
                        out, w, buffers_.queueA.data() + o, buffers_.queueB.data() + o,
                        buffers_.shadowQueue.data() + o, aovOut, Schedule::prefetch);
                }
            };
            if constexpr (Exec::kind == DeviceKind::Cpu)
                launch(CpuExec{}, "wavefront.chunks", slots, traceSlot, 1);
            else
                traceSlot(0);
        });
        if constexpr (Exec::kind != DeviceKind::Cpu) samples_.copyToHost(pass.span());
        if (aovs_) aovTarget_.copyBack(*aovs_);
        return rays.load();
    }
    size_t sceneBytes() const override { return scene_.bytes(); }
    /// The AOVs come from the first extend stage's hits (aovStage), as the megakernel's do.
    bool shareFirstHits(const AovLayout& layout, AovSamplePass* aovs) override {
        aovLayout_ = layout;
        aovs_ = aovs;
        return true;
    }

private:
    DeviceScene scene_;
    PathSettings settings_;
    size_t maxPaths_;
    Buffer<PixelSample> samples_;  // a GPU's
    wavefront_detail::ChunkBuffers<Exec> buffers_;
    AovLayout aovLayout_;
    AovSamplePass* aovs_ = nullptr;  // the caller's, while it shares first hits
    AovPassTarget<Exec> aovTarget_;
};

}  // namespace caustica
