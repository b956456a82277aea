// path_kernel.h — the path tracer's per-path step functions, shared by CPU and GPU and by both
// execution modes.
//
// Unidirectional path tracing with next-event estimation, combined with BSDF sampling by multiple
// importance sampling (power heuristic; Veach 1997, ch. 9) and Russian roulette. The meaning of
// max_depth, rr_depth and hide_emitters, and the roulette rule, follow Mitsuba 3's `path`
// integrator so that the same scene converges to the same image in both renderers.
//
// A path is a `PathState` advanced by a few step functions:
//   startPath  camera ray -> state
//   (extend)   closest hit of state.ray: the caller's intersector
//   missPath   the ray left the scene: environment emission, path ends
//   shadeHit   emission at the hit, one NEE sample (-> ShadowRay), BSDF sampling, roulette
//   (shadow)   any-hit test of the ShadowRay: the caller's intersector
//   addShadowContribution  the NEE sample's contribution if the shadow ray was unoccluded
// `pathRadiance` (the megakernel: one work item traces a whole path) is a loop over them; the
// wavefront driver (wavefront_pass.h) runs each step as its own kernel over a queue of live paths.
// Both draw the same random numbers in the same order and add radiance in the same order, so
// they produce bit-identical images.
//
// Templated on the intersector (own BVH, Embree) and on the sampler (independent, or a Metropolis
// sampler that replays primary samples): the sampling code itself is never duplicated.
#pragma once

#include <cstdint>

#include "caustica/scene/bsdf.h"
#include "caustica/scene/interaction.h"
#include "caustica/scene/light.h"
#include "caustica/util/sampling.h"

