// sppm_emission.h — emission rays for photon tracing: a point and a direction leaving a light,
// with the photon's flux weight Le·|cosθ| / (p_select · p_A · p_ω). Kernel code (CA_HD) in the
// style of scene/light.h, which samples lights only as seen from a point (next-event estimation).
//
// Lights are selected uniformly (as sampleLight), and every emitter type emits (docs/SPPM.md):
//   area         a point uniform by area (sampleAreaLightPosition), a cosine-weighted direction
//                about the front normal: Le · π · area / p_select.
//   point        a uniform direction: I · 4π / p_select.
//   spot         a direction uniform in the cone of cutoff_angle (in the light's frame): the
//                falloff (and texture) over the cone's pdf, I(ω) / (p_ω · p_select).
//   directional  the light's direction from a point uniform on the disk of radius R (the scene's
//                bounding sphere) perpendicular to it, pushed back R (Mitsuba 3's
//                directional::sample_ray): E · πR² / p_select.
//   constant     a uniform direction, the disk as above: Le · πR² / (p_ω · p_select).
//   envmap       a direction by envMapSample (importance by luminance), the disk as above:
//                Le(ω) · πR² / (p_ω · p_select).
// An environment's radiance Le(w) arrives from direction w, so its photon travels along -w.
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

namespace emission_detail {

/// A ray of a distant light travelling along unit `d`: its origin uniform on the disk of radius
/// R = light.sceneRadius about light.sceneCenter perpendicular to d, pushed back by R so that it
/// starts on or outside the scene's bounding sphere (Mitsuba 3's directional::sample_ray). The
/// disk's area is πR².
CA_HD_INLINE Ray distantRay(const Light& light, Vec3f d, Vec2f u) {
    const Frame frame(d);
    const Vec2f disk = sampleConcentricDisk(u);
    const Vec3f o =
        light.sceneCenter + (frame.s * disk.x + frame.t * disk.y - d) * light.sceneRadius;
    return Ray{o, d, kInfinity};
}

/// 1 - cos(cutoff) of a spot's cone, as 2 sin²(cutoff / 2) (no cancellation for narrow cones).
CA_HD_INLINE Float spotConeOmc(const Light& light) {
    const Float s = std::sin(Float(0.5) * light.cutoff);
    return 2 * s * s;
}

/// |det| of the spot's localFromWorld (rows r0, r1, r2): directions map from the local cone to the
/// world by its inverse, whose solid-angle Jacobian is dω_local / dω_world = |det| / |L w|³ at a
/// unit world direction w (1 for a rotation).
CA_HD_INLINE Float spotDet(const Light& light) {
    const Vec3f(&r)[3] = light.localFromWorld;
    return std::fabs(dot(r[0], cross(r[1], r[2])));
}

/// Upper bound of |L w|³ / |det L| over unit w, L = localFromWorld: the largest singular value σ
/// of L is bounded by the largest absolute row sum of LᵀL (an induced norm bounds the spectral
/// radius; exact for rotations and uniform scales).
CA_HD_INLINE Float spotJacobianBound(const Light& light) {
    const Vec3f(&r)[3] = light.localFromWorld;
    const Vec3f c[3] = {Vec3f(r[0].x, r[1].x, r[2].x), Vec3f(r[0].y, r[1].y, r[2].y),
                        Vec3f(r[0].z, r[1].z, r[2].z)};
    Float sigma2 = 0;
    for (int i = 0; i < 3; ++i)
        sigma2 = max(sigma2, std::fabs(dot(c[i], c[0])) + std::fabs(dot(c[i], c[1])) +
                                 std::fabs(dot(c[i], c[2])));
    const Float det = spotDet(light);
    return det > 0 ? sigma2 * std::sqrt(sigma2) / det : Float(0);
}

/// Largest channel texture `id` takes: exact for constants and bitmaps (an interpolation never
/// exceeds its texels); for a checkerboard, every texture of a smaller or equal id (its children
/// have smaller ids), an over-estimate.
CA_HD_INLINE Float textureMaxValue(const TextureView& v, uint32_t id) {
    const uint32_t first = v.textures[id].type == TextureType::Checkerboard ? 0 : id;
    Float m = 0;
    for (uint32_t k = first; k <= id; ++k) {
        const Texture& t = v.textures[k];
        if (t.type == TextureType::Constant) m = max(m, t.value.maxValue());
        if (t.type == TextureType::Checkerboard) {
            if (t.child0 == kNoTexture) m = max(m, t.value.maxValue());
            if (t.child1 == kNoTexture) m = max(m, t.value1.maxValue());
        }
        if (t.type == TextureType::Bitmap)
            for (size_t i = 0; i < size_t(t.width) * size_t(t.height); ++i)
                m = max(m, v.texels[t.texelOffset + i].maxValue());
    }
    return m;
}

/// Largest Le(ω) / p_ω (per channel) of envMapSample's directions, over the bilinear patches
/// that have probability: Le is at most the largest of the patch's four texels, and
/// p_ω = pRow · pCol · W (H − 1) / (2π² sinθ) is least where sinθ is largest on its rows.
CA_HD_INLINE Float envMapMaxRatio(const SceneView& scene, const Light& l) {
    using namespace envmap_detail;
    if (l.radiance.isBlack()) return 0;
    const uint32_t W = l.texWidth, H = l.texHeight;
    const Spectrum* t = scene.lightTexels.data() + l.texOffset;
    const Float dTheta = kPi / Float(H - 1);
    Float m = 0;
    for (uint32_t j = 0; j + 1 < H; ++j) {
        const Float pRow = discreteCdfPmf(marginalCdf(scene, l), j);
        if (!(pRow > 0)) continue;
        const Float th0 = Float(j) * dTheta, th1 = Float(j + 1) * dTheta;
        const Float sinMax =
            th0 <= kPi / 2 && th1 >= kPi / 2 ? Float(1) : max(std::sin(th0), std::sin(th1));
        const Span<const float> row = rowCdf(scene, l, j);
        for (uint32_t i = 0; i < W; ++i) {
            const Float pCol = discreteCdfPmf(row, i);
            if (!(pCol > 0)) continue;
            const uint32_t i1 = i + 1 == W ? 0 : i + 1;
            const Float le =
                max(max(t[j * W + i].maxValue(), t[j * W + i1].maxValue()),
                    max(t[(j + 1) * W + i].maxValue(), t[(j + 1) * W + i1].maxValue()));
            m = max(m, le * sinMax / (pRow * pCol));
        }
    }
    return m * (2 * kPi * kPi) / (Float(W) * Float(H - 1));
}

}  // namespace emission_detail

