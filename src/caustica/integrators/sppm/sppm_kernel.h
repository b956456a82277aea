// sppm_kernel.h — stochastic progressive photon mapping's per-item kernels (CA_HD: CPU and GPU),
// after Hachisuka & Jensen 2009 with pbrt-v4's per-pixel statistics (Pharr, Jakob, Humphreys,
// "Physically Based Rendering", 4th ed., sec. 13.x "Stochastic progressive photon mapping";
// Knaus & Zwicker 2011 for the radius reduction read as a per-pixel statistic).
//
// One iteration:
//   eye pass     one camera path per pixel (stream (pixel, iteration, seed)) follows delta
//                bounces with the path tracer's step function (path_kernel.h: shadeHit) to the
//                first vertex whose BSDF has a non-delta part. Emission the path tracer would
//                count there (camera ray, after delta bounces) and the direct light at that vertex
//                (one NEE sample and one BSDF sample, MIS-weighted exactly as the path tracer's)
//                go into the pixel's Ld. The vertex becomes the pixel's visible point.
//   photon pass  photon_count photon paths (stream (photon, iteration, seed')). A photon's first
//                hit is direct light (covered by NEE); at every later hit whose BSDF has a
//                non-delta part it deposits into each visible point whose sphere covers it:
//                Phi += β_vp · f_vp(wo, wi) · Φ_photon, M += 1.
//   update       per pixel (seed 003 eq. 2-4; pbrt-v4): if M > 0, N' = N + αM,
//                R' = R·sqrt(N'/(N + M)), τ' = (τ + Phi)·(R'/R)²; then Phi = M = 0.
//   image        L = Ld / iterations + τ / (iterations · photon_count · π R²).
//
// Deposits are summed in 64-bit fixed point with integer atomics, so the sums do not depend on
// the order of the adds (thread count, device): see SppmFixedPoint.
#pragma once

#include <atomic>
#include <cmath>
#include <cstdint>

#include "caustica/integrators/path/path_kernel.h"
#include "caustica/integrators/sppm/sppm_emission.h"
#include "caustica/integrators/sppm/sppm_settings.h"
#include "caustica/scene/bsdf.h"
#include "caustica/scene/camera.h"
#include "caustica/util/rng.h"

