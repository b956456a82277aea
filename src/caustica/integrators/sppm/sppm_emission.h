// sppm_emission.h — emission rays for photon tracing: a point and a direction leaving a light,
// with the photon's flux weight Le·|cosθ| / (p_select · p_A · p_ω). Kernel code (CA_HD) in the
// style of scene/light.h, which samples lights only as seen from a point (next-event estimation).
//
// Lights are selected uniformly (as sampleLight). Area emitters (mesh, sphere, cylinder) emit on
// the front side only (light.h's emittedRadiance): a point uniform by area (mesh: a triangle by
// area through the light's CDF, then a uniform point) and a cosine-weighted direction about the
// front normal, so the weight is Le · π · area / p_select. Point lights: a uniform direction,
// weight I · 4π / p_select. Spot, directional, constant and envmap emitters need a disk of the
// scene's bounds (or a cone) and are not sampled yet: sppmEmitterSupported() says which are.
#pragma once

#include "caustica/scene/interaction.h"
#include "caustica/scene/light.h"
#include "caustica/util/sampling.h"

namespace caustica {

/// One photon leaving a light.
struct EmissionSample {
    Ray ray;
    Spectrum flux;  // Le·|cosθ| / (p_select · p_A · p_ω): the flux the photon carries
};

CA_HD_INLINE bool sppmEmitterSupported(LightType type) {
    return type == LightType::Area || type == LightType::Point;
}

/// A point uniform by area on area light `light`'s shape, with its front (emitting) normal.
CA_HD_INLINE bool sampleAreaLightPoint(const SceneView& scene, const Light& light, Vec2f u, Vec3f& p,
                                       Vec3f& n) {
    const Shape& shape = scene.shapes[light.shape];
    if (shape.type == ShapeType::Mesh) {
        // As sampleLight: a triangle by area (u.x reused, rescaled), then a uniform point on it.
        const Span<const float> cdf(scene.lightCdf.data() + light.cdfOffset, light.cdfCount);
        Float triPdf;
        const uint32_t tri = sampleDiscreteCdf(cdf, u.x, &triPdf);
        if (!(triPdf > 0)) return false;
        const Float lo = tri > 0 ? cdf[tri - 1] : 0.0f;
        const Float ux = min((u.x - lo) / triPdf, kOneMinusEpsilon);
        const Vec2f b = sampleUniformTriangle(Vec2f(max(ux, Float(0)), u.y));
        Hit hit;
        hit.t = 0;
        hit.primId = shape.primOffset + tri;
        hit.b1 = b.x;
        hit.b2 = b.y;
        const SurfaceInteraction si = computeInteraction(scene, Ray{Vec3f(0), Vec3f(0), 0}, hit);
        p = si.p;
        n = si.ng;
        return true;
    }
    if (shape.type == ShapeType::Cylinder) {
        const Cylinder& c = scene.cylinders[shape.primOffset];
        SurfaceInteraction si;
        const Float phi = 2 * kPi * u.y;
        const Vec3f radial = c.xAxis * std::cos(phi) + cross(c.axis, c.xAxis) * std::sin(phi);
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

/// Samples a photon: uSelect picks the light, uPos the point, uDir the direction. Returns false
/// when there is nothing to emit (no lights, an unsupported or black emitter).
CA_HD_INLINE bool sampleEmission(const SceneView& scene, Float uSelect, Vec2f uPos, Vec2f uDir,
                                 EmissionSample& out) {
    const uint32_t count = uint32_t(scene.lights.size());
    if (count == 0) return false;
    const uint32_t index = min(uint32_t(uSelect * Float(count)), count - 1);
    const Light& light = scene.lights[index];
    const Float invSelect = Float(count);
    if (light.type == LightType::Point) {
        out.ray = Ray{light.position, sampleUniformSphere(uDir), kInfinity};
        out.flux = light.radiance * (4 * kPi * invSelect);
        return !out.flux.isBlack();
    }
    if (light.type != LightType::Area || !(light.area > 0)) return false;
    Vec3f p, n;
    if (!sampleAreaLightPoint(scene, light, uPos, p, n)) return false;
    const Float len = length(n);
    if (!(len > 0)) return false;
    n = n * (1 / len);
    const Vec3f local = sampleCosineHemisphere(uDir);
    if (!(local.z > 0)) return false;
    const Vec3f d = normalize(Frame(n).toWorld(local));
    out.ray = spawnRay(p, n, d);
    // Le·cosθ / ((1/area) · (cosθ/π) · (1/count)).
    out.flux = light.radiance * (kPi * light.area * invSelect);
    return !out.flux.isBlack();
}

/// The flux the photons of sampleEmission carry at most (host or device): the largest channel
/// of any supported light's weight. Sets the scale of the fixed-point flux sums.
CA_HD_INLINE Float maxEmissionFlux(const SceneView& scene) {
    const Float count = Float(scene.lights.size());
    Float m = 0;
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        if (l.type == LightType::Point) m = max(m, l.radiance.maxValue() * 4 * kPi * count);
        if (l.type == LightType::Area) m = max(m, l.radiance.maxValue() * kPi * l.area * count);
    }
    return m;
}

}  // namespace caustica
