// light.h — sampling and evaluation of the closed list of emitters (light_data.h). Shared
// CPU/GPU kernel code with Mitsuba 3's semantics: lights are selected uniformly, area emitters
// emit on the front side of their shape only, the constant environment from every direction.
// Needs finalizeLights (light_setup.h) to have run on the scene.
#pragma once

#include "caustica/scene/interaction.h"
#include "caustica/scene/light_delta.h"
#include "caustica/scene/light_envmap.h"
#include "caustica/util/sampling.h"

namespace caustica {

/// One sampled point (or direction) on a light, as seen from a reference point.
struct LightSample {
    Vec3f p;          // point on the light (for the environment: a point 2 scene radii away)
    Vec3f n;          // normal at p (zero for point and environment lights)
    Vec3f wi;         // unit, from the reference point towards the light
    Float dist = 0;   // distance to p, kInfinity for the environment
    Spectrum Le;      // radiance for area/environment, intensity / dist² for a point light
    Float pdf = 0;    // solid-angle pdf at ref incl. light selection; for delta lights the
                      // selection probability
    bool delta = false;
    uint32_t light = 0;
};

/// LightSample of code generic over the lane type F (util/lane.h).
template <class F>
using LightSampleOf = LaneOf<LightSample, F>;

namespace light_detail {

/// Uniform light selection (as Mitsuba's default emitter sampling).
CA_HD_INLINE Float selectionPdf(const SceneView& scene) {
    return scene.lights.empty() ? Float(0) : Float(1) / Float(scene.lights.size());
}

/// Visible cone of a sphere from a point outside it: 1 - cosθmax with sinθmax = r / |c - p|,
/// computed as sin²θmax / (1 + cosθmax) to avoid cancellation for small cones. Returns false
/// (cone undefined) when `p` is inside or on the sphere: area sampling is used there.
CA_HD_INLINE bool sphereCone(const Sphere& s, Vec3f p, Float& oneMinusCosMax, Float& distC) {
    const Float dc2 = lengthSquared(s.center - p);
    const Float r2 = s.radius * s.radius;
    if (!(dc2 > r2)) return false;
    const Float sin2Max = r2 / dc2;
    oneMinusCosMax = sin2Max / (1 + safeSqrt(1 - sin2Max));
    distC = std::sqrt(dc2);
    return true;
}

/// Sphere light from outside: a direction uniform in the visible cone and the point it hits
/// (pbrt-v4, Sphere::Sample(ShapeSampleContext), after Akalin's "sampling the visible sphere").
CA_HD_INLINE void sampleSphereCone(const Sphere& s, Vec3f refP, Float omc, Float distC, Vec2f u,
                                   Vec3f& p, Vec3f& outward) {
    const Float sinThetaMax = s.radius / distC;
    const Float v = u.x * omc;
    const Float sin2Theta = v * (2 - v), cosTheta = 1 - v;
    // Angle α at the sphere's centre between the axis and the sampled point (law of sines).
    const Float cosAlpha = sin2Theta / sinThetaMax +
                           cosTheta * safeSqrt(1 - sin2Theta / (sinThetaMax * sinThetaMax));
    const Float sinAlpha = safeSqrt(1 - cosAlpha * cosAlpha);
    Float sinPhi, cosPhi;  // φ = 2π u.y
    sinCosTwoPi(u.y, sinPhi, cosPhi);
    const Frame frame((s.center - refP) * (1 / distC));
    outward = frame.toWorld(Vec3f(-sinAlpha * cosPhi, -sinAlpha * sinPhi, -cosAlpha));
    outward = normalize(outward);
    p = s.center + outward * s.radius;
}

/// The point and spot lights' sample: the light's position `pos` as seen from `refP` (p, dist,
/// wi, pdf = selection pdf `selPdf`, delta) and the 1 / d² that scales its intensity into `Le`.
/// Returns false when refP is at `pos` (no direction).
CA_HD_INLINE bool sampleDeltaPosition(Vec3f pos, Vec3f refP, Float selPdf, LightSample& out,
                                      Float& invDist2) {
    const Vec3f d = pos - refP;
    const Float d2 = lengthSquared(d);
    if (!(d2 > 0)) return false;
    out.p = pos;
    out.dist = std::sqrt(d2);
    out.wi = d * (1 / out.dist);
    out.pdf = selPdf;
    out.delta = true;
    invDist2 = 1 / d2;
    return true;
}

/// Solid-angle pdf of a point `p` with front normal `n` sampled uniformly by area on a surface of
/// total area `area` (dω = |cosθ| dA / r²); 0 when p faces away from ref (or area is 0:
/// finalizeLights has not run). Generic over the lane type F (util/lane.h).
template <class F>
CA_HD_INLINE F areaToSolidAngle(const Vec3Of<F>& refP, const Vec3Of<F>& p, const Vec3Of<F>& n, F area) {
    const Vec3Of<F> d = p - refP;
    const F d2 = dot(d, d);
    const F cosL = -dot(d, n) / lane::sqrt(d2);
    const MaskOf<F> valid = (d2 > 0) & (area > 0) & (cosL > 0);  // else: back side of a one-sided emitter
    return lane::select(valid, d2 / (cosL * area), lane::splat<F>(0));
}
CA_HD_INLINE Float areaToSolidAngle(Vec3f refP, Vec3f p, Vec3f n, Float area) {
    return areaToSolidAngle<float>(refP, p, n, area);
}

/// The point corner + u.x edgeU + u.y edgeV of a parallelogram (a rectangle light), generic over
/// the lane type F.
template <class F>
CA_HD_FORCE_INLINE Vec3Of<F> parallelogramPoint(const Vec3Of<F>& corner, const Vec3Of<F>& edgeU,
                                                const Vec3Of<F>& edgeV, const Vec2Of<F>& u) {
    return corner + edgeU * u.x + edgeV * u.y;
}

/// The end of an area-light sample seen from refP (sampleLightIndex): the unit direction `wi` to
/// the sampled point `p`, its distance and the pdf with the light's selection probability;
/// false where the solid-angle pdf `pdf` is not positive and finite or p is at refP. Generic
/// over the lane type F.
template <class F>
CA_HD_INLINE MaskOf<F> areaLightDirection(const Vec3Of<F>& refP, const Vec3Of<F>& p, F pdf, F selPdf,
                                          Vec3Of<F>& wi, F& dist, F& pdfOut) {
    const Vec3Of<F> d = p - refP;
    dist = lane::sqrt(dot(d, d));
    wi = d * (1 / dist);
    pdfOut = pdf * selPdf;
    return (pdf > 0) & lane::isFinite(pdf) & (dist > 0);
}

}  // namespace light_detail

/// A point `p` uniform by area on area light `light`'s shape (mesh, cylinder, sphere) with its
/// front (emitting) unit normal `n`, flip_normals included: density 1 / light.area. Returns false
/// when the mesh's triangle CDF gives the point no probability. A mesh that is one parallelogram
/// (Light::isQuad) is sampled as Mitsuba samples its rectangle: p = corner + u.x edgeU + u.y edgeV.
CA_HD_INLINE bool sampleAreaLightPosition(const SceneView& scene, const Light& light, Vec2f u,
                                          Vec3f& p, Vec3f& n) {
    if (light.isQuad) {  // a parallelogram: the same density, no triangle to pick or rebuild
        p = light_detail::parallelogramPoint<float>(light.quadCorner, light.quadEdgeU, light.quadEdgeV, u);
        n = light.quadNormal;
        return true;
    }
    const Shape& shape = scene.shapes[light.shape];
    if (shape.type == ShapeType::Mesh) {
        // Triangle by area (reusing u.x, rescaled, so that u stays stratified), then a uniform
        // point on it: the area density is 1 / total area.
        const Span<const float> cdf(scene.lightCdf.data() + light.cdfOffset, light.cdfCount);
        Float triPdf;
        const uint32_t tri = sampleDiscreteCdf(cdf, u.x, &triPdf);
        if (!(triPdf > 0)) return false;
        const Float lo = tri > 0 ? cdf[tri - 1] : 0.0f;
        const Float ux = min((u.x - lo) / triPdf, kOneMinusEpsilon);
        const Vec2f b = sampleUniformTriangle(Vec2f(max(ux, Float(0)), u.y));
        // The same point and front normal as a ray hit there produces (flip_normals included),
        // without the hit's uv and partials.
        const TrianglePoint t = trianglePoint(scene, shape, shape.primOffset + tri, b.x, b.y);
        p = t.p;
        n = t.ng;
        return true;
    }
    if (shape.type == ShapeType::Cylinder) {
        // Uniform by area as Mitsuba's Cylinder::sample_position: height u.x, angle 2π u.y.
        const Cylinder& c = scene.cylinders[shape.primOffset];
        SurfaceInteraction si;
        Float sinPhi, cosPhi;  // φ = 2π u.y
        sinCosTwoPi(u.y, sinPhi, cosPhi);
        const Vec3f radial = c.xAxis * cosPhi + cross(c.axis, c.xAxis) * sinPhi;
        si.p = c.base + c.axis * (u.x * c.length) + radial * c.radius;
        cylinderInteraction(c, shape.flipNormals, si);
        p = si.p;
        n = si.ng;
        return true;
    }
    const Sphere& s = scene.spheres[shape.primOffset];
    const Vec3f outward = sampleUniformSphere(u);
    p = s.center + outward * s.radius;
    n = shape.flipNormals ? -outward : outward;
    return true;
}

/// Samples light `index` as seen from `refP` (`u` picks the point on it); `selPdf`, the
/// probability of having chosen that light, multiplies out.pdf. Returns false if there is
/// nothing to sample (back side, zero pdf).
CA_HD_INLINE bool sampleLightIndex(const SceneView& scene, uint32_t index, Float selPdf, Vec3f refP,
                                   Vec2f u, LightSample& out) {
    const Light& light = scene.lights[index];
    out.light = index;
    out.delta = false;
    out.n = Vec3f(0);

    switch (light.type) {
        case LightType::Point: {
            Float invDist2 = 0;
            if (!light_detail::sampleDeltaPosition(light.position, refP, selPdf, out, invDist2))
                return false;
            out.Le = light.radiance * invDist2;
            return true;
        }
        case LightType::Constant: {
            out.wi = sampleUniformSphere(u);
            out.p = refP + out.wi * (2 * light.sceneRadius);
            out.dist = kInfinity;
            out.Le = light.radiance;
            out.pdf = uniformSpherePdf() * selPdf;
            return true;
        }
        case LightType::Spot: {  // light_delta.h
            Float invDist2 = 0;
            if (!light_detail::sampleDeltaPosition(light.position, refP, selPdf, out, invDist2))
                return false;
            out.Le = spotIntensity(light, scene.textureView(), -out.wi) * invDist2;
            return !out.Le.isBlack();
        }
        case LightType::Directional: {  // light_delta.h; Mitsuba's point 2 radii away
            out.wi = -light.direction;
            const Float radius = max(light.sceneRadius, length(refP - light.sceneCenter));
            out.p = refP + out.wi * (2 * radius);
            out.dist = kInfinity;
            out.Le = light.radiance;
            out.pdf = selPdf;
            out.delta = true;
            return true;
        }
        case LightType::EnvMap: {  // light_envmap.h
            Float pdf;
            if (!envMapSample(scene, light, u, out.wi, pdf)) return false;
            out.p = refP + out.wi * (2 * light.sceneRadius);
            out.dist = kInfinity;
            out.Le = envMapRadiance(scene, light, out.wi);
            out.pdf = pdf * selPdf;
            return true;
        }
        case LightType::Area:
            break;
    }

    // Area light: a point on the shape and its front normal; a sphere seen from outside by its
    // visible cone, anything else uniformly by area.
    const Shape& shape = scene.shapes[light.shape];
    Float pdf, omc, distC;
    if (shape.type == ShapeType::Sphere &&
        light_detail::sphereCone(scene.spheres[shape.primOffset], refP, omc, distC)) {
        Vec3f outward;
        light_detail::sampleSphereCone(scene.spheres[shape.primOffset], refP, omc, distC, u, out.p,
                                       outward);
        out.n = shape.flipNormals ? -outward : outward;
        pdf = dot(out.p - refP, out.n) < 0 ? uniformConePdfOmc(omc) : Float(0);
    } else {
        if (!sampleAreaLightPosition(scene, light, u, out.p, out.n)) return false;
        pdf = light_detail::areaToSolidAngle(refP, out.p, out.n, light.area);
    }
    if (!(pdf > 0) || !std::isfinite(pdf)) return false;
    out.Le = light.radiance;
    return light_detail::areaLightDirection<float>(refP, out.p, pdf, selPdf, out.wi, out.dist, out.pdf);
}

/// Samples a light as seen from `refP`: `uSelect` picks the light (uniformly), `u` the point on
/// it. Returns false if there is nothing to sample (no lights, back side, zero pdf).
CA_HD_INLINE bool sampleLight(const SceneView& scene, Vec3f refP, Float uSelect, Vec2f u,
                              LightSample& out) {
    const uint32_t n = uint32_t(scene.lights.size());
    if (n == 0) return false;
    const uint32_t index = min(uint32_t(uSelect * Float(n)), n - 1);
    return sampleLightIndex(scene, index, Float(1) / Float(n), refP, u, out);
}

/// Solid-angle pdf (incl. selection) with which sampleLight would pick the point `onLight` of
/// area light `light` from `refP`: the MIS weight of an emitter hit by BSDF sampling.
CA_HD_INLINE Float pdfAreaLight(const SceneView& scene, uint32_t light, Vec3f refP,
                                const SurfaceInteraction& onLight) {
    if (light >= scene.lights.size()) return 0;
    const Light& l = scene.lights[light];
    if (l.type != LightType::Area) return 0;
    const Shape& shape = scene.shapes[l.shape];
    const Float selPdf = light_detail::selectionPdf(scene);
    if (shape.type == ShapeType::Sphere) {
        const Sphere& s = scene.spheres[shape.primOffset];
        Float omc, distC;
        if (light_detail::sphereCone(s, refP, omc, distC))
            return dot(onLight.p - refP, onLight.ng) < 0 ? uniformConePdfOmc(omc) * selPdf : 0;
    }
    return light_detail::areaToSolidAngle(refP, onLight.p, onLight.ng, l.area) * selPdf;
}

/// Solid-angle pdf (incl. selection) of sampling direction `dir` from the environment light.
CA_HD_INLINE Float pdfEnvironmentLight(const SceneView& scene, Vec3f dir) {
    if (scene.environmentLight < 0) return 0;
    const Light& env = scene.lights[uint32_t(scene.environmentLight)];
    if (env.type == LightType::EnvMap)
        return envMapPdf(scene, env, dir) * light_detail::selectionPdf(scene);
    return uniformSpherePdf() * light_detail::selectionPdf(scene);
}

/// Radiance an area emitter sends from `si` towards `w` (unit, away from the surface): zero on
/// the back side (w·ng <= 0) or when the shape does not emit.
CA_HD_INLINE Spectrum emittedRadiance(const SceneView& scene, const SurfaceInteraction& si,
                                      Vec3f w) {
    const Shape& shape = scene.shapes[si.shape];
    if (shape.light < 0) return {};
    const Light& light = scene.lights[uint32_t(shape.light)];
    if (light.type != LightType::Area || dot(w, si.ng) <= 0) return {};
    return light.radiance;
}

/// Radiance arriving from the environment along -dir (dir points away from the scene); zero
/// when the scene has no environment light.
CA_HD_INLINE Spectrum environmentRadiance(const SceneView& scene, Vec3f dir) {
    if (scene.environmentLight < 0) return {};
    const Light& env = scene.lights[uint32_t(scene.environmentLight)];
    if (env.type == LightType::EnvMap) return envMapRadiance(scene, env, dir);
    return env.radiance;
}

}  // namespace caustica
