// microfacet.h — the anisotropic GGX (Trowbridge–Reitz) microfacet distribution with Smith
// masking and visible-normal sampling, in a local frame whose +z is the macro-surface normal.
// Shared CPU/GPU kernel code; the same D, G1, G and sampling density as Mitsuba 3's
// MicrofacetDistribution (type ggx, sample_visible = true), which draws visible normals with
// Heitz's 2014 slope method where we use the simpler, exact hemisphere method of Heitz 2018.
// Local x is the frame's s axis: anisotropic roughness follows Frame(ns), not dp/du.
#pragma once

#include "caustica/util/math.h"

namespace caustica {

/// GGX distribution with roughness alphaU along local x and alphaV along local y.
struct GgxDistribution {
    Float alphaU = 0.1f, alphaV = 0.1f;

    GgxDistribution() = default;
    /// Roughness is clamped to 1e-4 as Mitsuba's MicrofacetDistribution::configure() does.
    CA_HD GgxDistribution(Float au, Float av) : alphaU(max(au, 1e-4f)), alphaV(max(av, 1e-4f)) {}

    /// Normal distribution D(m) of unit microfacet normal m (Walter et al. 2007, eq. 33, in the
    /// anisotropic form of Heitz 2014, "Understanding the Masking-Shadowing Function", sec. 5.4):
    /// D = 1 / (π αu αv (x²/αu² + y²/αv² + z²)²). Zero on the lower hemisphere.
    CA_HD Float D(Vec3f m) const {
        if (m.z <= 0) return 0;
        const Float s = sqr(m.x / alphaU) + sqr(m.y / alphaV) + sqr(m.z);
        const Float result = 1 / (kPi * alphaU * alphaV * s * s);
        return result * m.z > 1e-20f ? result : Float(0);  // as Mitsuba: avoid denormal trouble
    }

    /// Smith's monodirectional masking G1(v, m) = χ⁺(v·m) / (1 + Λ(v)) for GGX (Heitz 2014):
    /// 2 / (1 + sqrt(1 + tan²θ α²)), α² projected along v's azimuth. Zero when v sees the back of
    /// the microfacet or lies on the other side of the macro-surface than m.
    CA_HD Float G1(Vec3f v, Vec3f m) const {
        if (dot(v, m) * v.z <= 0) return 0;
        const Float xyAlpha2 = sqr(alphaU * v.x) + sqr(alphaV * v.y);
        if (xyAlpha2 == 0) return 1;  // normal incidence: no masking
        const Float tanThetaAlpha2 = xyAlpha2 / sqr(v.z);
        return 2 / (1 + std::sqrt(1 + tanThetaAlpha2));
    }

    /// Separable shadowing-masking G(wo, wi, m) = G1(wo, m) G1(wi, m) (Mitsuba's choice).
    CA_HD Float G(Vec3f wo, Vec3f wi, Vec3f m) const { return G1(wo, m) * G1(wi, m); }

    /// Samples a microfacet normal from the distribution of normals visible from `wo` (wo.z > 0)
    /// (Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4), listing 1):
    /// stretch wo to the hemisphere configuration, sample the projected area of the hemisphere,
    /// reproject and unstretch. The density is visiblePdf(wo, m).
    CA_HD Vec3f sampleVisible(Vec3f wo, Vec2f u) const {
        // Section 3.2: transform the view direction to the hemisphere configuration.
        const Vec3f vh = normalize(Vec3f(alphaU * wo.x, alphaV * wo.y, wo.z));
        // Section 4.1: orthonormal basis (with the special case of normal incidence).
        const Float lensq = vh.x * vh.x + vh.y * vh.y;
        const Vec3f t1 =
            lensq > 0 ? Vec3f(-vh.y, vh.x, 0) * (1 / std::sqrt(lensq)) : Vec3f(1, 0, 0);
        const Vec3f t2 = cross(vh, t1);
        // Section 4.2: parameterisation of the projected area.
        const Float r = std::sqrt(u.x);
        const Float phi = 2 * kPi * u.y;
        const Float p1 = r * std::cos(phi);
        Float p2 = r * std::sin(phi);
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
