// sppm_passes.h — the launches of the photon mappers' driver (sppm_driver.h), each a named free
// function template so that nvcc compiles their CA_HD lambdas for the GPU from this one source.
#pragma once

#include <cmath>
#include <cstdint>
#include <type_traits>

#include "caustica/integrators/lanes.h"
#include "caustica/integrators/megakernel_pass.h"
#include "caustica/integrators/sppm/sppm_kernel.h"
#include "caustica/integrators/sppm/sppm_photon.h"
#include "caustica/integrators/sppm/sppm_photon_store.h"
#include "caustica/integrators/sppm/sppm_visible_bsdf.h"
#include "caustica/parallel/launch.h"
#include "caustica/parallel/prefetch.h"

namespace caustica::sppm_detail {

/// Where the eye pass takes its camera samples: sppm one per pixel with sample index =
/// iteration; ppm `perPixel` per pixel, entry s = pixel · perPixel + j with sample index j.
struct EyeSampling {
    uint32_t perPixel = 1;
    uint64_t iteration = 0;
    bool fixedHitpoints = false;  // ppm
    bool addLd = true;            // false: a ppm resume regenerates the hitpoints only
    Spectrum* radiance = nullptr; // set: each entry's radiance goes here instead (addRadiance adds it)
};

/// Where eye pass entry s puts its results (eyePass).
struct EyeOutputs {
    EyeSampling sampling;
    SppmPixel* stats;
    SppmVisiblePoint* points;
    uint32_t* flags;
    uint32_t* rays;

    CA_HD void write(size_t s, const Spectrum& L, SppmVisiblePoint vp, bool has, uint32_t count) const {
        if (sampling.radiance)
            sampling.radiance[s] = L;
        else if (sampling.addLd)
            sppmAddLd(stats[s], L);
        vp.stat = uint32_t(s);
        points[s] = vp;
        flags[s] = has ? 1u : 0u;
        rays[s] = count;
    }
};

/// Entry s's camera sample: sppm one per pixel with sample index = iteration; ppm `perPixel`
/// per pixel, entry s = pixel · perPixel + j with sample index j.
CA_HD_INLINE CameraSample eyeCameraSample(const Camera& camera, const EyeSampling& sampling, int width, uint64_t seed,
                                          size_t s) {
    const size_t pixel = s / sampling.perPixel;
    const uint64_t sample = sampling.fixedHitpoints ? uint64_t(s % sampling.perPixel) : sampling.iteration;
    return cameraSample(camera, pixel, width, sample, seed);
}

/// traceLanes' policy for eye pass entries first + item (eyePass).
template <int L>
struct EyeLanes {
    const SceneView& view;
    const PathSettings& path;
    Float specularBelow;
    const EmitterBoxes& emitters;
    uint64_t seed;
    int width;
    size_t first;
    const EyeOutputs& out;
    SppmEyeState eyes[L];
    IndependentSampler samplers[L];
    ShadowRay shadows[L];
    SppmVisiblePoint points[L];
    bool hasPoint[L];
    uint32_t rays[L];
    size_t entries[L];

