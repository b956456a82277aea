// sppm_kernel.h — stochastic progressive photon mapping's per-item kernels (CA_HD: CPU and GPU),
// after Hachisuka & Jensen 2009 with pbrt-v4's per-pixel statistics (Pharr, Jakob, Humphreys,
// "Physically Based Rendering", 4th ed., sec. 13.x "Stochastic progressive photon mapping";
// Knaus & Zwicker 2011 for the radius reduction read as a per-pixel statistic).
//
// One iteration:
//   eye pass     one camera path per pixel (stream (pixel, iteration, seed)) follows specular
//                bounces (delta, or microfacet lobes smoother than roughness_threshold:
//                isSpecularBsdf) with the path tracer's step function (path_kernel.h: shadeHit)
//                to the first vertex that is not specular. Emission the path tracer would
//                count there (camera ray, after delta bounces) and the direct light at that vertex
//                (one NEE sample and one BSDF sample, MIS-weighted exactly as the path tracer's)
//                go into the pixel's Ld. The vertex becomes the pixel's visible point.
//   photon pass  photon_count photon paths (stream (photon, iteration, seed')), sppm_photon.h.
//                A photon's first hit is direct light (covered by NEE); at every later hit that
//                is not specular it contributes to each visible point whose sphere covers it:
//                Phi += β_vp · f_vp(wo, wi) · Φ_photon, M += 1 — either at once (direction
//                "deposit") or after it was stored and the visible point gathers (direction
//                "gather").
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
#include "caustica/integrators/sppm/sppm_settings.h"
#include "caustica/scene/bsdf.h"
#include "caustica/scene/camera.h"
#include "caustica/scene/emitter_boxes.h"
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
    uint32_t stat = 0;      // its statistics entry (sppm: the pixel; ppm: pixel · hitpoints + j)
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

/// Atomic fetch-and-add that returns the old value (photon slots of direction "gather").
CA_HD_INLINE uint64_t sppmAtomicFetchAdd(uint64_t* address, uint64_t value) {
#if CA_GPU_CODE
    return uint64_t(atomicAdd(reinterpret_cast<unsigned long long*>(address), static_cast<unsigned long long>(value)));
#else
    return std::atomic_ref<uint64_t>(*address).fetch_add(value, std::memory_order_relaxed);
#endif
}

/// Adds an eye pass's radiance to a pixel's Ld; invalid radiance (NaN/Inf/negative) is dropped as
/// the film drops such samples.
CA_HD_INLINE void sppmAddLd(SppmPixel& p, const Spectrum& L) {
    if (std::isfinite(L.r) && std::isfinite(L.g) && std::isfinite(L.b) && L.r >= 0 && L.g >= 0 && L.b >= 0) {
        p.ld[0] += double(L.r);
        p.ld[1] += double(L.g);
        p.ld[2] += double(L.b);
    }
}

/// Longest path (segments) for max_depth (-1: kSppmDepthCap per eye or photon path).
CA_HD_INLINE uint32_t sppmMaxDepth(const PathSettings& settings, uint32_t cap) {
    return settings.maxDepth < 0 ? cap : uint32_t(settings.maxDepth);
}

/// An eye path between two of its rays (sppmEyeHit): the path tracer's state, the settings with
/// max_depth bounded, and whether the ray to trace next is the visible point's emission check.
struct SppmEyeState {
    PathState path;
    PathSettings bounded;
    bool emissionCheck = false;
};

/// Starts the eye path of `cameraRay` (max_depth bounded by `cap`); false: it traces nothing.
CA_HD_INLINE bool sppmStartEye(SppmEyeState& eye, const Ray& cameraRay, const PathSettings& settings, uint32_t cap) {
    eye.bounded = settings;
    if (eye.bounded.maxDepth < 0) eye.bounded.maxDepth = int(cap);
    eye.emissionCheck = false;
    return startPath(eye.path, cameraRay, eye.bounded);
}

/// What the eye path does at the closest hit of eye.path.ray (`hit`; nullptr: a miss): the path
/// tracer's shadeHit for every vertex (emission, NEE + MIS, BSDF sampling, roulette), its NEE
/// sample in `shadow` when `hasShadow` (the caller tests it and adds it with addShadowContribution
/// before the next step); at the first non-specular vertex the visible point (`vp`, `hasPoint`),
/// after which the BSDF sample is traced once more, as the emission check, only when it may
/// reach an emitter (emitter_boxes.h; a ray that passes no emitter's box would find no emission,
/// so the image is the same). Returns whether the path traces eye.path.ray next.
template <class Sampler>
CA_HD bool sppmEyeHit(const SceneView& scene, Sampler& sampler, Float specularBelow, const EmitterBoxes& emitters,
                      SppmEyeState& eye, const Hit* hit, ShadowRay& shadow, bool& hasShadow, SppmVisiblePoint& vp,
                      bool& hasPoint) {
    PathState& path = eye.path;
    hasShadow = false;
    if (eye.emissionCheck) {
        // shadeHit with max_depth = depth + 1 adds the emission at this hit and stops, so a hit
        // on a shape that emits nothing adds nothing and needs no interaction.
        PathSettings emissionOnly = eye.bounded;
        emissionOnly.maxDepth = int(path.depth + 1);
        if (!hit) {
            missPath(scene, path, emissionOnly);
        } else if (scene.shapes[scene.shapeOf(hit->primId)].light >= 0) {
            ShadowRay unused;
            bool unusedFlag;
            shadeHit(scene, path, *hit, sampler, emissionOnly, unused, unusedFlag);
        }
        return false;
    }
    if (!hit) {
        missPath(scene, path, eye.bounded);
        return false;
    }
    const Spectrum betaHere = path.throughput;
    const Vec3f woHere = -normalize(path.ray.d);
    const uint32_t depthHere = path.depth + 1;  // segments from the camera to this hit
    const uint32_t bsdf = scene.shapes[scene.shapeOf(hit->primId)].bsdf;
    const bool specular = isSpecularBsdf(scene.bsdfs, bsdf, specularBelow);
    // Emission, NEE (MIS) and the BSDF sample, as the path tracer does at this vertex; the
    // interaction is built once and kept for the visible point.
    const SurfaceInteraction si = computeInteraction(scene, path.ray, *hit);
    const bool alive = shadeHitAt(scene, path, si, sampler, eye.bounded, shadow, hasShadow);
    if (specular) return alive;
    vp.si = si;
    vp.wo = woHere;
    vp.beta = betaHere;
    vp.bsdf = bsdf;
    vp.depth = depthHere;
    hasPoint = !betaHere.isBlack();
    eye.emissionCheck = alive && emitters.mayHitEmitter(path.ray);
    return eye.emissionCheck;
}