/// Samples a photon: uSelect picks the light, uPos the point (area lights; the disk of the
/// distant ones), uDir the direction. Returns false when there is nothing to emit (no lights,
/// a black emitter or direction, a zero pdf).
CA_HD_INLINE bool sampleEmission(const SceneView& scene, Float uSelect, Vec2f uPos, Vec2f uDir,
                                 EmissionSample& out) {
    using namespace emission_detail;
    const uint32_t count = uint32_t(scene.lights.size());
    if (count == 0) return false;
    const uint32_t index = min(uint32_t(uSelect * Float(count)), count - 1);
    const Light& light = scene.lights[index];
    const Float invSelect = Float(count);
    const Float diskArea = kPi * light.sceneRadius * light.sceneRadius;
    switch (light.type) {
        case LightType::Point:
            out.ray = Ray{light.position, sampleUniformSphere(uDir), kInfinity};
            out.flux = light.radiance * (4 * kPi * invSelect);
            return !out.flux.isBlack();
        case LightType::Spot: {
            // Uniform in the local cone, mapped to the world by localFromWorld's inverse (its
            // columns are the cofactors r1×r2, r2×r0, r0×r1 over det; the sign of det kept).
            const Float omc = spotConeOmc(light), det = spotDet(light);
            if (!(omc > 0) || !(det > 0)) return false;
            const Vec3f local = sampleUniformConeOmc(uDir, omc);
            const Vec3f(&r)[3] = light.localFromWorld;
            const Vec3f w = cross(r[1], r[2]) * local.x + cross(r[2], r[0]) * local.y +
                            cross(r[0], r[1]) * local.z;
            const Vec3f d = normalize(dot(r[0], cross(r[1], r[2])) < 0 ? -w : w);
            const Float lw = length(applyRows(light.localFromWorld, d));
            const Float pdf = uniformConePdfOmc(omc) * det / (lw * lw * lw);
            if (!(pdf > 0) || !std::isfinite(pdf)) return false;
            out.ray = Ray{light.position, d, kInfinity};
            out.flux = spotIntensity(light, scene.textureView(), d) * (invSelect / pdf);
            return !out.flux.isBlack();
        }
        case LightType::Directional:
            out.ray = distantRay(light, light.direction, uPos);
            out.flux = light.radiance * (diskArea * invSelect);
            return !out.flux.isBlack();
        case LightType::Constant:  // radiance from wi travels along -wi
            out.ray = distantRay(light, -sampleUniformSphere(uDir), uPos);
            out.flux = light.radiance * (diskArea * 4 * kPi * invSelect);
            return !out.flux.isBlack();
        case LightType::EnvMap: {
            Vec3f wi;
            Float pdf;
            if (!envMapSample(scene, light, uDir, wi, pdf)) return false;
            out.ray = distantRay(light, -wi, uPos);
            out.flux = envMapRadiance(scene, light, wi) * (diskArea * invSelect / pdf);
            return !out.flux.isBlack();
        }
        case LightType::Area:
            break;
    }
    if (!(light.area > 0)) return false;
    Vec3f p, n;
    if (!sampleAreaLightPosition(scene, light, uPos, p, n)) return false;
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

/// The flux the photons of sampleEmission carry at most (host or device; O(texels) for an
/// envmap or a textured spot): the largest channel of any light's weight, an over-estimate only
/// for a non-rigid spot transform or a checkerboard spot texture. Sets the scale of the
/// fixed-point flux sums.
CA_HD_INLINE Float maxEmissionFlux(const SceneView& scene) {
    using namespace emission_detail;
    const Float count = Float(scene.lights.size());
    Float m = 0;
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        const Float le = l.radiance.maxValue();
        const Float disk = kPi * l.sceneRadius * l.sceneRadius * count;
        switch (l.type) {
            case LightType::Area:
                m = max(m, le * kPi * l.area * count);
                break;
            case LightType::Point:
                m = max(m, le * 4 * kPi * count);
                break;
            case LightType::Spot: {
                const Float tex = l.texture == kNoTexture
                                      ? Float(1)
                                      : textureMaxValue(scene.textureView(), l.texture);
                m = max(m, le * tex * 2 * kPi * spotConeOmc(l) * spotJacobianBound(l) * count);
                break;
            }
            case LightType::Directional:
                m = max(m, le * disk);
                break;
            case LightType::Constant:
                m = max(m, le * 4 * kPi * disk);
                break;
            case LightType::EnvMap:  // the scale is in the texels
                m = max(m, envMapMaxRatio(scene, l) * disk);
                break;
        }
    }
    return m;
}

}  // namespace caustica
