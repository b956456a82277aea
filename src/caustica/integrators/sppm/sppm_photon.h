// sppm_photon.h — the photon pass of the photon mappers (CA_HD: CPU and GPU): one photon path
// from a light, the rule that decides what a photon gives a visible point, and the photon record
// that direction "gather" stores. Both directions call the same two functions, so that they
// compute the same estimate:
//   sppmTracePhoton   traces the path and calls sink(hit, wo, flux, k) at every vertex that may
//                     contribute (k >= 2 segments from the light, not specular);
//   sppmContribution  what such a photon adds to one visible point's flux sum (black: nothing).
#pragma once

#include <cmath>
#include <cstdint>

#include "caustica/integrators/sppm/sppm_emission.h"
#include "caustica/integrators/sppm/sppm_kernel.h"
#include "caustica/integrators/sppm/sppm_settings.h"
#include "caustica/scene/bsdf.h"

namespace caustica {

/// A stored photon (direction "gather"): where it arrived, from where, with what flux.
struct SppmPhoton {
    Vec3f p;         // the hit point
    Vec3f wo;        // unit, towards where the photon came from
    Vec3f ng;        // geometric normal of the surface it hit
    Spectrum flux;   // Φ of the photon path at this hit
    uint32_t depth;  // k: segments from the light to p
};

/// The random stream of photon `photon` of iteration `iteration` (distinct from the pixels').
CA_HD_INLINE IndependentSampler photonSampler(uint64_t photon, uint64_t iteration, uint64_t seed) {
    return IndependentSampler(photon, iteration, seed ^ 0x5350504d50484f54ull);  // "SPPMPHOT"
}

/// A direction lies on the same side of the geometric and the shading normal (else a shading
/// normal would let light through the surface: rejected, as Mitsuba's and pbrt's path tracers do).
CA_HD_INLINE bool consistentSide(Vec3f w, Vec3f ng, Vec3f ns) {
    return dot(w, ng) * dot(w, ns) > 0;
}

/// What a photon with flux Φ arriving at a point on a surface with geometric normal `ng` from
/// direction `wo` after k segments gives visible point vp (β_vp · f_vp(vp.wo, wo) · Φ), or black
/// when it gives nothing:
///   - the whole path (eye part + photon part) is longer than maxDepth segments;
///   - it arrived on a surface facing another way (vp and photon surfaces' geometric normals
///     disagree: the other side of a thin wall, the wall of a corner);
///   - it arrived from the back side of vp's surface by a shading normal alone (consistentSide);
///     a reflection-only BSDF gives an arrival from the geometric back nothing anyway, a
///     transmitting one (rough glass) takes it.
/// `bsdf(wi)`: vp's evalBsdf(…, vp.wo, wi) (sppm_visible_bsdf.h keeps it resolved for a gather).
template <class EvalBsdf>
CA_HD_INLINE Spectrum sppmContributionWith(const SppmVisiblePoint& vp, const EvalBsdf& bsdf, Vec3f ng, Vec3f wo,
                                           const Spectrum& flux, uint32_t k, uint32_t maxDepth) {
    if (vp.depth + k > maxDepth) return {};
    if (!(dot(vp.si.ng, ng) > 0)) return {};
    if (!consistentSide(wo, vp.si.ng, vp.si.ns)) return {};
    const Float c = std::fabs(dot(vp.si.ns, wo));
    if (!(c > Float(1e-7))) return {};
    // evalBsdf is f · |cos θi| about the shading normal; the photon's flux wants f alone.
    return vp.beta * bsdf(wo) * (flux * (1 / c));
}

CA_HD_INLINE Spectrum sppmContribution(const SceneView& scene, const SppmVisiblePoint& vp, Vec3f ng, Vec3f wo,
                                       const Spectrum& flux, uint32_t k, uint32_t maxDepth) {
    return sppmContributionWith(
        vp, [&](Vec3f wi) { return evalBsdf(scene.bsdfs, vp.bsdf, vp.si, vp.wo, wi); }, ng, wo, flux, k, maxDepth);
}

/// A photon path between two of its rays: the segment to trace next and what it carries.
struct SppmPhotonPath {
    Ray ray;              // the next segment
    Spectrum flux;        // Φ at the light
    Spectrum throughput;  // importance-mode weight since the light (roulette included)
    uint32_t k = 1;       // segments from the light to the next hit
};

/// The photon's emission (its first three numbers). Returns false when the light gives nothing.
template <class Sampler>
CA_HD_INLINE bool sppmStartPhoton(const SceneView& scene, Sampler& sampler, SppmPhotonPath& path) {
    EmissionSample e;
    const Float uSelect = sampler.get1D();
    const Vec2f uPos = sampler.get2D();
    const Vec2f uDir = sampler.get2D();
    if (!sampleEmission(scene, uSelect, uPos, uDir, e)) return false;
    path.ray = e.ray;
    path.flux = e.flux;
    path.throughput = Spectrum(1);
    path.k = 1;
    return true;
}

/// What every photon path of a pass follows.
struct SppmPhotonRules {
    PathSettings path;        // rr_depth (roulette "throughput")
    uint32_t maxDepth = 0;    // the longest whole path in segments, eye part included (every eye
                              // part has at least one segment)
    Float specularBelow = 0;  // roughness below which a lobe is specular (isSpecularBsdf)
    PhotonRoulette roulette = PhotonRoulette::Albedo;
};

/// Whether the path traces its next segment.
CA_HD_INLINE bool sppmPhotonWantsRay(const SppmPhotonPath& path, uint32_t maxDepth) {
    return path.k < maxDepth && path.k <= uint32_t(kSppmDepthCap);
}

/// The probability that a photon path goes on after its k-th hit, whose bounce took the largest
/// channel of its throughput from `before` to `after` (both > 0); 1: no roulette.
///   Albedo: at every bounce, after / before (at most 1), Jensen's photon-map roulette as
///     pbrt-v4's SPPM has it: a photon that survives is divided by that ratio, so it keeps the
///     power it left the light with and an absorbing bounce ends paths instead of dimming them.
///     A path's expected deposits are the same; fewer rays carry them (one bounce off a wall of
///     albedo 0.5 ends half the paths).
///   Throughput: from rr_depth on, min(after, 0.95), the path tracer's rule (after is relative to
///     the emitted flux).
CA_HD_INLINE Float sppmPhotonSurvival(const SppmPhotonRules& rules, uint32_t k, Float before, Float after) {
    if (rules.roulette == PhotonRoulette::Albedo) return min(after / before, Float(1));
    return k >= uint32_t(rules.path.rrDepth) ? min(after, Float(0.95)) : Float(1);
}

/// What the photon does at `hit`, the closest hit of path.ray: sink(si, wo, flux, k) there unless
/// k < 2 or the BSDF is specular, then (unless no contribution can follow) a BSDF sample and
/// roulette, which set path.ray to the next segment. Returns whether the path goes on (and traces
/// path.ray). Three numbers per hit that samples.
template <class Sampler, class Sink>
CA_HD_INLINE bool sppmPhotonHit(const SceneView& scene, Sampler& sampler, const SppmPhotonRules& rules,
                                SppmPhotonPath& path, const Hit& hit, Sink&& sink) {
    const uint32_t k = path.k, maxDepth = rules.maxDepth;
    const SurfaceInteraction si = computeInteraction(scene, path.ray, hit);
    const uint32_t bsdf = scene.shapes[si.shape].bsdf;
    const Vec3f wo = -normalize(path.ray.d);  // towards where the photon came from
    if (k >= 2 && !isSpecularBsdf(scene.bsdfs, bsdf, rules.specularBelow)) sink(si, wo, path.flux * path.throughput, k);
    if (k + 1 >= maxDepth) return false;  // no contribution can follow
    const Float uLobe = sampler.get1D();
    const Vec2f uBsdf = sampler.get2D();
    const Float uRoulette = sampler.get1D();
    BsdfSample bs;
    if (!sampleBsdf(scene.bsdfs, bsdf, si, wo, uLobe, uBsdf, bs)) return false;
    const Float num = std::fabs(dot(wo, si.ns)) * std::fabs(dot(bs.wi, si.ng));
    const Float den = std::fabs(dot(wo, si.ng)) * std::fabs(dot(bs.wi, si.ns));
    if (!(den > 0)) return false;
    const Float before = path.throughput.maxValue();
    path.throughput *= bs.weight * (bs.eta * bs.eta * num / den);
    const Float after = path.throughput.maxValue();
    if (!(after > 0) || !std::isfinite(after)) return false;
    if (const Float q = sppmPhotonSurvival(rules, k, before, after); q < 1) {
        if (uRoulette >= q) return false;
        path.throughput *= 1 / q;
    }
    path.ray = spawnRay(si.p, si.ng, bs.wi);
    path.k = k + 1;
    return sppmPhotonWantsRay(path, maxDepth);
}

/// Traces one photon path and calls sink(si, wo, flux, k) at every hit k >= 2 segments from the
/// light whose BSDF is not specular (isSpecularBsdf with rules.specularBelow). Roulette by
/// rules.roulette (sppmPhotonSurvival) on importance-mode weights: refraction weights are
/// converted from the BSDF's radiance mode (1/η²) to importance mode (× η²), and shading normals
/// corrected (Veach 1997, sec. 5.3; pbrt's CorrectShadingNormal). The passes' packet form
/// (sppm_passes.h, photonPathGroup) takes the same steps.
template <class Intersector, class Sampler, class Sink>
CA_HD void sppmTracePhoton(const SceneView& scene, const Intersector& accel, Sampler& sampler,
                           const SppmPhotonRules& rules, uint32_t& rays, Sink&& sink) {
    SppmPhotonPath path;
    if (!sppmStartPhoton(scene, sampler, path)) return;
    while (sppmPhotonWantsRay(path, rules.maxDepth)) {
        Hit hit;
        ++rays;
        if (!accel.intersect(path.ray, hit)) return;
        if (!sppmPhotonHit(scene, sampler, rules, path, hit, sink)) return;
    }
}

/// Adds a contribution to a statistics entry's fixed-point flux sum and photon count.
CA_HD_INLINE void sppmDeposit(const SppmFixedPoint& fixed, const Spectrum& d, uint64_t* phi, uint64_t* m) {
    sppmAtomicAdd(phi + 0, fixed.toUnits(d.r));
    sppmAtomicAdd(phi + 1, fixed.toUnits(d.g));
    sppmAtomicAdd(phi + 2, fixed.toUnits(d.b));
    sppmAtomicAdd(m, 1);
}

/// 30-bit Morton code of p in the box [lo, lo + extent) (10 bits per axis; outside: clamped).
CA_HD_INLINE uint32_t sppmMorton(Vec3f p, Vec3f lo, Vec3f invExtent) {
    auto spread = [](uint32_t v) {  // 10 bits -> every third bit
        v = (v | (v << 16)) & 0x030000FFu;
        v = (v | (v << 8)) & 0x0300F00Fu;
        v = (v | (v << 4)) & 0x030C30C3u;
        v = (v | (v << 2)) & 0x09249249u;
        return v;
    };
    auto axis = [](Float v) {
        const Float t = v * Float(1024);
        return t > 0 ? uint32_t(min(t, Float(1023))) : 0u;
    };
    const Vec3f q = (p - lo) * invExtent;
    return (spread(axis(q.x)) << 2) | (spread(axis(q.y)) << 1) | spread(axis(q.z));
}

}  // namespace caustica