namespace caustica {

struct PathSettings {
    int maxDepth = -1;          // longest path in segments; -1 = unbounded
    int rrDepth = 5;            // Russian roulette starts at this depth
    bool hideEmitters = false;  // emitters seen directly by the camera render black
};

/// Everything a path carries from one bounce to the next (the sampler's state is kept by the
/// caller: a plain `IndependentSampler` stored next to it in the wavefront, a reference in the
/// megakernel, so that samplers which are not plain data work too).
struct PathState {
    Ray ray;                    // the ray to trace next (camera ray, then BSDF-sampled rays)
    Spectrum throughput{1};     // product of BSDF weights (and roulette compensation) so far
    Spectrum radiance{0};       // radiance gathered so far
    Vec3f prevP;                // origin of `ray`, for the MIS weight of an area light it hits
    Float etaScale = 1;         // product of relative IORs crossed (Mitsuba's roulette uses eta²)
    Float prevBsdfPdf = 1;      // solid-angle pdf of the BSDF sample that produced `ray`
    uint32_t depth = 0;         // segments traced before `ray`
    bool prevBsdfDelta = true;  // camera rays count as delta: their emission is never MIS-weighted
};

/// An NEE sample waiting for its visibility test: `contribution` is added to the path's radiance
/// when `ray` is unoccluded.
struct ShadowRay {
    Ray ray;
    Spectrum contribution;
};

CA_HD_INLINE uint32_t maxDepthOf(const PathSettings& settings) {
    return settings.maxDepth < 0 ? 0xffffffffu : uint32_t(settings.maxDepth);
}

/// Starts a path along the camera ray `ray`. Returns false when no segment may be traced at all
/// (max_depth = 0): the path's radiance is then zero.
CA_HD_INLINE bool startPath(PathState& path, const Ray& ray, const PathSettings& settings) {
    path = PathState{};
    path.ray = ray;
    path.prevP = ray.o;
    return maxDepthOf(settings) > 0;
}

/// The path's ray found nothing: adds the environment's emission, MIS-weighted against NEE. The
/// path ends here.
CA_HD_INLINE void missPath(const SceneView& scene, PathState& path, const PathSettings& settings) {
    const bool visibleEmitter = !(path.depth == 0 && settings.hideEmitters);
    if (scene.environmentLight >= 0 && visibleEmitter) {
        Vec3f dir = normalize(path.ray.d);
        Float w = path.prevBsdfDelta ? 1
                                     : powerHeuristic(path.prevBsdfPdf, pdfEnvironmentLight(scene, dir));
        path.radiance += path.throughput * environmentRadiance(scene, dir) * w;
    }
}

/// The path's ray hit `hit`: adds the emission found there (MIS-weighted against NEE), draws one
/// NEE sample (returned in `shadow` when `*hasShadow`, to be tested and then given to
/// addShadowContribution before the path's next step), samples the BSDF to continue the path and
/// plays Russian roulette (Mitsuba 3: survival probability min(max(β)·η², 0.95)). Returns whether
/// the path continues along `path.ray`. Draws 1+2 (NEE) + 1+2 (BSDF) + 1 (roulette) numbers per
/// bounce, the NEE ones even at delta surfaces (a fixed layout per bounce helps Metropolis).
/// shadeHitAt: the same step at an interaction the caller already built (computeInteraction of
/// path.ray and its hit), so that a caller that keeps the interaction does not build it twice.
template <class Sampler>
CA_HD_INLINE bool shadeHitAt(const SceneView& scene, PathState& path, const SurfaceInteraction& si, Sampler& sampler,
                             const PathSettings& settings, ShadowRay& shadow, bool& hasShadow) {
    hasShadow = false;
    const uint32_t maxDepth = maxDepthOf(settings);
    const Vec3f wo = -normalize(path.ray.d);

    // ---- Emission found by the BSDF-sampled (or camera) ray, MIS-weighted against NEE.
    const bool visibleEmitter = !(path.depth == 0 && settings.hideEmitters);
    const int32_t lightIndex = scene.shapes[si.shape].light;
    if (lightIndex >= 0 && visibleEmitter) {
        Spectrum le = emittedRadiance(scene, si, wo);
        if (!le.isBlack()) {
            Float w = path.prevBsdfDelta
                          ? 1
                          : powerHeuristic(path.prevBsdfPdf,
                                           pdfAreaLight(scene, uint32_t(lightIndex), path.prevP, si));
            path.radiance += path.throughput * le * w;
        }
    }
    if (path.depth + 1 >= maxDepth) return false;

    const uint32_t bsdf = scene.shapes[si.shape].bsdf;
    const BsdfAtVertex bsdfAt(scene.bsdfs, bsdf, si, wo);  // resolved once for NEE and sampling

    // ---- Next-event estimation (skipped for purely specular surfaces).
    if (!isDeltaBsdf(scene.bsdfs, bsdf)) {
        Float uSelect = sampler.get1D();
        Vec2f uLight = sampler.get2D();
        LightSample ls;
        if (sampleLight(scene, si.p, uSelect, uLight, ls) && ls.pdf > 0 && !ls.Le.isBlack()) {
            Float bsdfPdf;
            const Spectrum f = bsdfAt.evalPdf(ls.wi, bsdfPdf);
            if (!f.isBlack()) {
                shadow.ray = ls.dist < kInfinity ? spawnRayTo(si.p, si.ng, ls.p, ls.n)
                                                 : spawnRay(si.p, si.ng, ls.wi);
                Float w = ls.delta ? 1 : powerHeuristic(ls.pdf, bsdfPdf);
                shadow.contribution = path.throughput * f * ls.Le * (w / ls.pdf);
                hasShadow = true;
            }
        }
    } else {
        // Keep the random-number layout of every bounce the same (useful to Metropolis).
        sampler.get1D();
        sampler.get2D();
    }

    // ---- BSDF sampling: continue the path.
    Float uLobe = sampler.get1D();
    Vec2f uDir = sampler.get2D();
    BsdfSample bs;
    if (!bsdfAt.sample(uLobe, uDir, bs)) return false;
    path.throughput *= bs.weight;
    path.etaScale *= bs.eta;
    path.prevBsdfPdf = bs.pdf;
    path.prevBsdfDelta = bs.delta;
    path.prevP = si.p;
    spawnRayInto(path.ray, si.p, si.ng, bs.wi);
    ++path.depth;

    // ---- Russian roulette (Mitsuba 3: survival probability min(max(β)·η², 0.95)).
    const Float throughputMax = path.throughput.maxValue();
    if (!(throughputMax > 0)) return false;
    Float uRoulette = sampler.get1D();
    if (path.depth >= uint32_t(settings.rrDepth)) {
        Float q = min(throughputMax * path.etaScale * path.etaScale, Float(0.95));
        if (uRoulette >= q) return false;
        path.throughput *= 1 / q;
    }
    return true;
}

template <class Sampler>
CA_HD bool shadeHit(const SceneView& scene, PathState& path, const Hit& hit, Sampler& sampler,
                    const PathSettings& settings, ShadowRay& shadow, bool& hasShadow) {
    return shadeHitAt(scene, path, computeInteraction(scene, path.ray, hit), sampler, settings, shadow, hasShadow);
}

/// Result of the visibility test of a ShadowRay that shadeHit produced for this path.
CA_HD_INLINE void addShadowContribution(PathState& path, const ShadowRay& shadow, bool occluded) {
    if (!occluded) path.radiance += shadow.contribution;
}

/// Radiance arriving along `ray` (a camera ray): the megakernel form, one work item tracing the
/// whole path. `rayCount` is incremented by the number of rays traced (closest-hit and shadow).
template <class Intersector, class Sampler>
CA_HD Spectrum pathRadiance(const SceneView& scene, const Intersector& accel, Sampler& sampler,
                            Ray ray, const PathSettings& settings, uint32_t& rayCount) {
    PathState path;
    if (!startPath(path, ray, settings)) return path.radiance;
    for (;;) {
        Hit hit;
        ++rayCount;
        if (!accel.intersect(path.ray, hit)) {
            missPath(scene, path, settings);
            break;
        }
        ShadowRay shadow;
        bool hasShadow;
        const bool alive = shadeHit(scene, path, hit, sampler, settings, shadow, hasShadow);
        if (hasShadow) {
            ++rayCount;
            addShadowContribution(path, shadow, accel.occluded(shadow.ray));
        }
        if (!alive) break;
    }
    return path.radiance;
}

}  // namespace caustica