    CA_HD bool begin(int lane, size_t item) {
        const size_t s = first + item;
        const CameraSample c = eyeCameraSample(view.camera, out.sampling, width, seed, s);
        samplers[lane] = c.sampler;
        points[lane] = SppmVisiblePoint{};
        hasPoint[lane] = false;
        rays[lane] = 0;
        entries[lane] = s;
        if (sppmStartEye(eyes[lane], c.ray, path, uint32_t(kSppmDepthCap))) return true;
        end(lane);
        return false;
    }
    CA_HD const Ray& ray(int lane) const { return eyes[lane].path.ray; }
    CA_HD bool hit(int lane, const Hit* hit, const Ray*& shadow) {
        ++rays[lane];
        bool hasShadow = false;
        const bool more = sppmEyeHit(view, samplers[lane], specularBelow, emitters, eyes[lane], hit, shadows[lane],
                                     hasShadow, points[lane], hasPoint[lane]);
        if (hasShadow) shadow = &shadows[lane].ray;
        return more;
    }
    CA_HD void shadow(int lane, bool occluded) {
        ++rays[lane];
        addShadowContribution(eyes[lane].path, shadows[lane], occluded);
    }
    CA_HD void end(int lane) {
        out.write(entries[lane], eyes[lane].path.radiance, points[lane], hasPoint[lane], rays[lane]);
    }
    CA_HD void move(int from, int to) {
        eyes[to] = eyes[from];
        samplers[to] = samplers[from];
        shadows[to] = shadows[from];
        points[to] = points[from];
        hasPoint[to] = hasPoint[from];
        rays[to] = rays[from];
        entries[to] = entries[from];
    }
};

/// Eye pass entries [first, first + count) (a work item of eyePass): side by side where the
/// intersector answers packets, else one after the other with sppmEyePath.
template <class Intersector>
CA_HD void eyeEntries(const SceneView& view, const Intersector& accel, const PathSettings& path, Float specularBelow,
                      const EmitterBoxes& emitters, uint64_t seed, int width, const EyeOutputs& out, size_t first,
                      size_t count) {
    constexpr int L = laneCount<Intersector>();
    if constexpr (L == 1) {
        for (size_t s = first; s < first + count; ++s) {
            CameraSample c = eyeCameraSample(view.camera, out.sampling, width, seed, s);
            SppmVisiblePoint vp;
            bool has = false;
            uint32_t rays = 0;
            const Spectrum radiance = sppmEyePath(view, accel, c.sampler, c.ray, path, uint32_t(kSppmDepthCap),
                                                  specularBelow, emitters, vp, has, rays);
            out.write(s, radiance, vp, has, rays);
        }
    } else {
        EyeLanes<L> lanes{view, path, specularBelow, emitters, seed, width, first, out, {}, {}, {}, {}, {}, {}, {}};
        traceLanes(view, accel, count, lanes);
    }
}

/// The eye pass: entry s's eye path (sppmEyePath), its Ld, visible point, flag and rays. With
/// Embree on the host a work item takes 64 entries, 16 in flight (lanes.h), each path bit for bit
/// its sppmEyePath.
template <class Exec, class Intersector>
void eyePass(Exec exec, const SceneView& view, const Intersector& accel, PathSettings path, Float specularBelow,
             EmitterBoxes emitters, uint64_t seed, EyeSampling sampling, int width, size_t entries, SppmPixel* stats,
             SppmVisiblePoint* points, uint32_t* flags, uint32_t* rays) {
    constexpr size_t G = laneCount<Intersector>() > 1 ? 64 : 1;
    const EyeOutputs out{sampling, stats, points, flags, rays};
    launch(
        exec, "sppm.eye", (entries + G - 1) / G,
        [=] CA_HD(size_t g) {
            const size_t first = g * G;
            eyeEntries(view, accel, path, specularBelow, emitters, seed, width, out, first, min(G, entries - first));
        },
        G > 1 ? 1 : 16);
}

/// Adds the radiance an eye pass kept aside (EyeSampling::radiance) to the entries' Ld.
template <class Exec>
void addRadiance(Exec exec, size_t entries, const Spectrum* radiance, SppmPixel* stats) {
    launch(exec, "sppm.add-ld", entries, [=] CA_HD(size_t s) { sppmAddLd(stats[s], radiance[s]); });
}

/// Morton keys of the listed visible points (keys[j] for list[j]) in the scene's box.
template <class Exec>
void mortonKeys(Exec exec, size_t count, const uint32_t* list, const SppmVisiblePoint* points, Vec3f lo,
                Vec3f invExtent, uint32_t* keys) {
    launch(exec, "sppm.morton", count,
           [=] CA_HD(size_t j) { keys[j] = sppmMorton(points[list[j]].si.p, lo, invExtent); });
}

/// The pixel footprint at each listed visible point (straight distance to its eye: the camera, or
/// on a stereo rig the eye of the point's pixel), into `out`. Entry s is pixel s / perPixel of a
/// film `width` pixels wide.
template <class Exec>
void footprints(Exec exec, size_t count, const uint32_t* list, const SppmVisiblePoint* points, Camera camera,
                int width, uint32_t perPixel, Float* out) {
    launch(exec, "sppm.footprint", count, [=] CA_HD(size_t j) {
        const SppmVisiblePoint& vp = points[list[j]];
        const Float filmX = Float((vp.stat / perPixel) % uint32_t(width));
        const Vec3f eye = cameraEyePosition(camera, filmX);
        out[j] = pixelFootprint(camera, length(vp.si.p - eye));
    });
}

/// A CPU loop over the list (Morton order) reads the visible points and their statistics out of
/// order, one miss each per item with little work in between to hide it: start loading the
/// records of item j + kSppmListPrefetch (every cache line of the visible point, its statistics
/// entry when `stats` is set). Nothing on a GPU.
inline constexpr size_t kSppmListPrefetch = 8;
CA_HD_INLINE void prefetchListItem(size_t j, size_t count, const uint32_t* list, const SppmVisiblePoint* points,
                                   const SppmPixel* stats) {
#if !CA_GPU_CODE
    if (j + kSppmListPrefetch >= count) return;
    const uint32_t s = list[j + kSppmListPrefetch];
    const char* vp = reinterpret_cast<const char*>(points + s);
    for (size_t b = 0; b < sizeof(SppmVisiblePoint); b += 64) prefetchRead(vp + b);
    prefetchRead(vp + sizeof(SppmVisiblePoint) - 1);
    if (stats) prefetchRead(&stats[s].radius);  // entry s: stats[s]
#else
    (void)j, (void)count, (void)list, (void)points, (void)stats;
#endif
}

template <class Exec>
void gatherPoints(Exec exec, size_t count, const uint32_t* list, const SppmVisiblePoint* points,
                  const SppmPixel* stats, Vec3f* positions, Float* radii) {
    launch(exec, "sppm.points", count, [=] CA_HD(size_t j) {
        prefetchListItem(j, count, list, points, stats);
        const SppmVisiblePoint& vp = points[list[j]];
        positions[j] = vp.si.p;
        radii[j] = Float(stats[vp.stat].radius);
    });
}

/// Photon path i of `iteration` (its own stream), its rays counted per block of 1024 paths.
template <class Intersector, class Sink>
CA_HD void photonPath(const SceneView& view, const Intersector& accel, size_t i, uint64_t iteration, uint64_t seed,
                      const SppmPhotonRules& rules, uint64_t* rayBlocks, Sink&& sink) {
    IndependentSampler sampler = photonSampler(i, iteration, seed);
    uint32_t rays = 0;
    sppmTracePhoton(view, accel, sampler, rules, rays, sink);
    sppmAtomicAdd(rayBlocks + i / 1024, rays);
}

/// Photon paths a launch item of the photon pass takes: a group, where the intersector answers
/// packets of rays (Embree on the host), else one (a GPU thread, the own BVH).
template <class Intersector>
constexpr size_t photonPathsPerItem() {
    return laneCount<Intersector>() > 1 ? 64 : 1;
}

/// traceLanes' policy for photon paths first + item of a pass (photonPathGroup).
template <int L, class Sink>
struct PhotonLanes {
    const SceneView& view;
    const SppmPhotonRules& rules;
    uint64_t iteration, seed;
    size_t first;
    Sink& sink;
    SppmPhotonPath paths[L];
    IndependentSampler samplers[L];
    uint32_t rays = 0;

