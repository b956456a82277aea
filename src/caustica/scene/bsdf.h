// bsdf.h — evaluation, pdf and sampling of the closed list of BSDFs (bsdf_data.h). Shared
// CPU/GPU kernel code with Mitsuba 3's semantics, so that caustica reproduces Mitsuba's images.
//
// Conventions: directions are unit vectors in world space; `wo` points from the surface towards
// the viewer (Mitsuba's si.wi), `wi` towards the light (Mitsuba's wo). The local frame is
// shadingFrame(si) (interaction.h: the shading normal and dp/du, as Mitsuba), mirrored for the
// back of a twosided BSDF and tilted by bumpmap/normalmap (resolve). Textured parameters are
// evaluated at si.uv before a BSDF is evaluated (applyBsdfTextures; texture.h). Light transport
// is in radiance mode (refraction scales by 1/η²).
#pragma once

#include <new>
#include <type_traits>

#include "caustica/scene/bsdf_composite.h"
#include "caustica/scene/bsdf_data.h"
#include "caustica/scene/bsdf_rough_dielectric.h"
#include "caustica/scene/bsdf_principled.h"
#include "caustica/scene/bsdf_rough_plastic.h"
#include "caustica/scene/fresnel.h"
#include "caustica/scene/interaction.h"
#include "caustica/scene/microfacet.h"
#include "caustica/scene/texture.h"
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

/// BsdfSample of code generic over the lane type F (util/lane.h).
template <class F>
using BsdfSampleOf = LaneOf<BsdfSample, F>;

