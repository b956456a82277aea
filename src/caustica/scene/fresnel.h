// fresnel.h — Fresnel reflectance of smooth dielectric and conductor interfaces, and the
// reflection/refraction of directions in a local frame whose +z is the surface normal.
// Shared CPU/GPU kernel code; formulas and conventions follow Mitsuba 3 (mitsuba/render/fresnel.h).
#pragma once

#include "caustica/util/spectrum.h"

namespace caustica {

/// Result of fresnelDielectric.
struct FresnelDielectric {
    Float r;         // unpolarised reflectance F in [0, 1] (1 under total internal reflection)
    Float cosThetaT; // cosine of the refracted direction, signed opposite to cosThetaI (0 at TIR)
    Float etaIT;     // relative IOR η_t/η_i of the interface as the ray crosses it
    Float etaTI;     // its reciprocal η_i/η_t
};

/// Exact unpolarised Fresnel reflectance of a smooth dielectric interface (pbrt-v4 eq. 9.4 and
/// the Fresnel equations 9.5/9.6, in Mitsuba 3's fresnel()). `cosThetaI` is the cosine between
/// the incident direction and the normal, `eta` the relative IOR (inside/outside) of the
/// interface. A negative cosThetaI means the direction lies inside, so the roles swap (1/eta).
CA_HD_INLINE FresnelDielectric fresnelDielectric(Float cosThetaI, Float eta) {
    const bool outside = cosThetaI >= 0;
    const Float etaIT = outside ? eta : 1 / eta;
    const Float etaTI = outside ? 1 / eta : eta;
    // Snell's law: sin²θt = (η_i/η_t)² sin²θi.
    const Float cosThetaTSqr = 1 - (1 - cosThetaI * cosThetaI) * (etaTI * etaTI);
    const Float cosI = std::fabs(cosThetaI);
    const Float cosT = safeSqrt(cosThetaTSqr);

    Float r;
    if (eta == 1) {
        r = 0;  // index-matched: no interface
    } else if (cosI == 0) {
        r = 1;  // grazing
    } else {
        const Float aS = (cosI - etaIT * cosT) / (cosI + etaIT * cosT);  // s-polarised amplitude
        const Float aP = (cosT - etaIT * cosI) / (cosT + etaIT * cosI);  // p-polarised amplitude
        r = Float(0.5) * (aS * aS + aP * aP);                            // = 1 when cosT = 0 (TIR)
    }
    return {r, outside ? -cosT : cosT, etaIT, etaTI};
}

/// Unpolarised Fresnel reflectance of a conductor with complex relative IOR η + iκ, one channel.
/// Closed form after Moeller ("Optics", 1988), as Mitsuba 3's fresnel_conductor. `cosThetaI`
/// must be >= 0. For η = 0, κ = 1 (Mitsuba's "none" material) it returns exactly 1.
CA_HD_INLINE Float fresnelConductor(Float cosThetaI, Float eta, Float k) {
    const Float cos2 = cosThetaI * cosThetaI;
    const Float sin2 = 1 - cos2;
    const Float sin4 = sin2 * sin2;
    const Float temp1 = eta * eta - k * k - sin2;
    const Float a2pb2 = safeSqrt(temp1 * temp1 + 4 * k * k * eta * eta);
    const Float a = safeSqrt(Float(0.5) * (a2pb2 + temp1));
    const Float term1 = a2pb2 + cos2;
    const Float term2 = 2 * cosThetaI * a;
    const Float rs = term1 + term2 > 0 ? (term1 - term2) / (term1 + term2) : Float(1);
    const Float term3 = a2pb2 * cos2 + sin4;
    const Float term4 = term2 * sin2;
    const Float rp = term3 + term4 > 0 ? rs * (term3 - term4) / (term3 + term4) : rs;
    return Float(0.5) * (rs + rp);
}

/// Per-channel conductor Fresnel reflectance for RGB complex IOR (eta, k).
CA_HD_INLINE Spectrum fresnelConductor(Float cosThetaI, const Spectrum& eta, const Spectrum& k) {
    return {fresnelConductor(cosThetaI, eta.r, k.r), fresnelConductor(cosThetaI, eta.g, k.g),
            fresnelConductor(cosThetaI, eta.b, k.b)};
}

/// Mirror reflection of `w` about the local normal +z.
CA_HD_INLINE Vec3f reflectLocal(Vec3f w) { return {-w.x, -w.y, w.z}; }

/// Mirror reflection of `w` about the unit vector `m` (both pointing away from the surface).
CA_HD_INLINE Vec3f reflect(Vec3f w, Vec3f m) { return m * (2 * dot(w, m)) - w; }

/// Refraction of `w` (pointing away from the surface) through the local +z interface, given the
/// signed cosThetaT and η_i/η_t from fresnelDielectric (Mitsuba 3's refract()).
CA_HD_INLINE Vec3f refractLocal(Vec3f w, Float cosThetaT, Float etaTI) {
    return {-etaTI * w.x, -etaTI * w.y, cosThetaT};
}

}  // namespace caustica
