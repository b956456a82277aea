// bsdf_rough_plastic.h — Mitsuba 3's roughplastic: a diffuse base under a rough (Beckmann or GGX)
// dielectric coating. The glossy lobe is the coating's microfacet reflection (Cook–Torrance with
// the dielectric Fresnel term); the diffuse lobe is the base seen through the coating, weighted
// by the coating's external transmittance t(cosθ) at both directions (a table over cosθ, linearly
// interpolated, as Mitsuba's lerp_gather) and corrected for internal reflections with the
// coating's internal diffuse reflectance. Both are Mitsuba's precomputation
// (roughplastic.cpp, parameters_changed; microfacet.h, eval_reflectance / eval_transmittance):
// a Gauss–Legendre quadrature over the visible-normal sampler's unit square.
// Local frame, `wo` towards the viewer, `wi` towards the light (Mitsuba's si.wi and wo);
// one-sided, isotropic roughness only (as Mitsuba).
#pragma once

#include <cmath>
#include <vector>

#include "caustica/scene/bsdf_data.h"
#include "caustica/scene/bsdf_rough_dielectric.h"
#include "caustica/scene/fresnel.h"
#include "caustica/scene/microfacet.h"
#include "caustica/util/sampling.h"

namespace caustica {

namespace bsdf_detail {

/// t(cosθ) from the table (Mitsuba's lerp_gather: index = min(⌊63 x⌋, 62), linear in between).
CA_HD_INLINE Float roughPlasticTransmittance(const Bsdf& b, Float cosTheta) {
    const Float x = cosTheta * Float(kRoughPlasticTableSize - 1);
    const int i = min(int(x), kRoughPlasticTableSize - 2);
    const Float t = x - Float(i);
    return (1 - t) * b.roughTransmittance[i] + t * b.roughTransmittance[i + 1];
}

/// Probability of sampling the glossy lobe for viewing cosine cosThetaO (Mitsuba's
/// prob_specular: (1 - t_o) · specularWeight against t_o · (1 - specularWeight)).
CA_HD_INLINE Float roughPlasticSpecularProb(const Bsdf& b, Float cosThetaO) {
    const Float t = roughPlasticTransmittance(b, cosThetaO);
    const Float ps = (1 - t) * b.specularWeight, pd = t * (1 - b.specularWeight);
    return ps + pd > 0 ? ps / (ps + pd) : b.specularWeight;
}

/// f · cosθi (Mitsuba's eval): F D G / (4 cosθo) · specular + the diffuse base through the
/// coating, diffuse / (1 - R_int) · t(cosθo) t(cosθi) cosθi / (π η²).
CA_HD_INLINE Spectrum roughPlasticEval(const Bsdf& b, Vec3f wo, Vec3f wi) {
    if (wo.z <= 0 || wi.z <= 0) return {};
    const MicrofacetDistribution md(b.distribution, b.alphaU, b.alphaU);
    const Vec3f h = normalize(wo + wi);
    const Float f = fresnelDielectric(dot(wo, h), b.etaRatio).r;
    const Spectrum spec = b.reflectance * (f * md.D(h) * md.G(wo, wi, h) / (4 * wo.z));
    Spectrum d = b.diffuse;
    for (int c = 0; c < 3; ++c) d[c] /= 1 - (b.nonlinear ? d[c] * b.fdrInt : b.fdrInt);
    const Float to = roughPlasticTransmittance(b, wo.z), ti = roughPlasticTransmittance(b, wi.z);
    return spec + d * (kInvPi * wi.z * to * ti / sqr(b.etaRatio));
}

/// Mitsuba's pdf: the glossy lobe by visible normals, D(h) G1(wo, h) / (4 cosθo), and the cosine
/// hemisphere, mixed by roughPlasticSpecularProb.
CA_HD_INLINE Float roughPlasticPdf(const Bsdf& b, Vec3f wo, Vec3f wi) {
    if (wo.z <= 0 || wi.z <= 0) return 0;
    const MicrofacetDistribution md(b.distribution, b.alphaU, b.alphaU);
    const Vec3f h = normalize(wo + wi);
    const Float pSpec = roughPlasticSpecularProb(b, wo.z);
    return pSpec * md.D(h) * md.G1(wo, h) / (4 * wo.z) + (1 - pSpec) * cosineHemispherePdf(wi);
}

/// Mitsuba's sample: a visible normal's reflection with probability pSpec, else the cosine
/// hemisphere; the weight is eval / pdf of the whole BSDF.
CA_HD_INLINE bool roughPlasticSample(const Bsdf& b, Vec3f wo, Float uLobe, Vec2f u, Vec3f& wi,
                                     Spectrum& weight, Float& pdf) {
    if (wo.z <= 0) return false;
    if (uLobe < roughPlasticSpecularProb(b, wo.z)) {
        const MicrofacetDistribution md(b.distribution, b.alphaU, b.alphaU);
        wi = reflect(wo, md.sampleVisible(wo, u));
    } else {
        wi = sampleCosineHemisphere(u);
    }
    pdf = roughPlasticPdf(b, wo, wi);
    if (!(pdf > 0)) return false;
    weight = roughPlasticEval(b, wo, wi) * (1 / pdf);
    return true;
}

/// Gauss–Legendre nodes and weights on [-1, 1] (Newton on P_n, in double precision).
inline void gaussLegendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
    nodes.assign(size_t(n), 0);
    weights.assign(size_t(n), 0);
    for (int i = 0; i < n; ++i) {
        double x = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1, p1 = x;  // P_0, P_1, then the recurrence up to P_n
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (x * p1 - p0) / (x * x - 1);
            const double dx = p1 / dp;
            x -= dx;
            if (std::fabs(dx) < 1e-15) break;
        }
        nodes[size_t(i)] = x;
        weights[size_t(i)] = 2 / ((1 - x * x) * dp * dp);
    }
}

