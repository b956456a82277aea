// direct_kernel.h — direct illumination with multiple importance sampling, Mitsuba 3's `direct`
// integrator (src/integrators/direct.cpp), shared by CPU and GPU.
//
// For each camera ray: the emission of a directly visible emitter (unless hide_emitters), then at
// the first surface `emitterSamples` light samples (only where the BSDF has a non-delta part,
// Mitsuba's BSDFFlags::Smooth) and `bsdfSamples` BSDF samples that count when they reach an
// emitter. The two strategies are combined with the power heuristic over the sample-count-scaled
// pdfs (Veach 1997, sec. 9.2.4, multi-sample model): with n_e emitter and n_b BSDF samples,
//     w_e = (f_e p_e)² / ((f_e p_e)² + (f_b p_b)²) / n_e,   f_e = n_e / (n_e + n_b),
// and symmetrically for BSDF samples, which is exactly direct.cpp's mis_weight · m_weight_*.
//
// Mitsuba quirk kept on purpose (checked against Mitsuba 3.9.1): a delta emitter's sample (point
// light) gets weight 1, *not* divided by emitter_samples, so with emitter_samples = n a point
// light contributes n times its radiance. caustica reproduces it so that scenes converge to the
// same image (docs/COMPATIBILITY.md).
//
// Templated on the intersector and the sampler like path_kernel.h. Random-number layout per
// camera sample (after the caller's pixel jitter): emitterSamples × (1 + 2), then
// bsdfSamples × (1 + 2), drawn even at delta surfaces (a fixed layout helps Metropolis).
#pragma once

#include <cstdint>

#include "caustica/scene/bsdf.h"
#include "caustica/scene/interaction.h"
#include "caustica/scene/light.h"
#include "caustica/util/sampling.h"

namespace caustica {

/// Parameters of the direct integrator (Mitsuba 3 names: emitter_samples, bsdf_samples,
/// hide_emitters; shading_samples sets both counts in the loader). At least one count is > 0.
struct DirectSettings {
    int emitterSamples = 1;     // light samples per camera sample
    int bsdfSamples = 1;        // BSDF samples per camera sample
    bool hideEmitters = false;  // emitters seen directly by the camera render black
};

/// The sample-count factors of direct.cpp: fraction of each technique among all samples (scales
/// the pdfs inside the power heuristic) and 1 / count (averages a technique's samples).
struct DirectWeights {
    Float fracEmitter, fracBsdf, invEmitterSamples, invBsdfSamples;
};

CA_HD_INLINE DirectWeights directWeights(const DirectSettings& s) {
    const Float ne = Float(s.emitterSamples), nb = Float(s.bsdfSamples), sum = ne + nb;
    return {ne / sum, nb / sum, ne > 0 ? 1 / ne : Float(0), nb > 0 ? 1 / nb : Float(0)};
}

/// Radiance arriving along the camera ray `ray` from emitters seen directly or after one
/// scattering event. `rayCount` is incremented by the rays traced (closest hit and shadow).
template <class Intersector, class Sampler>
CA_HD Spectrum directRadiance(const SceneView& scene, const Intersector& accel, Sampler& sampler,
                              const Ray& ray, const DirectSettings& settings, uint32_t& rayCount) {
    Spectrum result(0);
    const Vec3f dir = normalize(ray.d);

    // ---- Directly visible emitters (the environment where the ray escapes).
    Hit hit;
    ++rayCount;
    if (!accel.intersect(ray, hit)) {
        if (!settings.hideEmitters) result += environmentRadiance(scene, dir);
        return result;
    }
    const SurfaceInteraction si = computeInteraction(scene, ray, hit);
    const Vec3f wo = -dir;
    if (!settings.hideEmitters) result += emittedRadiance(scene, si, wo);

    const uint32_t bsdf = scene.shapes[si.shape].bsdf;
    const BsdfAtVertex bsdfAt(scene.bsdfs, bsdf, si, wo);  // resolved once for every sample here
    const DirectWeights w = directWeights(settings);

    // ---- Emitter sampling, where the BSDF has a non-delta part.
    const bool smooth = !isDeltaBsdf(scene.bsdfs, bsdf);
    for (int i = 0; i < settings.emitterSamples; ++i) {
        const Float uSelect = sampler.get1D();
        const Vec2f uLight = sampler.get2D();
        if (!smooth) continue;
        LightSample ls;
        if (!sampleLight(scene, si.p, uSelect, uLight, ls) || !(ls.pdf > 0) || ls.Le.isBlack())
            continue;
        Float bsdfPdf;
        const Spectrum f = bsdfAt.evalPdf(ls.wi, bsdfPdf);
        if (f.isBlack()) continue;
        const Ray shadow = ls.dist < kInfinity ? spawnRayTo(si.p, si.ng, ls.p, ls.n)
                                               : spawnRay(si.p, si.ng, ls.wi);
        ++rayCount;
        if (accel.occluded(shadow)) continue;
        // direct.cpp: delta emitters get weight 1 (not 1 / emitter_samples; see above).
        const Float mis =
            ls.delta ? Float(1)
                     : powerHeuristic(ls.pdf * w.fracEmitter, bsdfPdf * w.fracBsdf) *
                           w.invEmitterSamples;
        result += f * ls.Le * (mis / ls.pdf);
    }

    // ---- BSDF sampling: a sample counts when its ray reaches an emitter.
    for (int i = 0; i < settings.bsdfSamples; ++i) {
        const Float uLobe = sampler.get1D();
        const Vec2f uDir = sampler.get2D();
        BsdfSample bs;
        if (!bsdfAt.sample(uLobe, uDir, bs) || bs.weight.isBlack())
            continue;
        const Ray next = spawnRay(si.p, si.ng, bs.wi);
        ++rayCount;
        Hit emitterHit;
        Spectrum le;
        Float lightPdf = 0;  // stays 0 after a delta lobe: NEE cannot produce that direction
        if (accel.intersect(next, emitterHit)) {
            const SurfaceInteraction onLight = computeInteraction(scene, next, emitterHit);
            const int32_t light = scene.shapes[onLight.shape].light;
            if (light < 0) continue;
            le = emittedRadiance(scene, onLight, -normalize(bs.wi));
            if (!bs.delta) lightPdf = pdfAreaLight(scene, uint32_t(light), si.p, onLight);
        } else {
            if (scene.environmentLight < 0) continue;
            le = environmentRadiance(scene, bs.wi);
            if (!bs.delta) lightPdf = pdfEnvironmentLight(scene, bs.wi);
        }
        if (le.isBlack()) continue;
        const Float mis =
            powerHeuristic(bs.pdf * w.fracBsdf, lightPdf * w.fracEmitter) * w.invBsdfSamples;
        result += bs.weight * le * mis;
    }
    return result;
}

}  // namespace caustica