namespace bsdf_detail {

/// The PrincipledParams field of a principled BsdfParam (Roughness ... Flatness).
CA_HD_INLINE Float* principledSlot(PrincipledParams& p, BsdfParam param) {
    switch (param) {
        case BsdfParam::Roughness: return &p.roughness;
        case BsdfParam::Anisotropic: return &p.anisotropic;
        case BsdfParam::Metallic: return &p.metallic;
        case BsdfParam::SpecTint: return &p.specTint;
        case BsdfParam::Sheen: return &p.sheen;
        case BsdfParam::SheenTint: return &p.sheenTint;
        case BsdfParam::Clearcoat: return &p.clearcoat;
        case BsdfParam::ClearcoatGloss: return &p.clearcoatGloss;
        case BsdfParam::SpecTrans: return &p.specTrans;
        default: return &p.flatness;  // BsdfParam::Flatness
    }
}

/// Room for a textured copy of a Bsdf, left uninitialised until applyBsdfTextures needs it.
/// (A default-constructed Bsdf per evaluation, 536 bytes with zeroed tables, cost about 5% of
/// the path tracer's time although most BSDFs have no textures.)
union BsdfScratch {
    CA_HD_INLINE BsdfScratch() {}
    Bsdf bsdf;
};

/// applyBsdfTextures for a BSDF with textures.
CA_HD_INLINE const Bsdf& texturedBsdfCopy(const Bsdf& b, const SurfaceInteraction& si, BsdfScratch& scratch) {
    Bsdf& storage = *new (&scratch.bsdf) Bsdf(b);
    for (uint32_t i = 0; i < b.numTextures && i < uint32_t(kMaxBsdfTextures); ++i) {
        const uint32_t tex = b.textures[i].texture;
        switch (b.textures[i].param) {
            case BsdfParam::Reflectance: storage.reflectance = evalTexture(si.textures, tex, si.uv); break;
            case BsdfParam::Diffuse: storage.diffuse = evalTexture(si.textures, tex, si.uv); break;
            case BsdfParam::Transmittance: storage.transmittance = evalTexture(si.textures, tex, si.uv); break;
            case BsdfParam::Alpha: storage.alphaU = storage.alphaV = evalTexture1(si.textures, tex, si.uv); break;
            case BsdfParam::AlphaU: storage.alphaU = evalTexture1(si.textures, tex, si.uv); break;
            case BsdfParam::AlphaV: storage.alphaV = evalTexture1(si.textures, tex, si.uv); break;
            case BsdfParam::Weight: storage.weight = evalTexture1(si.textures, tex, si.uv); break;
            case BsdfParam::Eta: storage.eta = evalTexture(si.textures, tex, si.uv); break;
            case BsdfParam::K: storage.k = evalTexture(si.textures, tex, si.uv); break;
            case BsdfParam::Roughness: case BsdfParam::Anisotropic: case BsdfParam::Metallic:
            case BsdfParam::SpecTint: case BsdfParam::Sheen: case BsdfParam::SheenTint:
            case BsdfParam::Clearcoat: case BsdfParam::ClearcoatGloss: case BsdfParam::SpecTrans:
            case BsdfParam::Flatness:
                *principledSlot(storage.principled, b.textures[i].param) =
                    evalTexture1(si.textures, tex, si.uv);
                break;
        }
    }
    return storage;
}

/// `b` with its textured parameters (Bsdf::textures) replaced by the textures' values at si.uv:
/// `b` itself when it has none (inlined: most BSDFs), else a copy in `scratch`.
CA_HD_FORCE_INLINE const Bsdf& applyBsdfTextures(const Bsdf& b, const SurfaceInteraction& si,
                                                 BsdfScratch& scratch) {
    return b.numTextures == 0 ? b : texturedBsdfCopy(b, si, scratch);
}

/// The frame of a bumpmap or normalmap `b` nested in a frame `outer` (world axes, z possibly
/// mirrored by a twosided), as Mitsuba 3.9's PerturbedBSDF::frames (perturbed_bsdf.h). The
/// perturbed normal n is computed in the coordinates of the unperturbed shading frame: bumpmap:
/// dp/du' × dp/dv' with dp/du' = dp/du + n_s (scale ∂h/∂u − n_s·dp/du), turned towards the
/// geometric normal; normalmap: 2 rgb − 1. With flip_invalid_normals, n is mirrored about the
/// local z axis when the viewing direction wo is not on its side (Schüssler et al. 2017). Then
/// s = normalize((1, 0, 0) − n n_x), t = n × s, applied to `outer`'s axes.
CA_HD_INLINE Frame perturbedFrame(const Bsdf& b, const SurfaceInteraction& si, const Frame& outer,
                                  Vec3f wo) {
    Vec3f n;
    if (b.type == BsdfType::BumpMap) {
        const Vec2f grad = evalTextureGrad(si.textures, b.frameTexture, si.uv) * b.bumpScale;
        const Vec3f ns = si.ns;
        const Vec3f dpdu = si.dpdu + ns * (grad.x - dot(ns, si.dpdu));
        const Vec3f dpdv = si.dpdv + ns * (grad.y - dot(ns, si.dpdv));
        Vec3f cr = cross(dpdu, dpdv);
        if (dot(si.ng, cr) < 0) cr = -cr;
        n = shadingFrame(si).toLocal(cr);
    } else {
        const Spectrum c = evalTexture(si.textures, b.frameTexture, si.uv);
        n = Vec3f(2 * c.r - 1, 2 * c.g - 1, 2 * c.b - 1);
    }
    if (b.flipInvalidNormals) {
        const Vec3f woL = outer.toLocal(wo);
        if (woL.z * dot(woL, n) <= 0) n = Vec3f(-n.x, -n.y, n.z);
    }
    const Float len2 = lengthSquared(n);
    n = len2 > 0 && len2 < kInfinity ? n * (1 / std::sqrt(len2)) : Vec3f(0, 0, 1);
    Frame local;
    local.n = n;
    const Vec3f s = Vec3f(1, 0, 0) - n * n.x;
    const Float s2 = lengthSquared(s);
    local.s = s2 > 0 ? s * (1 / std::sqrt(s2)) : Vec3f(0, 1, 0);
    local.t = cross(local.n, local.s);
    Frame world;  // the local frame's axes in world space, through `outer`
    world.s = outer.toWorld(local.s);
    world.t = outer.toWorld(local.t);
    world.n = outer.toWorld(local.n);
    return world;
}

/// The concrete BSDF that applies at `si` for the viewing direction `wo` and the frame of its
/// local directions: Mitsuba's twosided (the back child sees directions mirrored: local z
/// negated) and bumpmap / normalmap (a perturbed frame) resolved. `outer` is the frame a
/// bumpmap/normalmap received: Mitsuba zeroes directions on different sides of it and of the
/// perturbed frame (the loader allows one bumpmap/normalmap and one twosided per chain).
struct Resolved {
    const Bsdf* bsdf;
    Frame frame;
    Frame outer;
    bool perturbed = false;
    bool shadowing = false;  // use_shadowing_function of the bumpmap/normalmap
};

/// `flip`: `id` lies under the back of a twosided resolved by bsdf_composite.h (normal negated).
CA_HD_INLINE Resolved resolve(Span<const Bsdf> bsdfs, uint32_t id, const SurfaceInteraction& si,
                              Vec3f wo, bool flip = false) {
    Resolved r{&bsdfs[id], shadingFrame(si), {}, false};
    if (flip) r.frame.n = -r.frame.n;
    for (int depth = 0; depth < 3; ++depth) {
        const Bsdf& b = *r.bsdf;
        if (b.type == BsdfType::TwoSided) {
            // Mitsuba's twosided: the front child when cosθo >= 0, else the back child mirrored.
            if (dot(wo, r.frame.n) < 0) {
                r.frame.n = -r.frame.n;
                r.bsdf = &bsdfs[b.back];
            } else {
                r.bsdf = &bsdfs[b.front];
            }
        } else if (b.type == BsdfType::BumpMap || b.type == BsdfType::NormalMap) {
            r.outer = r.frame;
            r.perturbed = true;
            r.shadowing = b.shadowTerminator;
            r.frame = perturbedFrame(b, si, r.outer, wo);
            r.bsdf = &bsdfs[b.front];
        } else {
            break;
        }
    }
    return r;
}

/// Mitsuba's bumpmap/normalmap side test: `w` must lie on the same side of both frames.
CA_HD_INLINE bool sameSide(const Resolved& r, Vec3f w) {
    return !r.perturbed || dot(w, r.outer.n) * dot(w, r.frame.n) > 0;
}

/// Mitsuba's shadowing term for bump and normal maps (eval_shadow_terminator; Estevez et al.,
/// "A Microfacet-Based Shadowing Function to Solve the Bump Terminator Problem", Ray Tracing
/// Gems 2019): α² = min(tan²θ_n / 8, 1) of the perturbed normal, G1 = 2 / (1 + sqrt(1 + α²
/// tan²θ_wi)), angles to the unperturbed normal. 1 without a perturbation. Multiplies f and the
/// sampled weight, not the pdf.
CA_HD_INLINE Float shadowTerminator(const Resolved& r, Vec3f wi) {
    if (!r.perturbed || !r.shadowing) return 1;
    auto tan2 = [](Float z) { return max(1 - z * z, Float(0)) / (z * z); };
    const Float alpha2 = min(Float(0.125) * tan2(dot(r.frame.n, r.outer.n)), Float(1));
    return 2 / (1 + std::sqrt(1 + alpha2 * tan2(dot(wi, r.outer.n))));
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

/// The diffuse BSDF in its local frame, generic over the lane type F (util/lane.h): f · cosθi =
/// R cosθi / π where both directions are above the surface (zero elsewhere, NaN included), its
/// pdf, and a cosine-weighted sample (valid where wo is above and the pdf positive; its weight is
/// R).
template <class F>
CA_HD_FORCE_INLINE MaskOf<F> diffuseBothAbove(const Vec3Of<F>& wo, const Vec3Of<F>& wi) {
    const MaskOf<F> woAbove = !(wo.z <= 0), wiAbove = !(wi.z <= 0);  // NaN: not above
    return woAbove & wiAbove;
}
template <class F>
CA_HD_INLINE SpectrumOf<F> diffuseEvalLocal(const SpectrumOf<F>& reflectance, const Vec3Of<F>& wo,
                                            const Vec3Of<F>& wi) {
    const F zero = lane::splat<F>(0);
    return lane::select<F>(diffuseBothAbove<F>(wo, wi), reflectance * (kInvPi * wi.z), SpectrumOf<F>{zero, zero, zero});
}
template <class F>
CA_HD_INLINE F diffusePdfLocal(const Vec3Of<F>& wo, const Vec3Of<F>& wi) {
    return lane::select(diffuseBothAbove<F>(wo, wi), cosineHemispherePdf<F>(wi), lane::splat<F>(0));
}
template <class F>
CA_HD_INLINE MaskOf<F> diffuseSampleLocal(const Vec3Of<F>& wo, const Vec2Of<F>& u, Vec3Of<F>& wi, F& pdf) {
    wi = sampleCosineHemisphere<F>(u);
    pdf = cosineHemispherePdf<F>(wi);
    const MaskOf<F> woAbove = !(wo.z <= 0);
    return woAbove & (pdf > 0);
}

/// f · cosθi of a non-twosided BSDF in its local frame; zero for delta lobes.
CA_HD_INLINE Spectrum evalLocal(const Bsdf& b, Vec3f wo, Vec3f wi) {
    switch (b.type) {
        case BsdfType::Diffuse:
            return diffuseEvalLocal<float>(b.reflectance, wo, wi);
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
        case BsdfType::RoughPlastic:
            return roughPlasticEval(b, wo, wi);
        case BsdfType::Principled:
            return principledEval(b, wo, wi);
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
            return diffusePdfLocal<float>(wo, wi);
        case BsdfType::RoughConductor:
            if (wo.z <= 0 || wi.z <= 0) return 0;
            return roughConductorPdf(microfacetOf(b), wo, wi, normalize(wo + wi));
        case BsdfType::RoughDielectric:
            return roughDielectricPdf(b, wo, wi);
        case BsdfType::RoughPlastic:
            return roughPlasticPdf(b, wo, wi);
        case BsdfType::Principled:
            return principledPdf(b, wo, wi);
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
            out.weight = b.reflectance;  // (R/π) cosθ / (cosθ/π)
            return diffuseSampleLocal<float>(wo, u, out.wi, out.pdf);
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
        case BsdfType::RoughPlastic:
            return roughPlasticSample(b, wo, uLobe, u, out.wi, out.weight, out.pdf);
        case BsdfType::Principled:
            return principledSample(b, wo, uLobe, u, out.wi, out.weight, out.pdf, out.eta);
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
            return false;  // composites: bsdf_composite.h
    }
}

CA_HD_INLINE bool isDeltaLocal(const Bsdf& b) {
    return b.type == BsdfType::Dielectric || b.type == BsdfType::Conductor ||
           b.type == BsdfType::ThinDielectric;
}

/// Whether leaf `id` (bumpmap/normalmap and twosided looked through) has no smooth part.
CA_HD_INLINE bool leafIsDelta(Span<const Bsdf> bsdfs, uint32_t id) {
    if (bsdfs[id].type == BsdfType::BumpMap || bsdfs[id].type == BsdfType::NormalMap)
        id = bsdfs[id].front;  // a perturbed frame changes no lobe
    const Bsdf& b = bsdfs[id];
    if (b.type == BsdfType::TwoSided)
        return isDeltaLocal(bsdfs[b.front]) && isDeltaLocal(bsdfs[b.back]);
    return isDeltaLocal(b);
}

/// A leaf BSDF prepared for queries from one viewing direction: resolved (twosided, bump or
/// normal map), textured, and wo turned into its local frame, the steps every query of it starts
/// with. Not copyable: the textured BSDF may live in its own scratch.
class PreparedLeaf {
public:
    // Members built in place, not default-initialised first: a zeroed Resolved (88 bytes, a
    // `rep stos`) cost about 1% of a shading-bound render.
    CA_HD_INLINE PreparedLeaf(Span<const Bsdf> bsdfs, uint32_t id, const SurfaceInteraction& si,
                              Vec3f wo, bool flip)
        : resolved_(resolve(bsdfs, id, si, wo, flip)),
          bsdf_(&applyBsdfTextures(*resolved_.bsdf, si, scratch_)),
          woLocal_(resolved_.frame.toLocal(wo)) {}
    PreparedLeaf(const PreparedLeaf&) = delete;
    PreparedLeaf& operator=(const PreparedLeaf&) = delete;

    /// f(wo, wi) · |cosθi|, wi in world space.
    CA_HD_INLINE Spectrum eval(Vec3f wi) const {
        if (!sameSide(resolved_, wi)) return {};
        return evalLocal(*bsdf_, woLocal_, resolved_.frame.toLocal(wi)) * shadowTerminator(resolved_, wi);
    }

    CA_HD_INLINE Float pdf(Vec3f wi) const {
        if (!sameSide(resolved_, wi)) return 0;
        return pdfLocal(*bsdf_, woLocal_, resolved_.frame.toLocal(wi));
    }

    /// eval (returned) and pdf (`pdf`) of a tree of this one leaf: each summed as the tree walk
    /// sums its leaves (from zero, weight 1), so the bits are evalBsdf's and pdfBsdf's.
    CA_HD_INLINE Spectrum evalPdfAlone(Vec3f wi, Float& pdf) const {
        Spectrum f;
        Float p = 0;
        if (sameSide(resolved_, wi)) {
            const Vec3f wiLocal = resolved_.frame.toLocal(wi);
            f += evalLocal(*bsdf_, woLocal_, wiLocal) * shadowTerminator(resolved_, wi) * Float(1);
            p += pdfLocal(*bsdf_, woLocal_, wiLocal) * Float(1);
        }  // else: zero, as the walk's sum of a zero
        pdf = p;
        return f;
    }

    /// A sampled direction, out.wi in world space.
    CA_HD_INLINE bool sample(Float uLobe, Vec2f u, BsdfSample& out) const {
        if (!sampleLocal(*bsdf_, woLocal_, uLobe, u, out)) return false;
        out.wi = resolved_.frame.toWorld(out.wi);
        out.weight = out.weight * shadowTerminator(resolved_, out.wi);
        return sameSide(resolved_, out.wi);
    }

    /// sample, then compositeSample's steps for a tree of this one leaf (no blend or mask to
    /// back up through), so the bits are sampleBsdf's.
    CA_HD_INLINE bool sampleAlone(Float uLobe, Vec2f u, BsdfSample& out) const {
        if (!sample(uLobe, u, out) || !(out.pdf > 0)) return false;
        const Spectrum value = out.weight * out.pdf;
        out.weight = value * (1 / out.pdf);
        return true;
    }

    /// The leaf resolved at the vertex (frame, perturbed, ...), its textured BSDF and wo in its
    /// local frame, for callers that take a shortcut through one kind of leaf (sppm's gather).
    CA_HD_INLINE const Resolved& resolved() const { return resolved_; }
    CA_HD_INLINE const Bsdf& bsdf() const { return *bsdf_; }
    CA_HD_INLINE Vec3f woLocal() const { return woLocal_; }

private:
    BsdfScratch scratch_;  // first: bsdf_ may point into it
    Resolved resolved_;
    const Bsdf* bsdf_;
    Vec3f woLocal_;
};

/// Room for a PreparedLeaf that is built (placement new) only when there is a plain leaf to
/// prepare: nothing is initialised otherwise. Never destroyed, which PreparedLeaf allows.
union PreparedLeafSlot {
    CA_HD_INLINE PreparedLeafSlot() {}
    PreparedLeaf leaf;
};
static_assert(std::is_trivially_destructible_v<PreparedLeaf>, "a PreparedLeafSlot is never destroyed");

/// The leaves of bsdf_composite.h's BSDF trees at `si` (everything but twosided, blendbsdf,
/// mask and null above them), in world space; `flip`: under the back of a twosided.
struct LeafOps {
    Span<const Bsdf> bsdfs;
    const SurfaceInteraction& si;

    CA_HD_INLINE Vec3f normal() const { return si.ns; }

    CA_HD_INLINE Spectrum eval(uint32_t id, bool flip, Vec3f wo, Vec3f wi) const {
        return PreparedLeaf(bsdfs, id, si, wo, flip).eval(wi);
    }

    CA_HD_INLINE Float pdf(uint32_t id, bool flip, Vec3f wo, Vec3f wi) const {
        return PreparedLeaf(bsdfs, id, si, wo, flip).pdf(wi);
    }

    CA_HD_INLINE bool sample(uint32_t id, bool flip, Vec3f wo, Float uLobe, Vec2f u,
                             BsdfSample& out) const {
        return PreparedLeaf(bsdfs, id, si, wo, flip).sample(uLobe, u, out);
    }

    CA_HD_INLINE bool isDelta(uint32_t id) const { return leafIsDelta(bsdfs, id); }

    /// blendbsdf weight / mask opacity (textured or not), clamped to [0, 1] as Mitsuba.
    CA_HD_INLINE Float weight(const Bsdf& b) const {
        BsdfScratch scratch;
        return clamp(applyBsdfTextures(b, si, scratch).weight, Float(0), Float(1));
    }
};

}  // namespace bsdf_detail

// The public entry points below walk the BSDF tree (bsdf_composite.h) only where they must
// (needsTreeWalk); a plain leaf (almost every BSDF of a scene: diffuse, dielectric, conductor,
// plastic, ... also under a bumpmap or normalmap, or a twosided over two such leaves, which the
// leaf resolves) goes straight to it. The leaf paths do the walk's floating-point operations on
// its one leaf of weight 1 (a sum that starts at zero, a product by one), so both give the same
// bits.

/// f(wo, wi) · |cosθi| of the non-delta part of BSDF `id` at `si` (world-space unit directions).
CA_HD_INLINE Spectrum evalBsdf(Span<const Bsdf> bsdfs, uint32_t id, const SurfaceInteraction& si,
                               Vec3f wo, Vec3f wi) {
    const bsdf_detail::LeafOps leaf{bsdfs, si};
    if (bsdf_detail::needsTreeWalk(bsdfs, id)) return bsdf_detail::compositeEval(bsdfs, leaf, id, wo, wi);
    Spectrum sum;
    sum += leaf.eval(id, false, wo, wi) * Float(1);
    return sum;
}

/// Solid-angle pdf with which sampleBsdf draws `wi` from its non-delta part.
CA_HD_INLINE Float pdfBsdf(Span<const Bsdf> bsdfs, uint32_t id, const SurfaceInteraction& si,
                           Vec3f wo, Vec3f wi) {
    const bsdf_detail::LeafOps leaf{bsdfs, si};
    if (bsdf_detail::needsTreeWalk(bsdfs, id)) return bsdf_detail::compositePdf(bsdfs, leaf, id, wo, wi);
    Float sum = 0;
    sum += leaf.pdf(id, false, wo, wi) * Float(1);
    return sum;
}

/// evalBsdf (returned) and pdfBsdf (`pdf`) of the same directions, the values of the two calls
/// bit for bit; a plain leaf is resolved, textured and turned into its local frame once for both
/// (next-event estimation wants both at every vertex).
CA_HD_INLINE Spectrum evalPdfBsdf(Span<const Bsdf> bsdfs, uint32_t id, const SurfaceInteraction& si,
                                  Vec3f wo, Vec3f wi, Float& pdf) {
    using namespace bsdf_detail;
    if (needsTreeWalk(bsdfs, id)) {
        pdf = pdfBsdf(bsdfs, id, si, wo, wi);
        return evalBsdf(bsdfs, id, si, wo, wi);
    }
    return PreparedLeaf(bsdfs, id, si, wo, false).evalPdfAlone(wi, pdf);
}

/// Samples an incident direction. `uLobe` chooses between lobes (dielectric reflection or
/// refraction, blendbsdf and mask children), `u` the direction within one. Returns false when
/// absorbed / no sample.
CA_HD_INLINE bool sampleBsdf(Span<const Bsdf> bsdfs, uint32_t id, const SurfaceInteraction& si,
                             Vec3f wo, Float uLobe, Vec2f u, BsdfSample& out) {
    const bsdf_detail::LeafOps leaf{bsdfs, si};
    if (bsdf_detail::needsTreeWalk(bsdfs, id))
        return bsdf_detail::compositeSample(bsdfs, leaf, id, wo, uLobe, u, out);
    return bsdf_detail::PreparedLeaf(bsdfs, id, si, wo, false).sampleAlone(uLobe, u, out);
}

/// BSDF `id` at `si` seen from `wo`, prepared once for the two queries a path vertex makes:
/// next-event estimation's evalPdf and the sample that continues the path. A plain leaf (or a
/// twosided over two, needsTreeWalk) is resolved (resolve), textured and given wo in its local
/// frame here, once instead of in each query; other composites walk their tree per query. Each
/// query returns evalPdfBsdf's / sampleBsdf's values bit for bit (the same operations on the same
/// operands). Not copyable: the textured BSDF may live in its own scratch.
class BsdfAtVertex {
public:
    CA_HD_INLINE BsdfAtVertex(Span<const Bsdf> bsdfs, uint32_t id, const SurfaceInteraction& si, Vec3f wo)
        : bsdfs_(bsdfs), si_(si), id_(id), wo_(wo), composite_(bsdf_detail::needsTreeWalk(bsdfs, id)) {
        if (!composite_) new (&slot_.leaf) bsdf_detail::PreparedLeaf(bsdfs, id, si, wo, false);
    }
    BsdfAtVertex(const BsdfAtVertex&) = delete;
    BsdfAtVertex& operator=(const BsdfAtVertex&) = delete;

