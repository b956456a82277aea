// sampling.h — warps from the unit square to the domains rendering integrates over, their pdfs,
// discrete sampling from a CDF and the MIS power heuristic. Shared CPU/GPU kernel code.
//
// Every warp takes uniform numbers in [0, 1)^2 and returns a point of its domain; the matching
// pdf is with respect to the domain's natural measure (solid angle, area, barycentric area).
#pragma once

#include <cstdint>

#include "caustica/util/math.h"
#include "caustica/util/span.h"

namespace caustica {

/// Concentric map of the square to the unit disk (Shirley and Chiu 1997, "A Low Distortion Map
/// Between Disk and Square"). Uniform in area: pdf 1/π. Generic over the lane type F (lane.h):
/// both octant cases are one expression, chosen by select.
template <class F>
CA_HD_INLINE Vec2Of<F> sampleConcentricDisk(const Vec2Of<F>& u) {
    const F x = 2 * u.x - 1, y = 2 * u.y - 1;
    // The point at radius r and angle θ = (π/4)(y/x) (|x| > |y|, r = x) or π/2 - (π/4)(x/y)
    // (r = y): both angles' sine and cosine come from one in [-π/4, π/4], cos(π/2 - a) = sin a.
    const MaskOf<F> xMajor = lane::abs(x) > lane::abs(y);
    const F r = lane::select(xMajor, x, y);
    F s, c;
    sinCosQuarterPi((kPi / 4) * (lane::select(xMajor, y, x) / r), s, c);
    const F zero = lane::splat<F>(0);
    const MaskOf<F> centre = (x == zero) & (y == zero);  // 0 / 0 above: the centre is (0, 0)
    return Vec2Of<F>{lane::select(centre, zero, r * lane::select(xMajor, c, s)),
                     lane::select(centre, zero, r * lane::select(xMajor, s, c))};
}
CA_HD_INLINE Vec2f sampleConcentricDisk(Vec2f u) { return sampleConcentricDisk<float>(u); }
CA_HD_INLINE Float concentricDiskPdf() { return kInvPi; }

/// Cosine-weighted directions on the +z hemisphere (Malley's method): pdf cosθ/π. Generic over
/// the lane type F.
template <class F>
CA_HD_INLINE Vec3Of<F> sampleCosineHemisphere(const Vec2Of<F>& u) {
    const Vec2Of<F> d = sampleConcentricDisk<F>(u);
    return Vec3Of<F>{d.x, d.y, lane::safeSqrt(1 - d.x * d.x - d.y * d.y)};
}
CA_HD_INLINE Vec3f sampleCosineHemisphere(Vec2f u) { return sampleCosineHemisphere<float>(u); }
template <class F>
CA_HD_INLINE F cosineHemispherePdf(const Vec3Of<F>& w) {
    return lane::select(w.z > 0, w.z * kInvPi, lane::splat<F>(0));
}
CA_HD_INLINE Float cosineHemispherePdf(Vec3f w) { return cosineHemispherePdf<float>(w); }

/// Uniform directions on the unit sphere: pdf 1/(4π).
CA_HD_INLINE Vec3f sampleUniformSphere(Vec2f u) {
    const Float z = 1 - 2 * u.x;
    const Float r = safeSqrt(1 - z * z);
    Float sinPhi, cosPhi;  // φ = 2π u.y
    sinCosTwoPi(u.y, sinPhi, cosPhi);
    return {r * cosPhi, r * sinPhi, z};
}
CA_HD_INLINE Float uniformSpherePdf() { return kInv4Pi; }

/// Uniform directions in the cone around +z whose solid angle is 2π·oneMinusCosMax, where
/// oneMinusCosMax = 1 - cosθmax. Taking 1 - cosθmax directly avoids the cancellation of small
/// cones: with v = u·(1 - cosθmax), cosθ = 1 - v and sin²θ = v(2 - v) exactly.
CA_HD_INLINE Vec3f sampleUniformConeOmc(Vec2f u, Float oneMinusCosMax) {
    const Float v = u.x * oneMinusCosMax;
    const Float cosTheta = 1 - v;
    const Float sinTheta = safeSqrt(v * (2 - v));
    Float sinPhi, cosPhi;  // φ = 2π u.y
    sinCosTwoPi(u.y, sinPhi, cosPhi);
    return {sinTheta * cosPhi, sinTheta * sinPhi, cosTheta};
}
CA_HD_INLINE Float uniformConePdfOmc(Float oneMinusCosMax) {
    return oneMinusCosMax > 0 ? 1 / (2 * kPi * oneMinusCosMax) : Float(0);
}
/// Uniform directions in the cone around +z of half-angle θmax: pdf 1/(2π(1 - cosθmax)).
CA_HD_INLINE Vec3f sampleUniformCone(Vec2f u, Float cosThetaMax) {
    return sampleUniformConeOmc(u, 1 - cosThetaMax);
}
CA_HD_INLINE Float uniformConePdf(Float cosThetaMax) { return uniformConePdfOmc(1 - cosThetaMax); }

/// Uniform point on a triangle as barycentrics (b1, b2) of vertices 1 and 2 (b0 = 1 - b1 - b2),
/// by Heitz's low-distortion map (Heitz 2019, "A Low-Distortion Map Between Triangle and Square",
/// listing 1). Uniform in area: the pdf is 1/area of the triangle.
CA_HD_INLINE Vec2f sampleUniformTriangle(Vec2f u) {
    Float b0, b1;
    if (u.x < u.y) {
        b0 = u.x / 2;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2;
        b0 = u.x - b1;
    }
    return {b1, 1 - b0 - b1};
}

/// Index i of the interval of a normalised cumulative distribution (cdf[i] = P(X <= i), last
/// entry 1) that u falls into: the first i with u < cdf[i] (binary search). Entries of zero
/// probability are never chosen. `pdf` (optional) receives the probability of i.
CA_HD_INLINE uint32_t sampleDiscreteCdf(Span<const float> cdf, Float u, Float* pdf) {
    const uint32_t n = uint32_t(cdf.size());
    if (n == 0) {
        if (pdf) *pdf = 0;
        return 0;
    }
    uint32_t lo = 0, hi = n - 1;  // answer in [lo, hi]
    while (lo < hi) {
        const uint32_t mid = lo + (hi - lo) / 2;
        if (u < cdf[mid])
            hi = mid;
        else
            lo = mid + 1;
    }
    if (pdf) *pdf = cdf[lo] - (lo > 0 ? cdf[lo - 1] : 0.0f);
    return lo;
}

/// Probability of index i under the cumulative distribution `cdf` (as sampleDiscreteCdf uses it).
CA_HD_INLINE Float discreteCdfPmf(Span<const float> cdf, uint32_t i) {
    if (i >= cdf.size()) return 0;
    return cdf[i] - (i > 0 ? cdf[i - 1] : 0.0f);
}

/// Veach's power heuristic with β = 2 (Veach 1997, eq. 9.13): the MIS weight of a sample drawn
/// with pdf `pdfA` when the other strategy would have drawn it with pdf `pdfB`. Robust to
/// infinite pdfs (delta strategies) and overflow: returns 1 if only pdfA is infinite, 0 if only
/// pdfB is, ½ if both are, and 0 when pdfA is 0. Generic over the lane type F.
template <LaneFloat F>
CA_HD_INLINE F powerHeuristic(F pdfA, F pdfB) {
    const MaskOf<F> infA = lane::isInf(pdfA), infB = lane::isInf(pdfB);
    const F r = pdfB / pdfA;  // no overflow from squaring large pdfs
    const F zero = lane::splat<F>(0);
    const F finite = lane::select(pdfA > zero, 1 / (1 + r * r), zero);
    const F infinite = lane::select(infA, lane::select(infB, lane::splat<F>(0.5f), lane::splat<F>(1)), zero);
    return lane::select(infA | infB, infinite, finite);
}
CA_HD_INLINE Float powerHeuristic(Float pdfA, Float pdfB) { return powerHeuristic<float>(pdfA, pdfB); }

}  // namespace caustica
