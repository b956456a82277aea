// bsdf.h — evaluation, pdf and sampling of the closed list of BSDFs (bsdf_data.h). Shared
// CPU/GPU kernel code with Mitsuba 3's semantics, so that caustica reproduces Mitsuba's images.
//
// Conventions: directions are unit vectors in world space; `wo` points from the surface towards
// the viewer (Mitsuba's si.wi), `wi` towards the light (Mitsuba's wo). The local frame is built
// from the shading normal si.ns. Light transport is in radiance mode (refraction scales by 1/η²).
#pragma once

#include "caustica/scene/bsdf_data.h"
#include "caustica/scene/bsdf_rough_dielectric.h"
#include "caustica/scene/fresnel.h"
#include "caustica/scene/interaction.h"
#include "caustica/scene/microfacet.h"
#include "caustica/util/sampling.h"
#include "caustica/util/span.h"

namespace caustica {

/// One sampled direction of a BSDF.
struct BsdfSample {
    Vec3f wi;         // sampled direction, world space, unit
    Spectrum weight;  // f · |cosθi| / pdf
    Float pdf = 0;    // solid-angle pdf; for a delta lobe the discrete probability of choosing it
    Float eta = 1;    // relative IOR η_t/η_i of the crossed interface, 1 for reflection
    bool delta = false;
};

namespace bsdf_detail {

/// A BSDF after resolving `twosided`: the child that applies and whether the local directions
/// must be mirrored to its front side (local z negated).
struct Resolved {
    const Bsdf* bsdf;
    bool flip;
};

/// Mitsuba's twosided: the front child when cosθo >= 0, else the back child seen mirrored.
CA_HD_INLINE Resolved resolve(Span<const Bsdf> bsdfs, uint32_t id, Float cosThetaO) {
    const Bsdf& b = bsdfs[id];
    if (b.type != BsdfType::TwoSided) return {&b, false};
    if (cosThetaO < 0) return {&bsdfs[b.back], true};
    return {&bsdfs[b.front], false};
}

CA_HD_INLINE Vec3f flipZ(Vec3f v) { return {v.x, v.y, -v.z}; }

CA_HD_INLINE MicrofacetDistribution microfacetOf(const Bsdf& b) {
    return {b.distribution, b.alphaU, b.alphaV};
}

/// Solid-angle pdf of sampling `wi` from `wo` by visible normals, via the half vector
/// (Walter et al. 2007, eq. 14: the Jacobian of reflection is 1/(4 |wi·m|)).
CA_HD_INLINE Float roughConductorPdf(const MicrofacetDistribution& md, Vec3f wo, Vec3f wi,
                                     Vec3f m) {
    if (dot(wo, m) <= 0 || dot(wi, m) <= 0) return 0;
    return md.D(m) * md.G1(wo, m) / (4 * wo.z);  // D_wo(m) / (4 wo·m)
}

/// Mitsuba's plastic: probability of choosing the specular lobe for Fresnel reflectance fo of
/// the viewing direction.
CA_HD_INLINE Float plasticSpecularProb(const Bsdf& b, Float fo) {
    const Float ps = fo * b.specularWeight, pd = (1 - fo) * (1 - b.specularWeight);
    return ps + pd > 0 ? ps / (ps + pd) : b.specularWeight;
}

/// Mitsuba's plastic diffuse lobe, f · cosθi / (cosθi/π): the base's reflectance corrected for
/// internal reflections at the coating, times the two Fresnel transmissions and 1/η² (radiance
/// crossing the coating twice).
CA_HD_INLINE Spectrum plasticDiffuse(const Bsdf& b, Float fo, Float fi) {
    Spectrum d = b.diffuse;
    for (int c = 0; c < 3; ++c) d[c] /= 1 - (b.nonlinear ? d[c] * b.fdrInt : b.fdrInt);
    return d * ((1 - fo) * (1 - fi) / sqr(b.etaRatio));
}

/// f · cosθi of a non-twosided BSDF in its local frame; zero for delta lobes.
CA_HD_INLINE Spectrum evalLocal(const Bsdf& b, Vec3f wo, Vec3f wi) {
    switch (b.type) {
        case BsdfType::Diffuse:
            if (wo.z <= 0 || wi.z <= 0) return {};
            return b.reflectance * (kInvPi * wi.z);
        case BsdfType::RoughConductor: {
            if (wo.z <= 0 || wi.z <= 0) return {};
            const MicrofacetDistribution md = microfacetOf(b);
            const Vec3f h = normalize(wo + wi);
            const Float d = md.D(h);
            if (d == 0) return {};
            // Cook–Torrance: f = F D G / (4 cosθo cosθi) (Walter et al. 2007, eq. 20).
            const Float dg = d * md.G(wo, wi, h) / (4 * wo.z);
            return b.reflectance * fresnelConductor(dot(wo, h), b.eta, b.k) * dg;
        }
        case BsdfType::RoughDielectric:
            return roughDielectricEval(b, wo, wi);
        case BsdfType::Plastic: {
            if (wo.z <= 0 || wi.z <= 0) return {};
            const Float fo = fresnelDielectric(wo.z, b.etaRatio).r;
            const Float fi = fresnelDielectric(wi.z, b.etaRatio).r;
            return plasticDiffuse(b, fo, fi) * (kInvPi * wi.z);
        }
        default:
            return {};  // Dielectric, Conductor: delta only
    }
}

/// Solid-angle pdf of sampling `wi` of a non-twosided BSDF in its local frame.
CA_HD_INLINE Float pdfLocal(const Bsdf& b, Vec3f wo, Vec3f wi) {
    switch (b.type) {
        case BsdfType::Diffuse:
            if (wo.z <= 0 || wi.z <= 0) return 0;
            return cosineHemispherePdf(wi);
        case BsdfType::RoughConductor:
            if (wo.z <= 0 || wi.z <= 0) return 0;
            return roughConductorPdf(microfacetOf(b), wo, wi, normalize(wo + wi));
        case BsdfType::RoughDielectric:
            return roughDielectricPdf(b, wo, wi);
        case BsdfType::Plastic: {
            if (wo.z <= 0 || wi.z <= 0) return 0;
            const Float fo = fresnelDielectric(wo.z, b.etaRatio).r;
            return (1 - plasticSpecularProb(b, fo)) * cosineHemispherePdf(wi);
        }
        default:
            return 0;
    }
}

/// Samples a non-twosided BSDF in its local frame; out.wi is local.
CA_HD_INLINE bool sampleLocal(const Bsdf& b, Vec3f wo, Float uLobe, Vec2f u, BsdfSample& out) {
    out.eta = 1;
    out.delta = false;
    switch (b.type) {
        case BsdfType::Diffuse: {
            if (wo.z <= 0) return false;
            out.wi = sampleCosineHemisphere(u);
            out.pdf = cosineHemispherePdf(out.wi);
            out.weight = b.reflectance;  // (R/π) cosθ / (cosθ/π)
            return out.pdf > 0;
        }
        case BsdfType::Dielectric: {
            // Mitsuba's smooth dielectric: choose reflection with probability F.
            const FresnelDielectric f = fresnelDielectric(wo.z, b.etaRatio);
            out.delta = true;
            if (uLobe < f.r) {
                out.wi = reflectLocal(wo);
                out.pdf = f.r;
                out.weight = b.reflectance;  // F R / F
            } else {
                out.wi = refractLocal(wo, f.cosThetaT, f.etaTI);
                out.pdf = 1 - f.r;
                out.eta = f.etaIT;
                // Radiance is compressed by (η_i/η_t)² crossing the interface (Veach 1997, 5.2).
                out.weight = b.transmittance * sqr(f.etaTI);  // (1 - F) T / η'² / (1 - F)
            }
            return out.pdf > 0;
        }
        case BsdfType::Conductor: {
            if (wo.z <= 0) return false;
            out.wi = reflectLocal(wo);
            out.pdf = 1;
            out.delta = true;
            out.weight = b.reflectance * fresnelConductor(wo.z, b.eta, b.k);
            return true;
        }
        case BsdfType::RoughConductor: {
            if (wo.z <= 0) return false;
            const MicrofacetDistribution md = microfacetOf(b);
            const Vec3f m = md.sampleVisible(wo, u);
            out.wi = reflect(wo, m);
            if (out.wi.z <= 0) return false;
            out.pdf = roughConductorPdf(md, wo, out.wi, m);
            if (!(out.pdf > 0)) return false;
            // f cosθi / pdf = F D G / (4 cosθo) / (D G1(wo) / (4 cosθo)) = F G1(wi)
            const Spectrum f = fresnelConductor(dot(wo, m), b.eta, b.k);
            out.weight = b.reflectance * f * md.G1(out.wi, m);
            return true;
        }
        case BsdfType::RoughDielectric:
            return roughDielectricSample(b, wo, uLobe, u, out.wi, out.weight, out.pdf, out.eta);
        case BsdfType::ThinDielectric: {
            // Mitsuba's thindielectric: a pane whose two interfaces reflect R = F + T²F/(1 - F²)
            // in total, R = 2F / (1 + F) (the internal reflections summed); the rest passes
            // straight through (no refraction: the pane is thin). Works from both sides.
            const Float f = fresnelDielectric(std::fabs(wo.z), b.etaRatio).r;
            const Float r = f * 2 / (1 + f);
            out.delta = true;
            if (uLobe <= r) {
                out.wi = reflectLocal(wo);
                out.pdf = r;
                out.weight = b.reflectance;
            } else {
                out.wi = -wo;
                out.pdf = 1 - r;
                out.weight = b.transmittance;
            }
            return out.pdf > 0;
        }
        case BsdfType::Plastic: {
            // Mitsuba's plastic: the specular lobe with probability ∝ F(wo) · specularWeight.
            if (wo.z <= 0) return false;
            const Float fo = fresnelDielectric(wo.z, b.etaRatio).r;
            const Float pSpec = plasticSpecularProb(b, fo);
            if (uLobe < pSpec) {
                out.wi = reflectLocal(wo);
                out.pdf = pSpec;
                out.delta = true;
                out.weight = b.reflectance * (fo / pSpec);
                return pSpec > 0;
            }
            out.wi = sampleCosineHemisphere(u);
            out.pdf = (1 - pSpec) * cosineHemispherePdf(out.wi);
            if (!(out.pdf > 0) || out.wi.z <= 0) return false;
            const Float fi = fresnelDielectric(out.wi.z, b.etaRatio).r;
            out.weight = plasticDiffuse(b, fo, fi) * (1 / (1 - pSpec));
            return true;
        }
        default:
            return false;  // nested TwoSided: invalid
    }
}

CA_HD_INLINE bool isDeltaLocal(const Bsdf& b) {
    return b.type == BsdfType::Dielectric || b.type == BsdfType::Conductor ||
           b.type == BsdfType::ThinDielectric;
}

/// A direction pair in the shading frame, mirrored to the front for the back of a twosided BSDF,
/// with the concrete (non-twosided) BSDF that applies.
struct LocalPair {
    const Bsdf* bsdf;
    Vec3f wo, wi;
};

CA_HD_INLINE LocalPair resolvePair(Span<const Bsdf> bsdfs, uint32_t id, const SurfaceInteraction& si,
                                   Vec3f wo, Vec3f wi) {
    const Frame frame(si.ns);
    Vec3f woL = frame.toLocal(wo), wiL = frame.toLocal(wi);
    const Resolved r = resolve(bsdfs, id, woL.z);
    if (r.flip) {
        woL = flipZ(woL);
        wiL = flipZ(wiL);
    }
    return {r.bsdf, woL, wiL};
}

}  // namespace bsdf_detail

/// f(wo, wi) · |cosθi| of the non-delta part of BSDF `id` at `si` (world-space unit directions).
CA_HD_INLINE Spectrum evalBsdf(Span<const Bsdf> bsdfs, uint32_t id, const SurfaceInteraction& si,
                               Vec3f wo, Vec3f wi) {
    const bsdf_detail::LocalPair p = bsdf_detail::resolvePair(bsdfs, id, si, wo, wi);
    return bsdf_detail::evalLocal(*p.bsdf, p.wo, p.wi);
}

/// Solid-angle pdf with which sampleBsdf draws `wi` from its non-delta part.
CA_HD_INLINE Float pdfBsdf(Span<const Bsdf> bsdfs, uint32_t id, const SurfaceInteraction& si,
                           Vec3f wo, Vec3f wi) {
    const bsdf_detail::LocalPair p = bsdf_detail::resolvePair(bsdfs, id, si, wo, wi);
    return bsdf_detail::pdfLocal(*p.bsdf, p.wo, p.wi);
}

/// Samples an incident direction. `uLobe` chooses between lobes (dielectric reflection or
/// refraction), `u` the direction within one. Returns false when absorbed / no sample.
CA_HD_INLINE bool sampleBsdf(Span<const Bsdf> bsdfs, uint32_t id, const SurfaceInteraction& si,
                             Vec3f wo, Float uLobe, Vec2f u, BsdfSample& out) {
    const Frame frame(si.ns);
    Vec3f woL = frame.toLocal(wo);
    const bsdf_detail::Resolved r = bsdf_detail::resolve(bsdfs, id, woL.z);
    if (r.flip) woL = bsdf_detail::flipZ(woL);
    if (!bsdf_detail::sampleLocal(*r.bsdf, woL, uLobe, u, out)) return false;
    if (r.flip) out.wi = bsdf_detail::flipZ(out.wi);
    out.wi = frame.toWorld(out.wi);
    return true;
}

/// Mitsuba's diffuse Fresnel reflectance (fresnel_diffuse_reflectance): the fraction of a
/// uniform (cosine-weighted) radiance distribution reflected by a smooth interface of relative
/// IOR eta, by the fits of Egan and Hilgeman 1973 (eta < 1) and d'Eon and Irving 2011.
CA_HD_INLINE Float fresnelDiffuseReflectance(Float eta) {
    if (eta < 1) {
        const Float invEta = 1 / eta;
        return Float(0.0636) * invEta + eta * (eta * Float(-1.4399) + Float(0.7099)) +
               Float(0.6681);
    }
    const Float x = 1 / eta;  // Horner in 1/eta
    return Float(0.919317) +
           x * (Float(-3.4793) +
                x * (Float(6.75335) +
                     x * (Float(-7.80989) + x * (Float(4.98554) + x * Float(-1.36881)))));
}

/// A plastic record with Mitsuba's precomputed terms: the coating's internal diffuse Fresnel
/// reflectance and the specular sampling weight mean(specular) / (mean(diffuse) + mean(specular)).
CA_HD_INLINE Bsdf makePlastic(Float etaRatio, Spectrum diffuse, Spectrum specular,
                              bool nonlinear) {
    Bsdf b;
    b.type = BsdfType::Plastic;
    b.etaRatio = etaRatio;
    b.diffuse = diffuse;
    b.reflectance = specular;
    b.nonlinear = nonlinear;
    b.fdrInt = fresnelDiffuseReflectance(1 / etaRatio);
    const Float dMean = (diffuse.r + diffuse.g + diffuse.b) / 3;
    const Float sMean = (specular.r + specular.g + specular.b) / 3;
    b.specularWeight = dMean + sMean > 0 ? sMean / (dMean + sMean) : Float(0.5);
    return b;
}

/// True when the BSDF has no non-delta component (next-event estimation is pointless).
CA_HD_INLINE bool isDeltaBsdf(Span<const Bsdf> bsdfs, uint32_t id) {
    const Bsdf& b = bsdfs[id];
    if (b.type == BsdfType::TwoSided)
        return bsdf_detail::isDeltaLocal(bsdfs[b.front]) &&
               bsdf_detail::isDeltaLocal(bsdfs[b.back]);
    return bsdf_detail::isDeltaLocal(b);
}

}  // namespace caustica