    /// evalPdfBsdf(bsdfs, id, si, wo, wi, pdf).
    CA_HD_INLINE Spectrum evalPdf(Vec3f wi, Float& pdf) const {
        if (composite_) return evalPdfBsdf(bsdfs_, id_, si_, wo_, wi, pdf);
        return slot_.leaf.evalPdfAlone(wi, pdf);
    }

    /// sampleBsdf(bsdfs, id, si, wo, uLobe, u, out).
    CA_HD_INLINE bool sample(Float uLobe, Vec2f u, BsdfSample& out) const {
        if (composite_) return sampleBsdf(bsdfs_, id_, si_, wo_, uLobe, u, out);
        return slot_.leaf.sampleAlone(uLobe, u, out);
    }

private:
    Span<const Bsdf> bsdfs_;
    const SurfaceInteraction& si_;
    uint32_t id_;
    Vec3f wo_;
    bool composite_;
    bsdf_detail::PreparedLeafSlot slot_;  // a plain leaf's, built only for one
};

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
    if (!bsdf_detail::isComposite(bsdfs[id].type)) return bsdf_detail::leafIsDelta(bsdfs, id);
    const SurfaceInteraction si{};
    return bsdf_detail::compositeIsDelta(bsdfs, bsdf_detail::LeafOps{bsdfs, si}, id);
}

