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

/// One path's vertex as shadeVertex sees it (F = float): the path, its interaction, sampler and
/// shadow ray, and the scene's BSDF, emitters and lights through their scalar functions. Its
/// writers (addRadiance, setShadow, advance, scaleThroughput) are called only where their mask
/// is set, which for one path means always.
template <class Sampler>
struct ScalarVertex {
    using F = float;
    const SceneView& scene;
    PathState& path;
    const SurfaceInteraction& si;
    Sampler& sampler;
    ShadowRay& shadow;
    bool& hasShadow;

    CA_HD_INLINE Vec3f rayDirection() const { return path.ray.d; }
    CA_HD_INLINE int32_t lightIndex() const { return scene.shapes[si.shape].light; }
    /// An emitter hit that counts (emitters seen directly render black with hide_emitters).
    CA_HD_INLINE bool emitterSeen(const PathSettings& settings) const {
        const bool visibleEmitter = !(path.depth == 0 && settings.hideEmitters);
        return lightIndex() >= 0 && visibleEmitter;
    }
    CA_HD_INLINE Spectrum emitted(Vec3f wo) const { return emittedRadiance(scene, si, wo); }
    CA_HD_INLINE bool prevDelta() const { return path.prevBsdfDelta; }
    /// The MIS weight of the emission found by the BSDF-sampled ray (1 after a delta bounce).
    CA_HD_INLINE Float emissionWeight() const {
        return path.prevBsdfDelta ? 1
                                  : powerHeuristic(path.prevBsdfPdf,
                                                   pdfAreaLight(scene, uint32_t(lightIndex()), path.prevP, si));
    }
    CA_HD_INLINE const Spectrum& throughput() const { return path.throughput; }
    CA_HD_INLINE void addRadiance(bool, const Spectrum& l) { path.radiance += l; }
    CA_HD_INLINE bool belowMaxDepth(const PathSettings& settings) const { return path.depth + 1 < maxDepthOf(settings); }
    CA_HD_INLINE uint32_t bsdfId() const { return scene.shapes[si.shape].bsdf; }
    CA_HD_INLINE bool deltaBsdf() const { return isDeltaBsdf(scene.bsdfs, bsdfId()); }
    CA_HD_INLINE BsdfAtVertex prepareBsdf(Vec3f wo) const { return BsdfAtVertex(scene.bsdfs, bsdfId(), si, wo); }
    CA_HD_INLINE Float get1D(bool) { return sampler.get1D(); }
    CA_HD_INLINE Vec2f get2D(bool) { return sampler.get2D(); }
    CA_HD_INLINE bool sampleLight(Float uSelect, Vec2f uLight, LightSample& ls) const {
        return caustica::sampleLight(scene, si.p, uSelect, uLight, ls);
    }
    CA_HD_INLINE void setShadow(bool, const LightSample& ls, const Spectrum& contribution) {
        shadow.ray = ls.dist < kInfinity ? spawnRayTo(si.p, si.ng, ls.p, ls.n) : spawnRay(si.p, si.ng, ls.wi);
        shadow.contribution = contribution;
        hasShadow = true;
    }
    CA_HD_INLINE void advance(bool, const BsdfSample& bs) {
        path.throughput *= bs.weight;
        path.etaScale *= bs.eta;
        path.prevBsdfPdf = bs.pdf;
        path.prevBsdfDelta = bs.delta;
        path.prevP = si.p;
        spawnRayInto(path.ray, si.p, si.ng, bs.wi);
        ++path.depth;
    }
    CA_HD_INLINE bool atLeastRrDepth(const PathSettings& settings) const {
        return path.depth >= uint32_t(settings.rrDepth);
    }
    CA_HD_INLINE Float etaScale() const { return path.etaScale; }
    CA_HD_INLINE void scaleThroughput(bool, Float s) { path.throughput *= s; }
};