namespace caustica {

/// A pixel's statistics, carried across iterations (and checkpoints).
struct SppmPixel {
    double ld[3] = {0, 0, 0};   // sum over iterations of the eye pass's emission + direct light
    double tau[3] = {0, 0, 0};  // τ: flux gathered within the current radius (per photon path)
    double n = 0;               // N: photons kept
    double radius = 0;          // R
};

/// The visible point of a pixel in the current iteration.
struct SppmVisiblePoint {
    SurfaceInteraction si;  // where the BSDF is evaluated
    Vec3f wo;               // unit, towards the camera side of the path
    Spectrum beta;          // path throughput from the camera to the point
    uint32_t bsdf = 0;
    uint32_t depth = 0;     // segments from the camera to the point
    uint32_t pixel = 0;
};

/// The fixed point of the deposit sums: value v is added as round(v · scale) to a uint64.
/// scale = 2^32 / Φmax, Φmax the largest flux a photon starts with (maxEmissionFlux): a deposit
/// is resolved to 2^-32 Φmax (rounding error <= 1.2e-10 Φmax per deposit, below float's own
/// precision for anything but negligible deposits), and a pixel's sum overflows only after
/// 2^32 deposits of Φmax each in one iteration. A deposit is clamped to 2^52 units (and NaN or
/// negative ones are dropped), so even a pathological f cannot wrap the sum.
struct SppmFixedPoint {
    double scale = 1;
    CA_HD uint64_t toUnits(Float v) const {
        const double x = double(v) * scale;
        if (!(x > 0)) return 0;
        return x >= 4503599627370496.0 ? uint64_t(4503599627370496ull) : uint64_t(x + 0.5);
    }
    double toValue(uint64_t units) const { return double(units) / scale; }
};

CA_HD_INLINE void sppmAtomicAdd(uint64_t* address, uint64_t value) {
#if CA_GPU_CODE
    atomicAdd(reinterpret_cast<unsigned long long*>(address), static_cast<unsigned long long>(value));
#else
    std::atomic_ref<uint64_t>(*address).fetch_add(value, std::memory_order_relaxed);
#endif
}

/// Longest path (segments) for max_depth (-1: kSppmDepthCap per eye or photon path).
CA_HD_INLINE uint32_t sppmMaxDepth(const PathSettings& settings, uint32_t cap) {
    return settings.maxDepth < 0 ? cap : uint32_t(settings.maxDepth);
}

/// The eye path of one pixel: Ld (returned) and the visible point (`hasPoint`). `cap` bounds the
/// segments traced when max_depth is unbounded. Uses the path tracer's shadeHit for every vertex
/// (emission, NEE + MIS, BSDF sampling, roulette), so no light-transport rule is restated here.
template <class Intersector, class Sampler>
CA_HD Spectrum sppmEyePath(const SceneView& scene, const Intersector& accel, Sampler& sampler, const Ray& cameraRay,
                           const PathSettings& settings, uint32_t cap, SppmVisiblePoint& vp, bool& hasPoint,
                           uint32_t& rays) {
    hasPoint = false;
    PathSettings bounded = settings;
    if (bounded.maxDepth < 0) bounded.maxDepth = int(cap);
    PathState path;
    if (!startPath(path, cameraRay, bounded)) return path.radiance;
    for (;;) {
        Hit hit;
        ++rays;
        if (!accel.intersect(path.ray, hit)) {
            missPath(scene, path, bounded);
            return path.radiance;
        }
        const Spectrum betaHere = path.throughput;
        const Vec3f woHere = -normalize(path.ray.d);
        const uint32_t depthHere = path.depth + 1;  // segments from the camera to this hit
        ShadowRay shadow;
        bool hasShadow = false;
        // Emission, NEE (MIS) and the BSDF sample, as the path tracer does at this vertex.
        const SurfaceInteraction si = computeInteraction(scene, path.ray, hit);
        const uint32_t bsdf = scene.shapes[si.shape].bsdf;
        const bool delta = isDeltaBsdf(scene.bsdfs, bsdf);
        const bool alive = shadeHit(scene, path, hit, sampler, bounded, shadow, hasShadow);
        if (hasShadow) {
            ++rays;
            addShadowContribution(path, shadow, accel.occluded(shadow.ray));
        }
        if (!delta) {
            // The visible point, and the emitter found by the BSDF sample (MIS weight vs NEE):
            // shadeHit with max_depth = depth + 1 adds the emission at the next hit and stops.
            vp.si = si;
            vp.wo = woHere;
            vp.beta = betaHere;
            vp.bsdf = bsdf;
            vp.depth = depthHere;
            hasPoint = !betaHere.isBlack();
            if (alive) {
                Hit next;
                ++rays;
                PathSettings emissionOnly = bounded;
                emissionOnly.maxDepth = int(path.depth + 1);
                if (accel.intersect(path.ray, next)) {
                    ShadowRay unused;
                    bool unusedFlag;
                    shadeHit(scene, path, next, sampler, emissionOnly, unused, unusedFlag);
                } else {
                    missPath(scene, path, emissionOnly);
                }
            }
            return path.radiance;
        }
        if (!alive) return path.radiance;
    }
}

/// f(wo, wi) of the visible point without the cosine (evalBsdf returns f·|cosθi| about the
/// shading normal): what a photon's flux is weighted with (pbrt-v4's bsdf.f(wo, wi)).
CA_HD_INLINE Spectrum sppmBsdfNoCosine(const SceneView& scene, const SppmVisiblePoint& vp, Vec3f wi) {
    const Float c = std::fabs(dot(vp.si.ns, wi));
    if (!(c > Float(1e-7))) return {};
    return evalBsdf(scene.bsdfs, vp.bsdf, vp.si, vp.wo, wi) * (1 / c);
}

/// The random stream of photon `photon` of iteration `iteration` (distinct from the pixels').
CA_HD_INLINE IndependentSampler photonSampler(uint64_t photon, uint64_t iteration, uint64_t seed) {
    return IndependentSampler(photon, iteration, seed ^ 0x5350504d50484f54ull);  // "SPPMPHOT"
}

/// Traces one photon path and deposits it: for every non-delta hit after the first, into each
/// visible point whose sphere covers it (`lookup.forEachSphereCovering` gives j: the point is
/// points[list[j]]),
/// when the whole path (eye part + photon part) has at most `maxDepth` segments, the photon
/// arrives on the front of the point's surface (geometric normals agree) and f > 0.
/// Roulette on the photon's throughput relative to its start (the path tracer's rule without η:
/// photons carry importance-mode weights). Refraction weights are converted from the BSDF's
/// radiance mode (1/η²) to importance mode (× η²), and shading normals corrected (Veach 1997,
/// sec. 5.3; pbrt's CorrectShadingNormal).
template <class Intersector, class Lookup, class Sampler>
CA_HD void sppmTracePhoton(const SceneView& scene, const Intersector& accel, const Lookup& lookup,
                           const SppmVisiblePoint* points, const uint32_t* list, Sampler& sampler, const PathSettings& settings,
                           uint32_t maxDepth, const SppmFixedPoint& fixed, uint64_t* phi, uint64_t* m,
                           uint32_t& rays) {
    EmissionSample e;
    const Float uSelect = sampler.get1D();
    const Vec2f uPos = sampler.get2D();
    const Vec2f uDir = sampler.get2D();
    if (!sampleEmission(scene, uSelect, uPos, uDir, e)) return;
    Ray ray = e.ray;
    Spectrum throughput(1);
    for (uint32_t k = 1; k < maxDepth && k <= uint32_t(kSppmDepthCap); ++k) {  // k: segments light -> hit
        Hit hit;
        ++rays;
        if (!accel.intersect(ray, hit)) return;
        const SurfaceInteraction si = computeInteraction(scene, ray, hit);
        const uint32_t bsdf = scene.shapes[si.shape].bsdf;
        const Vec3f wo = -normalize(ray.d);  // towards where the photon came from
        if (k >= 2 && !isDeltaBsdf(scene.bsdfs, bsdf)) {
            const Spectrum flux = e.flux * throughput;
            lookup.forEachSphereCovering(si.p, [&](uint32_t j) {
                const SppmVisiblePoint& vp = points[list[j]];
                if (vp.depth + k > maxDepth) return;
                if (!(dot(vp.si.ng, si.ng) > 0)) return;
                const Spectrum d = vp.beta * sppmBsdfNoCosine(scene, vp, wo) * flux;
                if (d.isBlack()) return;
                uint64_t* p = phi + 3 * size_t(vp.pixel);
                sppmAtomicAdd(p + 0, fixed.toUnits(d.r));
                sppmAtomicAdd(p + 1, fixed.toUnits(d.g));
                sppmAtomicAdd(p + 2, fixed.toUnits(d.b));
                sppmAtomicAdd(m + vp.pixel, 1);
            });
        }
        if (k + 1 >= maxDepth) return;  // no deposit can follow (every eye part has >= 1 segment)
        const Float uLobe = sampler.get1D();
        const Vec2f uBsdf = sampler.get2D();
        const Float uRoulette = sampler.get1D();
        BsdfSample bs;
        if (!sampleBsdf(scene.bsdfs, bsdf, si, wo, uLobe, uBsdf, bs)) return;
        const Float num = std::fabs(dot(wo, si.ns)) * std::fabs(dot(bs.wi, si.ng));
        const Float den = std::fabs(dot(wo, si.ng)) * std::fabs(dot(bs.wi, si.ns));
        if (!(den > 0)) return;
        throughput *= bs.weight * (bs.eta * bs.eta * num / den);
        const Float tmax = throughput.maxValue();
        if (!(tmax > 0) || !std::isfinite(tmax)) return;
        if (k >= uint32_t(settings.rrDepth)) {
            const Float q = min(tmax, Float(0.95));
            if (uRoulette >= q) return;
            throughput *= 1 / q;
        }
        ray = spawnRay(si.p, si.ng, bs.wi);
    }
}

/// Hachisuka & Jensen's update of one pixel (seed 003 eq. 2-4; pbrt-v4's SPPM): phi is this
/// iteration's flux sum, m its photon count.
CA_HD_INLINE void sppmUpdatePixel(SppmPixel& p, const double phi[3], uint64_t m, double alpha) {
    if (m == 0) return;
    const double nNew = p.n + alpha * double(m);
    const double rNew = p.radius * std::sqrt(nNew / (p.n + double(m)));
    const double shrink = p.radius > 0 ? (rNew / p.radius) * (rNew / p.radius) : 0;
    for (int c = 0; c < 3; ++c) p.tau[c] = (p.tau[c] + phi[c]) * shrink;
    p.n = nNew;
    p.radius = rNew;
}

/// The pixel's radiance after `iterations` iterations of `photons` photon paths each.
CA_HD_INLINE void sppmPixelRadiance(const SppmPixel& p, uint64_t iterations, uint64_t photons, double out[3]) {
    const double it = double(iterations);
    const double area = 3.14159265358979323846 * p.radius * p.radius;
    const double np = it * double(photons);
    for (int c = 0; c < 3; ++c)
        out[c] = (iterations > 0 ? p.ld[c] / it : 0) + (np > 0 && area > 0 ? p.tau[c] / (np * area) : 0);
}

}  // namespace caustica
