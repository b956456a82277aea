// bsdf_principled.h — Mitsuba 3's principled BSDF (src/bsdfs/principled.cpp and
// principledhelpers.h; Burley 2012/2015, "Physically Based Shading at Disney" and "Extending
// the Disney BRDF to a BSDF with Integrated Subsurface Scattering"): a GGX specular lobe
// (anisotropic through the shading frame) with a Fresnel term blending the dielectric, metallic
// and tinted responses, GGX transmission (spec_trans), a GTR1 clearcoat, Burley's diffuse with
// retro-reflection (and flatness' fake subsurface), and sheen. Lobes are present only when their
// parameter was given (PrincipledParams::has*), as Mitsuba. Every formula, including the
// clearcoat's missing 1/(4 cosθ cosθ) and the sampling probabilities, follows Mitsuba 3.
// Local frame; `wo` towards the viewer (Mitsuba's si.wi), `wi` towards the light (Mitsuba's wo).
#pragma once

#include "caustica/scene/bsdf_data.h"
#include "caustica/scene/bsdf_rough_dielectric.h"
#include "caustica/scene/fresnel.h"
#include "caustica/scene/microfacet.h"
#include "caustica/util/sampling.h"

namespace caustica::bsdf_detail {

CA_HD_INLINE Float mulSign(Float v, Float s) { return s < 0 ? -v : v; }
CA_HD_INLINE Vec3f mulSign(Vec3f v, Float s) { return s < 0 ? -v : v; }

/// Mitsuba's luminance of a linear RGB colour.
CA_HD_INLINE Float luminanceOf(const Spectrum& c) {
    return c.r * Float(0.212671) + c.g * Float(0.715160) + c.b * Float(0.072169);
}

/// Schlick's weight (1 - cosθ)^5, cosθ clamped to [0, 1].
CA_HD_INLINE Float schlickWeight(Float c) {
    const Float m = clamp(1 - c, Float(0), Float(1));
    return sqr(sqr(m)) * m;
}

/// Mitsuba's calc_schlick: R0 + (1 - R0) w, w from the incident cosine (η_it > 1) or from the
/// refracted one (η_it < 1).
CA_HD_INLINE Float schlickFresnel(Float r0, Float cosThetaI, Float eta) {
    const bool outside = cosThetaI >= 0;
    const Float etaIT = outside ? eta : 1 / eta, etaTI = outside ? 1 / eta : eta;
    const Float cosT = safeSqrt(1 - (1 - cosThetaI * cosThetaI) * sqr(etaTI));
    const Float w = etaIT > 1 ? schlickWeight(std::fabs(cosThetaI)) : schlickWeight(cosT);
    return r0 + (1 - r0) * w;
}

CA_HD_INLINE Spectrum schlickFresnel(const Spectrum& r0, Float cosThetaI, Float eta) {
    return {schlickFresnel(r0.r, cosThetaI, eta), schlickFresnel(r0.g, cosThetaI, eta),
            schlickFresnel(r0.b, cosThetaI, eta)};
}

/// Mitsuba's mac_mic_compatibility: both directions on the side of microfacet `m` (oriented to
/// the viewer's side) for a reflection, on opposite sides for a refraction. `v` is the viewer.
CA_HD_INLINE bool macMicCompatible(Vec3f m, Vec3f v, Vec3f l, Float cosV, bool reflection) {
    const Vec3f ms = mulSign(m, cosV);
    return dot(v, ms) > 0 && (reflection ? dot(l, ms) > 0 : dot(l, ms) < 0);
}

/// GTR1 (Berry) distribution of the clearcoat, isotropic, roughness alpha.
struct Gtr1 {
    Float alpha;
    CA_HD Float D(Vec3f m) const {
        const Float a2 = sqr(alpha);
        const Float r = (a2 - 1) / (kPi * std::log(a2) * (1 + (a2 - 1) * sqr(m.z)));
        return r * m.z > Float(1e-20) ? r : Float(0);
    }
    CA_HD Float pdf(Vec3f m) const { return m.z < 0 ? Float(0) : m.z * D(m); }
    CA_HD Vec3f sample(Vec2f u) const {
        const Float a2 = sqr(alpha);
        const Float cos2 = (1 - std::pow(a2, 1 - u.y)) / (1 - a2);
        const Float sinT = std::sqrt(max(Float(0), 1 - cos2));
        const Float cosT = std::sqrt(max(Float(0), cos2));
        Float sinPhi, cosPhi;  // φ = 2π u.x
        sinCosTwoPi(u.x, sinPhi, cosPhi);
        return {cosPhi * sinT, sinPhi * sinT, cosT};
    }
};

/// Mitsuba's smith_ggx1 (the clearcoat's masking, α 0.25).
CA_HD_INLINE Float smithGgx1(Vec3f v, Vec3f wh, Float alpha) {
    if (dot(v, wh) * v.z <= 0) return 0;
    if (v.z == 1) return 1;
    const Float c2 = sqr(std::fabs(v.z)), tan2 = (1 - c2) / c2;
    return 2 / (1 + std::sqrt(1 + sqr(alpha) * tan2));
}

/// The specular distribution: α = max(0.001, roughness²), stretched by the anisotropy
/// (aspect sqrt(1 - 0.9 anisotropic)) when given (Mitsuba's calc_dist_params).
CA_HD_INLINE MicrofacetDistribution principledDistribution(const PrincipledParams& p) {
    const Float r2 = sqr(p.roughness);
    if (!p.hasAnisotropic) {
        const Float a = max(Float(0.001), r2);
        return {MicrofacetType::GGX, a, a};
    }
    const Float aspect = std::sqrt(1 - Float(0.9) * p.anisotropic);
    return {MicrofacetType::GGX, max(Float(0.001), r2 / aspect), max(Float(0.001), r2 * aspect)};
}

/// Sampling probabilities of the four lobes (Mitsuba normalises all but the specular reflection,
/// which takes what remains).
struct PrincipledProbs {
    Float specReflect, specTrans, clearcoat, diffuse;
};

CA_HD_INLINE PrincipledProbs principledProbs(const PrincipledParams& p, bool front, Float f) {
    const Float brdf = (1 - p.metallic) * (1 - p.specTrans);
    const Float bsdf = p.hasSpecTrans ? (1 - p.metallic) * p.specTrans : Float(0);
    PrincipledProbs r;
    r.specReflect = front ? p.specRate * (1 - bsdf * (1 - f)) : f;
    r.specTrans = p.hasSpecTrans ? (front ? p.specRate * bsdf * (1 - f) : 1 - f) : Float(0);
    r.clearcoat = p.hasClearcoat && front ? Float(0.25) * p.clearcoat * p.clearcoatRate : Float(0);
    r.diffuse = front ? brdf * p.diffuseRate : Float(0);
    const Float inv = 1 / (r.specReflect + r.specTrans + r.clearcoat + r.diffuse);
    r.specReflect *= inv;
    r.specTrans *= inv;
    r.clearcoat *= inv;
    r.diffuse *= inv;
    return r;
}

/// The half vector of a pair (Mitsuba's eval/pdf), on the upper side.
CA_HD_INLINE Vec3f principledHalf(const PrincipledParams& p, Vec3f v, Vec3f l) {
    const bool reflect = v.z * l.z > 0;
    const Float etaPath = v.z > 0 ? p.eta : 1 / p.eta;
    const Vec3f wh = normalize(v + l * (reflect ? Float(1) : etaPath));
    return mulSign(wh, wh.z);
}

/// f · |cosθi| (Mitsuba's eval). v = wo (viewer), l = wi (light).
CA_HD_INLINE Spectrum principledEval(const Bsdf& b, Vec3f v, Vec3f l) {
    const PrincipledParams& p = b.principled;
    const Float cosV = v.z, cosL = l.z;
    if (cosV == 0) return {};
    const Spectrum& base = b.reflectance;
    const Float brdf = (1 - p.metallic) * (1 - p.specTrans), bsdf = (1 - p.metallic) * p.specTrans;
    const bool reflect = cosV * cosL > 0, refract = cosV * cosL < 0, front = cosV > 0;
    const Float etaPath = front ? p.eta : 1 / p.eta, invEtaPath = front ? 1 / p.eta : p.eta;
    const MicrofacetDistribution md = principledDistribution(p);
    const Vec3f wh = principledHalf(p, v, l);
    const Float f = fresnelDielectric(dot(v, wh), p.eta).r;
    const bool reflCompat = macMicCompatible(wh, v, l, cosV, true);
    const bool refrCompat = macMicCompatible(wh, v, l, cosV, false);
    const Float d = md.D(wh), g = md.G(v, l, wh);
    Spectrum value;
    if (reflect && reflCompat && f > 0) {  // main specular reflection
        const Float vh = dot(v, wh);
        Spectrum fp;  // Mitsuba's principled_fresnel
        if (front) {
            Spectrum schlick;
            if (p.hasMetallic) schlick += schlickFresnel(base, vh, p.eta) * p.metallic;
            const Float specTint = p.hasSpecTint ? p.specTint : Float(0);
            if (p.hasSpecTint) {
                const Float lum = luminanceOf(base);
                const Spectrum tint = lum > 0 ? base * (1 / lum) : Spectrum(1.0f);
                const Float etaIT = vh >= 0 ? p.eta : 1 / p.eta;
                const Float r0 = sqr((etaIT - 1) / (etaIT + 1));
                schlick += schlickFresnel(tint * r0, vh, p.eta) * ((1 - p.metallic) * specTint);
            }
            fp = schlick + Spectrum((1 - p.metallic) * (1 - specTint) * f);
        } else {
            fp = Spectrum(bsdf * f);  // inside: the plain dielectric
        }
        value += fp * (d * g / (4 * std::fabs(cosV)));
    }
    if (p.hasSpecTrans && bsdf > 0 && refract && refrCompat && f < 1) {  // transmission
        const Float vh = dot(v, wh), lh = dot(l, wh);
        const Float t = sqr(invEtaPath) * (1 - f) * d * g * sqr(etaPath) * vh * lh /
                        (cosV * sqr(vh + etaPath * lh));
        const Spectrum sqrtBase(std::sqrt(base.r), std::sqrt(base.g), std::sqrt(base.b));
        value += sqrtBase * (bsdf * std::fabs(t));
    }
    if (p.hasClearcoat && p.clearcoat > 0 && reflect && reflCompat && front) {
        const Float fcc = schlickFresnel(Float(0.04), dot(v, wh), p.eta);
        const Gtr1 cc{Float(0.1) + (Float(0.001) - Float(0.1)) * p.clearcoatGloss};
        const Float gcc = smithGgx1(v, wh, Float(0.25)) * smithGgx1(l, wh, Float(0.25));
        value += Spectrum(p.clearcoat * Float(0.25) * fcc * cc.D(wh) * gcc * std::fabs(cosL));
    }
    if (brdf > 0 && reflect && front) {  // diffuse, retro-reflection, fake subsurface, sheen
        const Float fo = schlickWeight(std::fabs(cosL)), fi = schlickWeight(std::fabs(cosV));
        const Float fDiff = (1 - Float(0.5) * fi) * (1 - Float(0.5) * fo);
        const Float cosD = dot(wh, l);
        const Float rr = 2 * p.roughness * sqr(cosD);
        const Float fRetro = rr * (fo + fi + fo * fi * (rr - 1));
        Float lobe = fDiff + fRetro;
        if (p.hasFlatness) {
            const Float fss90 = rr / 2;
            const Float fss = (1 + (fss90 - 1) * fo) * (1 + (fss90 - 1) * fi);
            const Float ss = Float(1.25) * (fss * (1 / (std::fabs(cosL) + std::fabs(cosV)) -
                                                   Float(0.5)) + Float(0.5));
            lobe = lobe + (ss - lobe) * p.flatness;
        }
        value += base * (brdf * std::fabs(cosL) * kInvPi * lobe);
        if (p.hasSheen && p.sheen > 0 && 1 - p.metallic > 0) {
            const Float fd = schlickWeight(std::fabs(cosD));
            Spectrum sheenColour(1.0f);
            if (p.hasSheenTint) {
                const Float lum = luminanceOf(base);
                const Spectrum tint = lum > 0 ? base * (1 / lum) : Spectrum(1.0f);
                sheenColour = Spectrum(1.0f) + (tint - Spectrum(1.0f)) * p.sheenTint;
            }
            value += sheenColour * (p.sheen * (1 - p.metallic) * fd * std::fabs(cosL));
        }
    }
    return value;
}

/// Mitsuba's pdf.
CA_HD_INLINE Float principledPdf(const Bsdf& b, Vec3f v, Vec3f l) {
    const PrincipledParams& p = b.principled;
    const Float cosV = v.z, cosL = l.z;
    if (cosV == 0) return 0;
    const bool front = cosV > 0, reflect = cosV * cosL > 0, refract = cosV * cosL < 0;
    const Float etaPath = front ? p.eta : 1 / p.eta;
    const Vec3f wh = principledHalf(p, v, l);
    const MicrofacetDistribution md = principledDistribution(p);
    const Float f = fresnelDielectric(dot(v, wh), p.eta).r;
    const PrincipledProbs pr = principledProbs(p, front, f);
    const Float vh = dot(v, wh), lh = dot(l, wh);
    Float dwhDwl;
    if (p.hasSpecTrans && !reflect)
        dwhDwl = std::fabs(sqr(etaPath) * lh / sqr(vh + etaPath * lh));
    else
        dwhDwl = std::fabs(1 / (4 * lh));
    const Vec3f vUp = mulSign(v, cosV);
    Float pdf = 0;
    const bool reflMacMic = macMicCompatible(wh, v, l, cosV, true) && reflect;
    if (reflMacMic) pdf += pr.specReflect * md.visiblePdf(vUp, wh) * dwhDwl;
    if (reflect) pdf += pr.diffuse * kInvPi * cosL;
    if (p.hasSpecTrans && macMicCompatible(wh, v, l, cosV, false) && refract)
        pdf += pr.specTrans * md.visiblePdf(vUp, wh) * dwhDwl;
    if (p.hasClearcoat && reflMacMic) {
        const Gtr1 cc{Float(0.1) + (Float(0.001) - Float(0.1)) * p.clearcoatGloss};
        pdf += pr.clearcoat * cc.pdf(wh) * dwhDwl;
    }
    return pdf;
}

/// Mitsuba's sample: a lobe by uLobe (diffuse, clearcoat, transmission, else reflection), its
/// direction, then weight = eval / pdf of the whole BSDF.
CA_HD_INLINE bool principledSample(const Bsdf& b, Vec3f v, Float uLobe, Vec2f u, Vec3f& l,
                                   Spectrum& weight, Float& pdf, Float& eta) {
    const PrincipledParams& p = b.principled;
    const Float cosV = v.z;
    if (cosV == 0) return false;
    const bool front = cosV > 0;
    const Float bsdf = p.hasSpecTrans ? (1 - p.metallic) * p.specTrans : Float(0);
    if (!front && !(bsdf > 0)) return false;
    const MicrofacetDistribution md = principledDistribution(p);
    const Vec3f m = md.sampleVisible(mulSign(v, cosV), u);
    const FresnelDielectric f = fresnelDielectric(dot(v, m), p.eta);
    const PrincipledProbs pr = principledProbs(p, front, f.r);
    eta = 1;
    if (uLobe < pr.diffuse) {
        l = sampleCosineHemisphere(u);
        if (!(cosV * l.z > 0)) return false;
    } else if (p.hasClearcoat && uLobe < pr.diffuse + pr.clearcoat) {
        const Gtr1 cc{Float(0.1) + (Float(0.001) - Float(0.1)) * p.clearcoatGloss};
        const Vec3f mcc = cc.sample(u);
        l = reflect(v, mcc);
        if (!(macMicCompatible(mcc, v, l, cosV, true) && cosV * l.z > 0)) return false;
    } else if (p.hasSpecTrans && uLobe < pr.diffuse + pr.clearcoat + pr.specTrans) {
        l = refractMicro(v, m, f.cosThetaT, f.etaTI);
        eta = f.etaIT;
        if (!(macMicCompatible(m, v, l, cosV, false) && cosV * l.z < 0)) return false;
    } else {
        l = reflect(v, m);
        if (!(macMicCompatible(m, v, l, cosV, true) && cosV * l.z > 0)) return false;
    }
    pdf = principledPdf(b, v, l);
    if (!(pdf > 0)) return false;
    weight = principledEval(b, v, l) * (1 / pdf);
    return true;
}

}  // namespace caustica::bsdf_detail