/// The path's ray hit a surface (the vertex `v`): adds the emission found there (MIS-weighted
/// against NEE), draws one NEE sample (`v.setShadow`: a shadow ray to test and the contribution
/// to add if it is unoccluded, addShadowContribution), samples the BSDF to continue the path and
/// plays Russian roulette (Mitsuba 3: survival probability min(max(β)·η², 0.95)). Returns where
/// the path continues along its new ray. Draws 1+2 (NEE) + 1+2 (BSDF) + 1 (roulette) numbers per
/// bounce, the NEE ones even at delta surfaces (a fixed layout per bounce helps Metropolis).
/// Generic over the vertex V: one path (ScalarVertex, F = float: every GPU thread, and the CPU
/// where vertices are not grouped) or several side by side (V::F a lane type, masks where the
/// scalar form returns early), the same operations in the same order either way.
template <class V>
CA_HD_INLINE MaskOf<typename V::F> shadeVertex(V& v, const PathSettings& settings) {
    using F = typename V::F;
    using M = MaskOf<F>;
    const Vec3Of<F> d = v.rayDirection();
    const Vec3Of<F> wo = -(d * (1 / lane::sqrt(dot(d, d))));  // -normalize(d)

    // ---- Emission found by the BSDF-sampled (or camera) ray, MIS-weighted against NEE.
    const M emits = v.emitterSeen(settings);
    if (lane::any(emits)) {
        const SpectrumOf<F> le = v.emitted(wo);
        const M found = emits & !isBlack<F>(le);
        if (lane::any(found)) v.addRadiance(found, v.throughput() * le * v.emissionWeight());
    }
    M alive = v.belowMaxDepth(settings);
    if (!lane::any(alive)) return alive;

    const auto bsdf = v.prepareBsdf(wo);  // resolved once for NEE and sampling

    // ---- Next-event estimation (skipped for purely specular surfaces; its numbers drawn anyway,
    // to keep the random-number layout of every bounce the same, useful to Metropolis).
    const F uSelect = v.get1D(alive);
    const Vec2Of<F> uLight = v.get2D(alive);
    M lit = alive & !v.deltaBsdf();
    if (lane::any(lit)) {
        LightSampleOf<F> ls;
        lit = lit & v.sampleLight(uSelect, uLight, ls);
        lit = lit & (ls.pdf > 0) & !isBlack<F>(ls.Le);
        if (lane::any(lit)) {
            F bsdfPdf;
            const SpectrumOf<F> f = bsdf.evalPdf(ls.wi, bsdfPdf);
            lit = lit & !isBlack<F>(f);
            if (lane::any(lit)) {
                const F w = lane::select(ls.delta, lane::splat<F>(1), powerHeuristic<F>(ls.pdf, bsdfPdf));
                v.setShadow(lit, ls, v.throughput() * f * ls.Le * (w / ls.pdf));
            }
        }
    }

    // ---- BSDF sampling: continue the path.
    const F uLobe = v.get1D(alive);
    const Vec2Of<F> uDir = v.get2D(alive);
    BsdfSampleOf<F> bs;
    alive = alive & bsdf.sample(uLobe, uDir, bs);
    if (!lane::any(alive)) return alive;
    v.advance(alive, bs);

    // ---- Russian roulette (Mitsuba 3: survival probability min(max(β)·η², 0.95)).
    const F throughputMax = maxValue<F>(v.throughput());
    alive = alive & (throughputMax > 0);
    if (!lane::any(alive)) return alive;
    const F uRoulette = v.get1D(alive);
    const M roulette = alive & v.atLeastRrDepth(settings);
    if (lane::any(roulette)) {
        const F q = lane::min(throughputMax * v.etaScale() * v.etaScale(), lane::splat<F>(0.95f));
        alive = alive & !(roulette & (uRoulette >= q));
        const M survivors = roulette & alive;
        if (lane::any(survivors)) v.scaleThroughput(survivors, 1 / q);
    }
    return alive;
}

/// shadeVertex of one path at an interaction the caller already built (computeInteraction of
/// path.ray and its hit), so that a caller that keeps the interaction does not build it twice.
/// `hasShadow`: whether `shadow` holds an NEE sample to test.
template <class Sampler>
CA_HD_INLINE bool shadeHitAt(const SceneView& scene, PathState& path, const SurfaceInteraction& si, Sampler& sampler,
                             const PathSettings& settings, ShadowRay& shadow, bool& hasShadow) {
    hasShadow = false;
    ScalarVertex<Sampler> v{scene, path, si, sampler, shadow, hasShadow};
    return shadeVertex(v, settings);
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
