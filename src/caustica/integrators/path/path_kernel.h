// path_kernel.h — the path tracer's per-sample function, shared by CPU and GPU.
//
// Unidirectional path tracing with next-event estimation, combined with BSDF sampling by multiple
// importance sampling (power heuristic; Veach 1997, ch. 9) and Russian roulette. The meaning of
// max_depth, rr_depth and hide_emitters, and the roulette rule, follow Mitsuba 3's `path`
// integrator so that the same scene converges to the same image in both renderers.
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

/// Radiance arriving along `ray` (a camera ray). `rayCount` is incremented by the number of rays
/// traced (closest-hit and shadow), for statistics.
template <class Intersector, class Sampler>
CA_HD Spectrum pathRadiance(const SceneView& scene, const Intersector& accel, Sampler& sampler,
                            Ray ray, const PathSettings& settings, uint32_t& rayCount) {
    const uint32_t maxDepth = settings.maxDepth < 0 ? 0xffffffffu : uint32_t(settings.maxDepth);
    Spectrum radiance(0), throughput(1);
    Float etaScale = 1;           // product of relative IORs crossed (Mitsuba's roulette uses eta²)
    Float prevBsdfPdf = 1;        // solid-angle pdf of the BSDF sample that produced `ray`
    bool prevBsdfDelta = true;    // camera rays count as delta: their emission is never MIS-weighted
    Vec3f prevP = ray.o;

    for (uint32_t depth = 0; maxDepth > 0; ) {
        Hit hit;
        ++rayCount;
        const bool found = accel.intersect(ray, hit);
        const bool visibleEmitter = !(depth == 0 && settings.hideEmitters);

        // ---- Emission found by the BSDF-sampled (or camera) ray, MIS-weighted against NEE.
        if (!found) {
            if (scene.environmentLight >= 0 && visibleEmitter) {
                Vec3f dir = normalize(ray.d);
                Float w = prevBsdfDelta ? 1 : powerHeuristic(prevBsdfPdf, pdfEnvironmentLight(scene, dir));
                radiance += throughput * environmentRadiance(scene, dir) * w;
            }
            break;
        }
        const SurfaceInteraction si = computeInteraction(scene, ray, hit);
        const Vec3f wo = -normalize(ray.d);
        const int32_t lightIndex = scene.shapes[si.shape].light;
        if (lightIndex >= 0 && visibleEmitter) {
            Spectrum le = emittedRadiance(scene, si, wo);
            if (!le.isBlack()) {
                Float w = prevBsdfDelta ? 1
                                        : powerHeuristic(prevBsdfPdf, pdfAreaLight(scene, uint32_t(lightIndex), prevP, si));
                radiance += throughput * le * w;
            }
        }
        if (depth + 1 >= maxDepth) break;

        const uint32_t bsdf = scene.shapes[si.shape].bsdf;

        // ---- Next-event estimation (skipped for purely specular surfaces).
        if (!isDeltaBsdf(scene.bsdfs, bsdf)) {
            Float uSelect = sampler.get1D();
            Vec2f uLight = sampler.get2D();
            LightSample ls;
            if (sampleLight(scene, si.p, uSelect, uLight, ls) && ls.pdf > 0 && !ls.Le.isBlack()) {
                Spectrum f = evalBsdf(scene.bsdfs, bsdf, si, wo, ls.wi);
                if (!f.isBlack()) {
                    Ray shadow = ls.dist < kInfinity ? spawnRayTo(si.p, si.ng, ls.p, ls.n)
                                                     : spawnRay(si.p, si.ng, ls.wi);
                    ++rayCount;
                    if (!accel.occluded(shadow)) {
                        Float w = ls.delta ? 1 : powerHeuristic(ls.pdf, pdfBsdf(scene.bsdfs, bsdf, si, wo, ls.wi));
                        radiance += throughput * f * ls.Le * (w / ls.pdf);
                    }
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
        if (!sampleBsdf(scene.bsdfs, bsdf, si, wo, uLobe, uDir, bs)) break;
        throughput *= bs.weight;
        etaScale *= bs.eta;
        prevBsdfPdf = bs.pdf;
        prevBsdfDelta = bs.delta;
        prevP = si.p;
        ray = spawnRay(si.p, si.ng, bs.wi);
        ++depth;

        // ---- Russian roulette (Mitsuba 3: survival probability min(max(β)·η², 0.95)).
        const Float throughputMax = throughput.maxValue();
        if (!(throughputMax > 0)) break;
        Float uRoulette = sampler.get1D();
        if (depth >= uint32_t(settings.rrDepth)) {
            Float q = min(throughputMax * etaScale * etaScale, Float(0.95));
            if (uRoulette >= q) break;
            throughput *= 1 / q;
        }
    }
    return radiance;
}

}  // namespace caustica
