#include "caustica/integrators/path/wavefront.h"

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "caustica/parallel/device.h"
#include "caustica/parallel/primitives.h"
#include "caustica/scene/camera.h"
#include "caustica/util/error.h"
#include "caustica/util/rng.h"
#include "caustica/util/span.h"

namespace caustica {
namespace {

/// The paths in flight, struct-of-arrays by record, indexed by path id within the chunk. Queues
/// hold path ids; flags and `selected` are indexed by position within the queue being compacted.
struct WavefrontPaths {
    std::vector<PathState> state;
    std::vector<IndependentSampler> sampler;
    std::vector<Hit> hit;
    std::vector<ShadowRay> shadow;
    std::vector<uint32_t> live, next, shadowQueue;  // queues of path ids
    std::vector<uint32_t> alive, hasShadow;          // per queue position: 0 or 1
    std::vector<uint32_t> selected;                  // compacted queue positions

    explicit WavefrontPaths(size_t n)
        : state(n), sampler(n), hit(n), shadow(n), live(n), next(n), shadowQueue(n), alive(n),
          hasShadow(n), selected(n) {}
};

/// Keeps the entries of `queue[0, count)` whose flag is set, in order, writing them to `out`;
/// returns how many. (Compaction of the flags, then a gather: the GPU's form too.)
uint32_t compactQueue(const Device& device, WavefrontPaths& w, const std::vector<uint32_t>& flags,
                      const std::vector<uint32_t>& queue, size_t count,
                      std::vector<uint32_t>& out) {
    const uint32_t kept = compactIndices(device, Span<const uint32_t>(flags.data(), count),
                                         Span<uint32_t>(w.selected.data(), count));
    parallelFor(device, "wavefront.gather", kept,
                [&](size_t q) { out[q] = queue[w.selected[q]]; }, 256);
    return kept;
}

/// Traces the paths with pass slots [begin, begin + n) to completion; returns the rays traced.
template <class Intersector>
uint64_t traceChunk(const SceneView& scene, const Intersector& accel, const PathSettings& settings,
                    uint64_t seed, int firstSampleIndex, SamplePass& pass, size_t begin, size_t n,
                    WavefrontPaths& w) {
    const Device device = Device::cpu();
    const size_t k = size_t(pass.samplesPerPixel), width = size_t(pass.width);
    uint64_t rays = 0;

    // ---- Generate: camera rays; the sample's film position goes straight to its pass slot.
    parallelFor(device, "wavefront.generate", n, [&](size_t i) {
        const size_t slot = begin + i, pixel = slot / k, s = slot % k;
        const int x = int(pixel % width), y = int(pixel / width);
        IndependentSampler& sampler = w.sampler[i];
        sampler = IndependentSampler(pixel, uint64_t(firstSampleIndex) + s, seed);
        Vec2f jitter = sampler.get2D();
        Vec2f pos(Float(x) + jitter.x, Float(y) + jitter.y);
        pass.samples[slot].pos = pos;
        w.live[i] = uint32_t(i);
        w.alive[i] = startPath(w.state[i], sampleCameraRay(scene.camera, pos, sampler), settings);
    });
    size_t liveCount = compactQueue(device, w, w.alive, w.live, n, w.next);
    std::swap(w.live, w.next);

    while (liveCount > 0) {
        // ---- Extend: closest hit of every live path's ray (`alive` holds "found" until shade).
        parallelFor(device, "wavefront.extend", liveCount, [&](size_t j) {
            const uint32_t i = w.live[j];
            w.hit[i] = Hit{};
            w.alive[j] = accel.intersect(w.state[i].ray, w.hit[i]);
        });
        rays += liveCount;

        // ---- Shade: emission, NEE sample, BSDF sample, roulette (or the miss of the scene).
        parallelFor(device, "wavefront.shade", liveCount, [&](size_t j) {
            const uint32_t i = w.live[j];
            bool shadowRay = false;
            if (w.alive[j])
                w.alive[j] = shadeHit(scene, w.state[i], w.hit[i], w.sampler[i], settings,
                                      w.shadow[i], shadowRay);
            else
                missPath(scene, w.state[i], settings);
            w.hasShadow[j] = shadowRay;
        });

        // ---- Shadow: any-hit test of the NEE samples, over the queue of paths that made one.
        const size_t shadowCount =
            compactQueue(device, w, w.hasShadow, w.live, liveCount, w.shadowQueue);
        parallelFor(device, "wavefront.shadow", shadowCount, [&](size_t q) {
            const uint32_t i = w.shadowQueue[q];
            addShadowContribution(w.state[i], w.shadow[i], accel.occluded(w.shadow[i].ray));
        });
        rays += shadowCount;

        // ---- Compaction: the paths still alive form the next bounce's queue, in order.
        liveCount = compactQueue(device, w, w.alive, w.live, liveCount, w.next);
        std::swap(w.live, w.next);
    }

    parallelFor(device, "wavefront.finish", n,
                [&](size_t i) { pass.samples[begin + i].L = w.state[i].radiance; });
    return rays;
}

}  // namespace

size_t wavefrontBytesPerPath() {
    return sizeof(PathState) + sizeof(IndependentSampler) + sizeof(Hit) + sizeof(ShadowRay) +
           6 * sizeof(uint32_t);
}

uint64_t renderPathPassWavefront(const Scene& scene, const Accel& accel,
                                 const PathSettings& settings, uint64_t seed, int firstSampleIndex,
                                 SamplePass& pass, size_t maxPathsInFlight) {
    if (maxPathsInFlight == 0) throw Error("wavefront: maxPathsInFlight must be positive");
    const SceneView view = scene.view();
    const size_t total = pass.samples.size();
    // Path ids within a chunk are 32-bit queue entries.
    const size_t chunk = std::min({maxPathsInFlight, total, size_t(0xffffffffu)});
    if (chunk == 0) return 0;
    WavefrontPaths paths(chunk);
    uint64_t rays = 0;
    accel.visit([&](const auto& intersector) {
        for (size_t begin = 0; begin < total; begin += chunk) {
            const size_t n = std::min(chunk, total - begin);
            rays += traceChunk(view, intersector, settings, seed, firstSampleIndex, pass, begin, n,
                               paths);
        }
    });
    return rays;
}

}  // namespace caustica
