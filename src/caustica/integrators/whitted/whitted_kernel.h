// whitted_kernel.h — Whitted ray tracing (Whitted 1980, "An Improved Illumination Model for
// Shaded Display"), shared by CPU and GPU: the fast preview of issue 21 (seed 002).
//
// Along each camera ray, at every hit:
//   - the emission found there (seen directly or through a chain of specular bounces);
//   - at a surface with a smooth (non-delta) BSDF part: direct light, one sample of EVERY
//     emitter in the scene (area lights sampled by area / visible cone, point, spot,
//     directional, environment) with a shadow ray each — the classic Whitted light loop, no MIS
//     (nothing else in this integrator finds those paths, so the weight is 1);
//   - through every delta lobe of the BSDF (bsdf_delta_lobes.h: mirror reflection, dielectric
//     reflection AND refraction weighted by Fresnel, thin glass, a plastic's coating, masks'
//     transparency): a new ray, traced the same way. Rough / glossy lobes get direct light only;
//     there is no indirect diffuse or glossy light.
// The recursion is a depth-first walk with an explicit stack of kWhittedStackSize pending rays
// (no recursion on a GPU). A hit's lobes all go on the stack while they fit (the deterministic
// split of classic Whitted); when they do not, ONE lobe is chosen at random, with probability
// proportional to its mean weight times η² (for glass: by Fresnel, as sampleBsdf), and its weight
// divided by that probability (unbiased, as the path tracer's BSDF sampling). So the stack bound
// changes the noise, never the expectation.
//
// max_depth, rr_depth and hide_emitters mean what they mean for the path tracer (Mitsuba 3's
// path): max_depth counts ray segments (-1 unbounded; 1 = emitters seen directly; 2 = direct light
// at the first hit), Russian roulette from rr_depth on each branch (survival probability
// min(max(β)·η², 0.95)), hide_emitters blackens emitters seen directly by the camera. So on a
// scene whose only light paths are specular chains ending in direct light, whitted and path
// converge to the same image.
//
// Random numbers come from the per-camera-sample sampler (counter-based): per smooth hit one 2D
// number per emitter, per branch past rr_depth one for roulette, per overflowing split one. They
// depend on the pixel and sample only, never on threads.
#pragma once

#include <cstdint>

#include "caustica/integrators/path/path_kernel.h"
#include "caustica/scene/bsdf.h"
#include "caustica/scene/bsdf_delta_lobes.h"
#include "caustica/scene/interaction.h"
#include "caustica/scene/light.h"

