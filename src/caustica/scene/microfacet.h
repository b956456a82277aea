// microfacet.h — Mitsuba 3's MicrofacetDistribution: anisotropic Beckmann and GGX
// (Trowbridge–Reitz) normal distributions with Smith masking and visible-normal sampling, in a
// local frame whose +z is the macro-surface normal. Shared CPU/GPU kernel code; the same D, G1, G
// and sampling densities as Mitsuba 3 (sample_visible = true):
// - Beckmann: D, the rational approximation of G1 that Mitsuba uses, and Mitsuba's sampler of
//   visible slopes (Jakob's inversion of the visible-slope CDF with three Newton steps).
// - GGX: D and exact G1; visible normals drawn with the exact hemisphere method of Heitz 2018
//   where Mitsuba uses Heitz's 2014 slope method (same density).
// Local x is the frame's s axis: anisotropic roughness follows Frame(ns), not dp/du.
#pragma once

#include "caustica/util/math.h"

namespace caustica {

/// Inverse error function, Giles' single-precision approximation ("Approximating the erfinv
/// function", GPU Computing Gems 2011) as in Dr.Jit's dr::erfinv. |x| < 1.
CA_HD_INLINE Float erfinvApprox(Float x) {
    const Float w = -std::log((1 - x) * (1 + x));
    Float p;
    if (w < 5) {
        const Float t = w - Float(2.5);
        p = 2.81022636e-08f;
        p = 3.43273939e-07f + p * t;
        p = -3.5233877e-06f + p * t;
        p = -4.39150654e-06f + p * t;
        p = 0.00021858087f + p * t;
        p = -0.00125372503f + p * t;
        p = -0.00417768164f + p * t;
        p = 0.246640727f + p * t;
        p = 1.50140941f + p * t;
    } else {
        const Float t = std::sqrt(w) - 3;
        p = -0.000200214257f;
        p = 0.000100950558f + p * t;
        p = 0.00134934322f + p * t;
        p = -0.00367342844f + p * t;
        p = 0.00573950773f + p * t;
        p = -0.0076224613f + p * t;
        p = 0.00943887047f + p * t;
        p = 1.00167406f + p * t;
        p = 2.83297682f + p * t;
    }
    return p * x;
}

/// Mitsuba's `distribution` parameter (its default is Beckmann).
enum class MicrofacetType : uint32_t { Beckmann, GGX };

/// Microfacet distribution with roughness alphaU along local x and alphaV along local y.
struct MicrofacetDistribution {
    MicrofacetType type = MicrofacetType::GGX;
    Float alphaU = 0.1f, alphaV = 0.1f;

    MicrofacetDistribution() = default;
    /// Roughness is clamped to 1e-4 as Mitsuba's MicrofacetDistribution::configure() does.
    CA_HD MicrofacetDistribution(MicrofacetType t, Float au, Float av)
        : type(t), alphaU(max(au, 1e-4f)), alphaV(max(av, 1e-4f)) {}

    /// Normal distribution D(m) of unit microfacet normal m, in the anisotropic forms of Heitz
    /// 2014 ("Understanding the Masking-Shadowing Function", sec. 5.4). Zero on the lower
    /// hemisphere.
    /// - Beckmann (Walter et al. 2007, eq. 25): exp(-(x²/αu² + y²/αv²)/z²) / (π αu αv z⁴);
    /// - GGX (Walter et al. 2007, eq. 33): 1 / (π αu αv (x²/αu² + y²/αv² + z²)²).
    CA_HD Float D(Vec3f m) const {
        if (m.z <= 0) return 0;
        Float result;
        if (type == MicrofacetType::Beckmann) {
            const Float cos2 = sqr(m.z);
            result = std::exp(-(sqr(m.x / alphaU) + sqr(m.y / alphaV)) / cos2) /
                     (kPi * alphaU * alphaV * sqr(cos2));
        } else {
            const Float s = sqr(m.x / alphaU) + sqr(m.y / alphaV) + sqr(m.z);
            result = 1 / (kPi * alphaU * alphaV * s * s);
        }
        return result * m.z > 1e-20f ? result : Float(0);  // as Mitsuba: avoid denormal trouble
    }

    /// Smith's monodirectional masking G1(v, m) = χ⁺(v·m) / (1 + Λ(v)) (Heitz 2014), α
    /// projected along v's azimuth, a = 1 / (α tanθ):
    /// - Beckmann: Walter et al. 2007's rational approximation (eq. 27, < 0.35% relative error),
    ///   (3.535 a + 2.181 a²) / (1 + 2.276 a + 2.577 a²), 1 from a >= 1.6, as Mitsuba;
    /// - GGX: 2 / (1 + sqrt(1 + tan²θ α²)).
    /// Zero when v sees the back of the microfacet or lies on the other side of the
    /// macro-surface than m.
    CA_HD Float G1(Vec3f v, Vec3f m) const {
        if (dot(v, m) * v.z <= 0) return 0;
        const Float xyAlpha2 = sqr(alphaU * v.x) + sqr(alphaV * v.y);
        if (xyAlpha2 == 0) return 1;  // normal incidence: no masking
        const Float tanThetaAlpha2 = xyAlpha2 / sqr(v.z);
        if (type == MicrofacetType::Beckmann) {
            const Float a = 1 / std::sqrt(tanThetaAlpha2), a2 = a * a;
            if (a >= Float(1.6)) return 1;
            return (Float(3.535) * a + Float(2.181) * a2) /
                   (1 + Float(2.276) * a + Float(2.577) * a2);
        }
        return 2 / (1 + std::sqrt(1 + tanThetaAlpha2));
    }