namespace bsdf_detail {
/// A leaf that photon mapping treats as a mirror: delta, or a microfacet interface (rough
/// conductor or dielectric) whose larger untextured roughness alpha is below `threshold`.
CA_HD_INLINE bool isSpecularLocal(const Bsdf& b, Float threshold) {
    if (isDeltaLocal(b)) return true;
    const bool microfacet = b.type == BsdfType::RoughConductor || b.type == BsdfType::RoughDielectric;
    return microfacet && max(b.alphaU, b.alphaV) < threshold;
}
/// isSpecularLocal through the wrappers LeafOps::isDelta looks through (bump/normal map, twosided).
CA_HD_INLINE bool isSpecularLeaf(Span<const Bsdf> bsdfs, uint32_t id, Float threshold) {
    if (bsdfs[id].type == BsdfType::BumpMap || bsdfs[id].type == BsdfType::NormalMap) id = bsdfs[id].front;
    const Bsdf& b = bsdfs[id];
    if (b.type == BsdfType::TwoSided)
        return isSpecularLocal(bsdfs[b.front], threshold) && isSpecularLocal(bsdfs[b.back], threshold);
    return isSpecularLocal(b, threshold);
}
}  // namespace bsdf_detail

/// Photon mapping's "specular" vertex (no visible point, no photon deposit; paths go on by
/// sampling the BSDF): every lobe delta or a microfacet lobe with roughness alpha < threshold.
/// threshold 0: the delta BSDFs exactly (isDeltaBsdf).
CA_HD_INLINE bool isSpecularBsdf(Span<const Bsdf> bsdfs, uint32_t id, Float threshold) {
    if (!(threshold > 0)) return isDeltaBsdf(bsdfs, id);
    if (!bsdf_detail::isComposite(bsdfs[id].type)) return bsdf_detail::isSpecularLeaf(bsdfs, id, threshold);
    const SurfaceInteraction si{};
    const bsdf_detail::LeafOps leaf{bsdfs, si};
    bool specular = true;
    bsdf_detail::forEachLeaf<true>(bsdfs, leaf, id, false, leaf.normal(), [&](uint32_t l, Float, bool) {
        specular = specular && bsdf_detail::isSpecularLeaf(bsdfs, l, threshold);
    });
    return specular;
}

}  // namespace caustica