namespace caustica {

/// max_depth, rr_depth, hide_emitters: the path tracer's three parameters, with their meaning.
using WhittedSettings = PathSettings;

/// Pending rays of one camera sample. Depth-first, a binary split (glass) leaves at most one
/// sibling per level on the stack, so splits stay deterministic for about this many levels.
constexpr int kWhittedStackSize = 16;

/// A ray waiting to be traced, with what its radiance is multiplied by.
struct WhittedBranch {
    Ray ray;
    Spectrum throughput;
    Float etaScale;  // product of the relative IORs crossed (roulette uses η², as the path tracer)
    uint32_t depth;  // segments traced before `ray`
};

/// The shadow ray from surface point `si` to the light sample `ls`: to its point, or along ls.wi
/// without end for the environment and directional lights.
CA_HD_INLINE Ray shadowRayTo(const SurfaceInteraction& si, const LightSample& ls) {
    return ls.dist < kInfinity ? spawnRayTo(si.p, si.ng, ls.p, ls.n) : spawnRay(si.p, si.ng, ls.wi);
}

/// Direct light at a smooth surface: one sample of every emitter, each with a shadow ray.
template <class Intersector, class Sampler>
CA_HD Spectrum whittedDirectLight(const SceneView& scene, const Intersector& accel,
                                  Sampler& sampler, const SurfaceInteraction& si, Vec3f wo,
                                  uint32_t bsdf, uint32_t& rayCount) {
    Spectrum sum(0);
    const uint32_t lights = uint32_t(scene.lights.size());
    for (uint32_t i = 0; i < lights; ++i) {
        const Vec2f u = sampler.get2D();
        LightSample ls;
        // Selection probability 1: every light is sampled.
        if (!sampleLightIndex(scene, i, 1, si.p, u, ls) || !(ls.pdf > 0) || ls.Le.isBlack())
            continue;
        const Spectrum f = evalBsdf(scene.bsdfs, bsdf, si, wo, ls.wi);
        if (f.isBlack()) continue;
        ++rayCount;
        if (!accel.occluded(shadowRayTo(si, ls))) sum += f * ls.Le * (1 / ls.pdf);
    }
    return sum;
}

/// How likely a full stack continues along `lobe`: its mean weight without the radiance
/// scaling η'² of a refraction, so a dielectric's lobes are chosen by Fresnel (as sampleBsdf).
CA_HD_INLINE Float lobeImportance(const DeltaLobe& lobe) {
    return lobe.weight.average() * sqr(lobe.eta);
}

/// The lobe a full stack continues along: index into lobes[0, k) chosen with `u` in [0, 1) in
/// proportion to lobeImportance, and its probability; -1 when no lobe carries weight.
CA_HD_INLINE int chooseWhittedLobe(const DeltaLobe* lobes, int k, Float u, Float& probability) {
    Float total = 0;
    for (int i = 0; i < k; ++i) total += lobeImportance(lobes[i]);
    if (!(total > 0)) return -1;
    u *= total;
    int chosen = k - 1;  // where rounding leaves u >= 0 after the last subtraction
    for (int i = 0; i < k - 1; ++i) {
        u -= lobeImportance(lobes[i]);
        if (u < 0) {
            chosen = i;
            break;
        }
    }
    probability = lobeImportance(lobes[chosen]) / total;
    return chosen;
}

/// Pushes the branch of `lobe` leaving `si` after Russian roulette (from rr_depth). Returns
/// whether it was pushed.
template <class Sampler>
CA_HD_INLINE bool pushWhittedBranch(WhittedBranch* stack, int& n, const WhittedBranch& parent,
                                    const SurfaceInteraction& si, const DeltaLobe& lobe,
                                    Float scale, Sampler& sampler,
                                    const WhittedSettings& settings) {
    WhittedBranch child;
    child.throughput = parent.throughput * lobe.weight * scale;
    child.etaScale = parent.etaScale * lobe.eta;
    child.depth = parent.depth + 1;
    const Float throughputMax = child.throughput.maxValue();
    if (!(throughputMax > 0)) return false;
    if (child.depth >= uint32_t(settings.rrDepth)) {
        const Float q = min(throughputMax * child.etaScale * child.etaScale, Float(0.95));
        if (sampler.get1D() >= q) return false;
        child.throughput *= 1 / q;
    }
    child.ray = spawnRay(si.p, si.ng, lobe.wi);
    stack[n++] = child;
    return true;
}

/// The radiance functor MegakernelPass runs per camera sample (megakernel_pass.h): radiance
/// arriving along the camera ray `ray`; `rayCount` is incremented by the rays traced (closest
/// hit and shadow).
struct WhittedRadiance {
    WhittedSettings settings;

    template <class Intersector, class Sampler>
    CA_HD Spectrum operator()(const SceneView& scene, const Intersector& accel, Sampler& sampler,
                              const Ray& ray, uint32_t& rayCount) const {
        Spectrum result(0);
        const uint32_t maxDepth = maxDepthOf(settings);
        if (maxDepth == 0) return result;
        WhittedBranch stack[kWhittedStackSize];
        int n = 0;
        stack[n++] = WhittedBranch{ray, Spectrum(1), 1, 0};
        while (n > 0) {
            const WhittedBranch branch = stack[--n];
            const bool visibleEmitter = !(branch.depth == 0 && settings.hideEmitters);
            const Vec3f dir = normalize(branch.ray.d);
            Hit hit;
            ++rayCount;
            if (!accel.intersect(branch.ray, hit)) {
                if (visibleEmitter) result += branch.throughput * environmentRadiance(scene, dir);
                continue;
            }
            const SurfaceInteraction si = computeInteraction(scene, branch.ray, hit);
            const Vec3f wo = -dir;
            if (visibleEmitter && scene.shapes[si.shape].light >= 0)
                result += branch.throughput * emittedRadiance(scene, si, wo);
            if (branch.depth + 1 >= maxDepth) continue;  // no segment left for light or a new ray

            const uint32_t bsdf = scene.shapes[si.shape].bsdf;
            if (!isDeltaBsdf(scene.bsdfs, bsdf))
                result += branch.throughput *
                          whittedDirectLight(scene, accel, sampler, si, wo, bsdf, rayCount);

            DeltaLobe lobes[kMaxDeltaLobes];
            const int k = deltaLobes(scene.bsdfs, bsdf, si, wo, lobes);
            if (n + k <= kWhittedStackSize) {
                // Every lobe, the first one on top (traced next).
                for (int i = k - 1; i >= 0; --i)
                    pushWhittedBranch(stack, n, branch, si, lobes[i], 1, sampler, settings);
                continue;
            }
            // The stack is full: one lobe, chosen at random.
            Float probability = 0;
            const int chosen = chooseWhittedLobe(lobes, k, sampler.get1D(), probability);
            if (chosen >= 0)
                pushWhittedBranch(stack, n, branch, si, lobes[chosen], 1 / probability, sampler,
                                  settings);
        }
        return result;
    }
};

}  // namespace caustica