    /// Separable shadowing-masking G(wo, wi, m) = G1(wo, m) G1(wi, m) (Mitsuba's choice).
    CA_HD Float G(Vec3f wo, Vec3f wi, Vec3f m) const { return G1(wo, m) * G1(wi, m); }

    /// Samples a microfacet normal from the distribution of normals visible from `wo` (wo.z > 0);
    /// the density is visiblePdf(wo, m).
    CA_HD Vec3f sampleVisible(Vec3f wo, Vec2f u) const {
        return type == MicrofacetType::Beckmann ? sampleVisibleBeckmann(wo, u)
                                                : sampleVisibleGgx(wo, u);
    }

    /// Beckmann visible normals as Mitsuba 3 (MicrofacetDistribution::sample with
    /// sample_visible_11; Heitz and d'Eon 2014, "Importance Sampling Microfacet-Based BSDFs using
    /// the Distribution of Visible Normals"): stretch wo to unit roughness, sample the visible
    /// slopes of the standard Beckmann distribution (the slope along the azimuth of wo by a
    /// Newton-refined inversion of its CDF in erf space, the other one Gaussian), rotate and
    /// unstretch the slope, and turn it into a normal.
    CA_HD Vec3f sampleVisibleBeckmann(Vec3f wo, Vec2f u) const {
        // Step 1: stretch wo.
        const Vec3f wp = normalize(Vec3f(alphaU * wo.x, alphaV * wo.y, wo.z));
        const Float sinTheta2 = max(Float(0), 1 - sqr(wp.z));
        const Float sinTheta = std::sqrt(sinTheta2);
        Float cosPhi = 1, sinPhi = 0;
        if (sinTheta2 > 0) {
            const Float inv = 1 / sinTheta;
            cosPhi = clamp(wp.x * inv, Float(-1), Float(1));
            sinPhi = clamp(wp.y * inv, Float(-1), Float(1));
        }
        // Step 2: visible slopes of the unit-roughness distribution for this elevation. At normal
        // incidence tanθ = 0 and cotθ = ∞ (erf(∞) = 1, exp(-∞) = 0): the first Newton step then
        // lands on the exact answer x = 2u - 1, as in Mitsuba.
        const Float sqrtPiInv = Float(0.5641895835477563);  // 1/√π
        Float ux = min(max(u.x, Float(1e-6)), 1 - Float(1e-6));
        const Float uy = min(max(u.y, Float(1e-6)), 1 - Float(1e-6));
        const Float tanTheta = sinTheta / wp.z, cotTheta = 1 / tanTheta;
        // Search interval, everything parameterised in the erf() domain.
        const Float maxval = std::erf(cotTheta);
        // Initial guess (inverse of an approximation computed in Mathematica).
        Float x = maxval - (maxval + 1) * std::erf(std::sqrt(-std::log(ux)));
        // Normalisation of the CDF.
        ux *= 1 + maxval + sqrtPiInv * tanTheta * std::exp(-sqr(cotTheta));
        for (int i = 0; i < 3; ++i) {  // three Newton iterations
            const Float slope = erfinvApprox(x);
            const Float value = 1 + x + sqrtPiInv * tanTheta * std::exp(-sqr(slope)) - ux;
            const Float derivative = 1 - slope * tanTheta;
            x -= value / derivative;
        }
        const Float slopeX = erfinvApprox(x), slopeY = erfinvApprox(2 * uy - 1);
        // Step 3: rotate and unstretch.
        const Float sx = (cosPhi * slopeX - sinPhi * slopeY) * alphaU;
        const Float sy = (sinPhi * slopeX + cosPhi * slopeY) * alphaV;
        // Step 4: the normal.
        return normalize(Vec3f(-sx, -sy, 1));
    }

    /// GGX visible normals (Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), listing 1):
    /// stretch wo to the hemisphere configuration, sample the projected area of the hemisphere,
    /// reproject and unstretch.
    CA_HD Vec3f sampleVisibleGgx(Vec3f wo, Vec2f u) const {
        // Section 3.2: transform the view direction to the hemisphere configuration.
        const Vec3f vh = normalize(Vec3f(alphaU * wo.x, alphaV * wo.y, wo.z));
        // Section 4.1: orthonormal basis (with the special case of normal incidence).
        const Float lensq = vh.x * vh.x + vh.y * vh.y;
        const Vec3f t1 =
            lensq > 0 ? Vec3f(-vh.y, vh.x, 0) * (1 / std::sqrt(lensq)) : Vec3f(1, 0, 0);
        const Vec3f t2 = cross(vh, t1);
        // Section 4.2: parameterisation of the projected area.
        const Float r = std::sqrt(u.x);
        Float sinPhi, cosPhi;  // φ = 2π u.y
        sinCosTwoPi(u.y, sinPhi, cosPhi);
        const Float p1 = r * cosPhi;
        Float p2 = r * sinPhi;
        const Float s = Float(0.5) * (1 + vh.z);
        p2 = (1 - s) * std::sqrt(max(Float(0), 1 - p1 * p1)) + s * p2;
        // Section 4.3: reprojection onto the hemisphere.
        const Vec3f nh = t1 * p1 + t2 * p2 + vh * safeSqrt(1 - p1 * p1 - p2 * p2);
        // Section 3.4: back to the ellipsoid configuration.
        return normalize(Vec3f(alphaU * nh.x, alphaV * nh.y, max(Float(0), nh.z)));
    }

    /// Density of sampleVisible: D_wo(m) = G1(wo, m) max(0, wo·m) D(m) / cosθo (Heitz 2018, eq. 2).
    CA_HD Float visiblePdf(Vec3f wo, Vec3f m) const {
        if (wo.z <= 0) return 0;
        const Float c = dot(wo, m);
        if (c <= 0) return 0;
        return G1(wo, m) * c * D(m) / wo.z;
    }
};

}  // namespace caustica
