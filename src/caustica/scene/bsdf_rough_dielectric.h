// bsdf_rough_dielectric.h — Mitsuba 3's roughdielectric (Walter et al. 2007, "Microfacet Models
// for Refraction through Rough Surfaces"): a rough interface between two dielectrics, Beckmann or
// GGX normals, reflection with probability F(wo·m) and refraction otherwise, visible-normal
// sampling. Shared CPU/GPU kernel code, used by bsdf.h. Directions are local (+z the macro
// normal), `wo` towards the viewer, `wi` towards the light (Mitsuba's si.wi and wo); both sides
// of the surface work; radiance transport (refraction scales by 1/η²).
#pragma once

#include "caustica/scene/bsdf_data.h"
#include "caustica/scene/fresnel.h"
#include "caustica/scene/microfacet.h"

namespace caustica::bsdf_detail {

/// Refraction of `w` through a microfacet of normal `m` (Mitsuba's refract(wi, m, cosθt, η_i/η_t)),
/// with the signed cosThetaT and etaTI of fresnelDielectric(dot(w, m), η).
CA_HD_INLINE Vec3f refractMicro(Vec3f w, Vec3f m, Float cosThetaT, Float etaTI) {
    return m * (dot(w, m) * etaTI + cosThetaT) - w * etaTI;
}

/// The half vector of a direction pair (upper hemisphere) and the relative IOR η_t/η_i seen from
/// `wo` for a refraction (1 for a reflection).
struct RoughDielectricPair {
    Vec3f m;
    Float eta;
    bool reflect;
};

CA_HD_INLINE RoughDielectricPair roughDielectricPair(const Bsdf& b, Vec3f wo, Vec3f wi) {
    RoughDielectricPair p;
    p.reflect = wo.z * wi.z > 0;
    p.eta = wo.z > 0 ? b.etaRatio : 1 / b.etaRatio;
    p.m = normalize(wo + wi * (p.reflect ? Float(1) : p.eta));
    if (p.m.z < 0) p.m = -p.m;
    return p;
}

/// f · |cosθi| (Mitsuba's eval).
CA_HD_INLINE Spectrum roughDielectricEval(const Bsdf& b, Vec3f wo, Vec3f wi) {
    if (wo.z == 0 || wi.z == 0) return {};
    const RoughDielectricPair p = roughDielectricPair(b, wo, wi);
    const MicrofacetDistribution md(b.distribution, b.alphaU, b.alphaV);
    const Float d = md.D(p.m);
    const Float g = md.G(wo, wi, p.m);  // zero when a direction sees the back of m
    if (d == 0 || g == 0) return {};
    const Float f = fresnelDielectric(dot(wo, p.m), b.etaRatio).r;
    if (p.reflect) return b.reflectance * (f * d * g / (4 * std::fabs(wo.z)));
    // Walter et al. eq. 21 with the 1/η² of radiance transport.
    const Float om = dot(wo, p.m), im = dot(wi, p.m);
    const Float value = sqr(1 / p.eta) * (1 - f) * d * g * sqr(p.eta) * om * im /
                        (wo.z * sqr(om + p.eta * im));
    return b.transmittance * std::fabs(value);
}

/// Solid-angle pdf of roughDielectricSample (Mitsuba's pdf).
CA_HD_INLINE Float roughDielectricPdf(const Bsdf& b, Vec3f wo, Vec3f wi) {
    if (wo.z == 0 || wi.z == 0) return 0;
    const RoughDielectricPair p = roughDielectricPair(b, wo, wi);
    // The side tests of G1, which sampling and eval apply too.
    if (dot(wo, p.m) * wo.z <= 0 || dot(wi, p.m) * wi.z <= 0) return 0;
    const Float om = dot(wo, p.m), im = dot(wi, p.m);
    // Jacobian of the half-vector mapping (Walter et al. eqs. 14 and 17).
    const Float dwhDwi = p.reflect ? 1 / (4 * im) : sqr(p.eta) * im / sqr(om + p.eta * im);
    const MicrofacetDistribution md(b.distribution, b.alphaU, b.alphaV);
    const Vec3f woUp = wo.z < 0 ? -wo : wo;
    Float prob = md.visiblePdf(woUp, p.m);
    const Float f = fresnelDielectric(om, b.etaRatio).r;
    prob *= p.reflect ? f : 1 - f;
    return prob * std::fabs(dwhDwi);
}

/// Samples a visible normal (seen from wo mirrored to the upper side), then reflection with
/// probability F(wo·m), else refraction through m.
CA_HD_INLINE bool roughDielectricSample(const Bsdf& b, Vec3f wo, Float uLobe, Vec2f u,
                                        Vec3f& wi, Spectrum& weight, Float& pdf, Float& eta) {
    if (wo.z == 0) return false;
    const MicrofacetDistribution md(b.distribution, b.alphaU, b.alphaV);
    const Vec3f woUp = wo.z < 0 ? -wo : wo;
    const Vec3f m = md.sampleVisible(woUp, u);
    pdf = md.visiblePdf(woUp, m);
    if (!(pdf > 0)) return false;
    const FresnelDielectric f = fresnelDielectric(dot(wo, m), b.etaRatio);
    Float dwhDwi;
    if (uLobe <= f.r) {
        wi = reflect(wo, m);
        eta = 1;
        pdf *= f.r;
        dwhDwi = 1 / (4 * dot(wi, m));
        weight = b.reflectance;
        if (wi.z * wo.z <= 0) return false;  // reflected through the macro-surface
    } else {
        wi = refractMicro(wo, m, f.cosThetaT, f.etaTI);
        eta = f.etaIT;
        pdf *= 1 - f.r;
        dwhDwi = sqr(eta) * dot(wi, m) / sqr(dot(wo, m) + eta * dot(wi, m));
        weight = b.transmittance * sqr(f.etaTI);
        if (wi.z * wo.z >= 0) return false;  // refracted back to the viewer's side
    }
    // f |cosθi| / pdf = G1(wi, m) (visible-normal sampling); G1 is zero on the wrong side.
    weight = weight * md.G1(wi, m);
    pdf *= std::fabs(dwhDwi);
    return pdf > 0 && !weight.isBlack();
}

}  // namespace caustica::bsdf_detail