    CA_HD bool begin(int lane, size_t item) {
        samplers[lane] = photonSampler(first + item, iteration, seed);
        return sppmStartPhoton(view, samplers[lane], paths[lane]) && sppmPhotonWantsRay(paths[lane], rules.maxDepth);
    }
    CA_HD const Ray& ray(int lane) const { return paths[lane].ray; }
    CA_HD bool hit(int lane, const Hit* hit, const Ray*&) {
        ++rays;
        return hit && sppmPhotonHit(view, samplers[lane], rules, paths[lane], *hit, sink);
    }
    CA_HD void shadow(int, bool) {}
    CA_HD void end(int) {}
    CA_HD void move(int from, int to) {
        paths[to] = paths[from];
        samplers[to] = samplers[from];
    }
};

/// Photon paths [first, first + count) side by side (lanes.h): each path takes its hits with the
/// one-path loop's step function (sppmPhotonHit) and its own stream, so it makes the photons it
/// makes traced alone; only the order of the sink's calls differs. With packets of one ray it is
/// photonPath for each. Rays are counted in block first / 1024.
template <class Intersector, class Sink>
CA_HD void photonPathGroup(const SceneView& view, const Intersector& accel, size_t first, size_t count,
                           uint64_t iteration, uint64_t seed, const SppmPhotonRules& rules, uint64_t* rayBlocks,
                           Sink&& sink) {
    constexpr int L = laneCount<Intersector>();
    if constexpr (L == 1) {
        for (size_t i = first; i < first + count; ++i)
            photonPath(view, accel, i, iteration, seed, rules, rayBlocks, sink);
    } else {
        PhotonLanes<L, std::remove_reference_t<Sink>> lanes{view, rules, iteration, seed, first, sink, {}, {}, 0};
        traceLanes(view, accel, count, lanes);
        sppmAtomicAdd(rayBlocks + first / 1024, lanes.rays);
    }
}

/// Direction "deposit": each photon of [first, first + photons) adds into every visible point
/// whose sphere covers its hit (`lookup` over the visible points' spheres; j indexes `list`).
template <class Exec, class Intersector, class Lookup>
void depositPhotons(Exec exec, const SceneView& view, const Intersector& accel, const Lookup& lookup,
                    const SppmVisiblePoint* points, const uint32_t* list, SppmPhotonRules rules,
                    SppmFixedPoint fixed, uint64_t seed, uint64_t iteration, uint64_t first,
                    uint64_t photons, uint64_t* phi, uint64_t* m, uint64_t* rayBlocks) {
    constexpr size_t G = photonPathsPerItem<Intersector>();
    launch(
        exec, "sppm.photons", size_t((photons + G - 1) / G),
        [=] CA_HD(size_t g) {
            const size_t from = size_t(first) + g * G, count = min(G, size_t(first + photons) - from);
            photonPathGroup(view, accel, from, count, iteration, seed, rules, rayBlocks,
                            [&](const SurfaceInteraction& si, Vec3f wo, const Spectrum& flux, uint32_t k) {
                                lookup.forEachSphereCovering(si.p, [&](uint32_t j) {
                                    const SppmVisiblePoint& vp = points[list[j]];
                                    const Spectrum d = sppmContribution(view, vp, si.ng, wo, flux, k, rules.maxDepth);
                                    if (!d.isBlack()) sppmDeposit(fixed, d, phi + 3 * size_t(vp.stat), m + vp.stat);
                                });
                            });
        },
        G > 1 ? 1 : 16);
}

/// Direction "gather", first half: each photon path of [first, first + photons) appends its
/// photons to `store` (sppm_photon_store.h: in batches, with their sort keys when store.keys is
/// set; store.counter counts them all, so the caller sees an overflow and traces again).
template <class Exec, class Intersector>
void storePhotons(Exec exec, const SceneView& view, const Intersector& accel, SppmPhotonRules rules,
                  uint64_t seed, uint64_t iteration, uint64_t first, uint64_t photons,
                  SppmPhotonStore store, uint64_t* rayBlocks) {
    constexpr size_t G = photonPathsPerItem<Intersector>();
    launch(
        exec, "sppm.store", size_t((photons + G - 1) / G),
        [=] CA_HD(size_t g) {
            const size_t from = size_t(first) + g * G, count = min(G, size_t(first + photons) - from);
            SppmPhotonBatch batch(store);
            photonPathGroup(view, accel, from, count, iteration, seed, rules, rayBlocks,
                            [&](const SurfaceInteraction& si, Vec3f wo, const Spectrum& flux, uint32_t k) {
                                batch.add(SppmPhoton{si.p, wo, si.ng, flux, k});
                            });
            batch.flush();
        },
        G > 1 ? 1 : 16);
}

/// Copies the photons into `order` (sorted: order = the sort's permutation; else identity) and
/// writes their positions. The permutation reads the store out of order, so a CPU starts loading
/// the record kSppmArrangePrefetch items ahead (both its cache lines; nothing on a GPU).
inline constexpr size_t kSppmArrangePrefetch = 16;
template <class Exec>
void arrangePhotons(Exec exec, size_t count, const SppmPhoton* from, const uint32_t* order, SppmPhoton* to,
                    Vec3f* positions) {
    launch(exec, "sppm.photon-arrange", count, [=] CA_HD(size_t i) {
        if (order && i + kSppmArrangePrefetch < count) {
            const SppmPhoton* ahead = from + order[i + kSppmArrangePrefetch];
            prefetchRead(ahead);
            prefetchRead(reinterpret_cast<const char*>(ahead + 1) - 1);
        }
        const SppmPhoton ph = from[order ? order[i] : i];
        to[i] = ph;
        positions[i] = ph.p;
    });
}

/// Direction "gather", second half: every listed visible point sums the photons within its
/// radius (`lookup` over the photon positions; radii[j]: list[j]'s radius, gatherPoints). Each
/// statistics entry has one visible point, so no atomics: the fixed-point sum is written once.
template <class Exec, class Lookup>
void gatherPhotons(Exec exec, const SceneView& view, const Lookup& lookup, const SppmPhoton* photons,
                   const SppmVisiblePoint* points, const uint32_t* list, size_t count, const Float* radii,
                   uint32_t maxDepth, SppmFixedPoint fixed, uint64_t* phi, uint64_t* m) {
    launch(
        exec, "sppm.gather", count,
        [=] CA_HD(size_t j) {
            prefetchListItem(j, count, list, points, nullptr);
            const SppmVisiblePoint& vp = points[list[j]];
            const SppmVisibleBsdf bsdf(view.bsdfs, vp);  // resolved once for all its photons
            const auto evalAt = [&](Vec3f wi) { return bsdf.eval(wi); };
            uint64_t sum[3] = {0, 0, 0};
            uint64_t found = 0;
            lookup.forEachPointWithin(vp.si.p, radii[j], [&](uint32_t i) {
                const SppmPhoton& ph = photons[i];
                const Spectrum d = sppmContributionWith(vp, evalAt, ph.ng, ph.wo, ph.flux, ph.depth, maxDepth);
                if (d.isBlack()) return;
                sum[0] += fixed.toUnits(d.r);
                sum[1] += fixed.toUnits(d.g);
                sum[2] += fixed.toUnits(d.b);
                ++found;
            });
            for (int c = 0; c < 3; ++c) phi[3 * size_t(vp.stat) + c] = sum[c];
            m[vp.stat] = found;
        },
        16);
}

template <class Exec>
void updateStats(Exec exec, size_t entries, double alpha, bool global, uint64_t iteration, SppmFixedPoint fixed,
                 SppmPixel* stats, uint64_t* phi, uint64_t* m) {
    launch(exec, "sppm.update", entries, [=] CA_HD(size_t p) {
        double flux[3];
        for (int c = 0; c < 3; ++c) {
            flux[c] = double(phi[3 * p + c]) / fixed.scale;
            phi[3 * p + c] = 0;
        }
        if (global)
            sppmUpdatePixelGlobal(stats[p], flux, m[p], alpha, iteration);
        else
            sppmUpdatePixel(stats[p], flux, m[p], alpha);
        m[p] = 0;
    });
}

template <class Exec>
void initStats(Exec exec, size_t entries, double radius, SppmPixel* stats, uint64_t* phi, uint64_t* m) {
    launch(exec, "sppm.init", entries, [=] CA_HD(size_t p) {
        stats[p] = SppmPixel{};
        stats[p].radius = radius;
        for (int c = 0; c < 3; ++c) phi[3 * p + c] = 0;
        m[p] = 0;
    });
}

template <class Exec>
void zeroCounters(Exec exec, size_t n, uint64_t* counters) {
    launch(exec, "sppm.zero", n, [=] CA_HD(size_t i) { counters[i] = 0; });
}

}  // namespace caustica::sppm_detail