/// Mitsuba's eval_reflectance (transmit = false) or eval_transmittance (true) of a rough
/// dielectric interface of relative IOR eta seen from direction w (upper hemisphere): the
/// albedo of its reflection (transmission) lobe, ∫∫ F (1 - F) G1(w', m) over the visible-normal
/// sampler's unit square, by Gauss–Legendre quadrature with 32² nodes (eta > 1) or 128².
inline double roughInterfaceAlbedo(const MicrofacetDistribution& md, Vec3f w, Float eta,
                                   bool transmit) {
    std::vector<double> nodes, weights;
    gaussLegendre(eta > 1 ? 32 : 128, nodes, weights);
    double sum = 0;
    for (size_t i = 0; i < nodes.size(); ++i)
        for (size_t j = 0; j < nodes.size(); ++j) {
            const Vec2f u(Float(nodes[i] * 0.5 + 0.5), Float(nodes[j] * 0.5 + 0.5));
            const Vec3f m = md.sampleVisible(w, u);
            const FresnelDielectric f = fresnelDielectric(dot(w, m), eta);
            Vec3f out;
            Float value;
            if (transmit) {
                out = refractMicro(w, m, f.cosThetaT, f.etaTI);
                value = out.z * w.z >= 0 ? 0 : md.G1(out, m) * (1 - f.r);
            } else {
                out = reflect(w, m);
                value = out.z <= 0 || w.z <= 0 ? 0 : md.G1(out, m) * f.r;
            }
            sum += double(value) * weights[i] * weights[j] * 0.25;
        }
    return sum;
}

}  // namespace bsdf_detail

/// A roughplastic record with Mitsuba's precomputed terms (host only: ~10⁶ microfacet samples
/// for the internal reflectance). The specular sampling weight is mean(specular) /
/// (mean(diffuse) + mean(specular)) (0.5 when both are black).
inline Bsdf makeRoughPlastic(MicrofacetType type, Float alpha, Float etaRatio, Spectrum diffuse,
                             Spectrum specular, bool nonlinear) {
    Bsdf b;
    b.type = BsdfType::RoughPlastic;
    b.distribution = type;
    b.alphaU = b.alphaV = alpha;
    b.etaRatio = etaRatio;
    b.diffuse = diffuse;
    b.reflectance = specular;
    b.nonlinear = nonlinear;
    const Float dMean = (diffuse.r + diffuse.g + diffuse.b) / 3;
    const Float sMean = (specular.r + specular.g + specular.b) / 3;
    b.specularWeight = dMean + sMean > 0 ? sMean / (dMean + sMean) : Float(0.5);
    const MicrofacetDistribution md(type, alpha, alpha);
    double internal = 0;
    for (int i = 0; i < kRoughPlasticTableSize; ++i) {
        const Float mu = std::max(Float(1e-6), Float(i) / Float(kRoughPlasticTableSize - 1));
        const Vec3f w(std::sqrt(1 - mu * mu), 0, mu);
        b.roughTransmittance[i] =
            Float(bsdf_detail::roughInterfaceAlbedo(md, w, etaRatio, true));
        internal += bsdf_detail::roughInterfaceAlbedo(md, w, 1 / etaRatio, false) * mu;
    }
    b.fdrInt = Float(internal / kRoughPlasticTableSize * 2);  // Mitsuba: mean(R · cosθ) · 2
    return b;
}

}  // namespace caustica