/// The eye path of one pixel: Ld (returned) and the visible point (`hasPoint`), by sppmEyeHit's
/// steps. `cap` bounds the segments traced when max_depth is unbounded. `specularBelow`: the
/// roughness threshold of isSpecularBsdf.
template <class Intersector, class Sampler>
CA_HD Spectrum sppmEyePath(const SceneView& scene, const Intersector& accel, Sampler& sampler, const Ray& cameraRay,
                           const PathSettings& settings, uint32_t cap, Float specularBelow,
                           const EmitterBoxes& emitters, SppmVisiblePoint& vp, bool& hasPoint, uint32_t& rays) {
    hasPoint = false;
    SppmEyeState eye;
    if (!sppmStartEye(eye, cameraRay, settings, cap)) return eye.path.radiance;
    for (;;) {
        Hit hit;
        ++rays;
        const bool found = accel.intersect(eye.path.ray, hit);
        ShadowRay shadow;
        bool hasShadow;
        const bool more =
            sppmEyeHit(scene, sampler, specularBelow, emitters, eye, found ? &hit : nullptr, shadow, hasShadow, vp, hasPoint);
        if (hasShadow) {
            ++rays;
            addShadowContribution(eye.path, shadow, accel.occluded(shadow.ray));
        }
        if (!more) return eye.path.radiance;
    }
}

/// The width of one pixel's footprint at a point at `distance` from the camera: the auto initial
/// radius is a few of these (perspective and thin lens: distance · 2 tan(fov_x / 2) / width;
/// orthographic: the film's width in the scene / width).
CA_HD_INLINE Float pixelFootprint(const Camera& camera, Float distance) {
    const Float perPixel = 2 * camera.tanHalfX / Float(camera.width > 0 ? camera.width : 1);
    if (camera.type == CameraType::Orthographic)
        return perPixel * length(camera.worldFromCamera.applyVector(Vec3f(1, 0, 0)));
    return distance * perPixel;
}

/// Hachisuka & Jensen's update of one pixel (seed 003 eq. 2-4; pbrt-v4's SPPM): phi is this
/// iteration's flux sum, m its photon count. (radius_schedule "local".)
CA_HD_INLINE void sppmUpdatePixel(SppmPixel& p, const double phi[3], uint64_t m, double alpha) {
    if (m == 0) return;
    const double nNew = p.n + alpha * double(m);
    const double rNew = p.radius * std::sqrt(nNew / (p.n + double(m)));
    const double shrink = p.radius > 0 ? (rNew / p.radius) * (rNew / p.radius) : 0;
    for (int c = 0; c < 3; ++c) p.tau[c] = (p.tau[c] + phi[c]) * shrink;
    p.n = nNew;
    p.radius = rNew;
}

/// Knaus & Zwicker 2011 (eq. 15), radius_schedule "global": every pixel's radius follows one
/// sequence, R_{i+1}² = R_i² (i + α) / (i + 1) after iteration i = 1, 2, ..., whatever its photon
/// count. τ' = (τ + Phi)(R'/R)² keeps τ / (π R²) the sum over iterations of Phi_i / (π R_i²), so
/// the image formula is the same for both schedules. n counts the photons (statistics only).
CA_HD_INLINE void sppmUpdatePixelGlobal(SppmPixel& p, const double phi[3], uint64_t m, double alpha,
                                        uint64_t iteration) {
    const double i = double(iteration);
    const double shrink = (i + alpha) / (i + 1);
    for (int c = 0; c < 3; ++c) p.tau[c] = (p.tau[c] + phi[c]) * shrink;
    p.n += double(m);
    p.radius *= std::sqrt(shrink);
}

/// The pixel's radiance after `iterations` iterations of `photons` photon paths each; ld is the
/// sum of `ldCount` eye-pass estimates (sppm: one per iteration; ppm: the one eye pass).
CA_HD_INLINE void sppmPixelRadiance(const SppmPixel& p, uint64_t iterations, uint64_t photons, uint64_t ldCount,
                                    double out[3]) {
    const double area = 3.14159265358979323846 * p.radius * p.radius;
    const double np = double(iterations) * double(photons);
    for (int c = 0; c < 3; ++c)
        out[c] = (ldCount > 0 ? p.ld[c] / double(ldCount) : 0) + (np > 0 && area > 0 ? p.tau[c] / (np * area) : 0);
}

}  // namespace caustica
